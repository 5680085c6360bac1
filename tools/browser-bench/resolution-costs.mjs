// The render scale in the browser (headless Chromium, WebGL 1 on SwiftShader): the demo page's default frame of the
// built-in scene at full size against scale 0.5 with the edge upscale (FXAA's pass doing it) and with the bilinear
// one, at each size asked, taking turns round by round. Per configuration: the GPU milliseconds of the frame's passes
// (EXT_disjoint_timer_query; the sum over the passes of a frame) and the interval between frames drawn back to back,
// medians; and each scaled frame's error against the full-size one (snapshots; MAE over the colour channels, 0..255).
// Prints the issue's targets beside them: scale 0.5 + edge <= 0.35 x the full frame, its MAE <= 0.8 x bilinear's.
//
// Usage: node tools/browser-bench/resolution-costs.mjs [--sizes 1280x720] [--rounds N] [--frames N] [--state S]
//          [--csv FILE]   (--state: a state text added to every configuration, e.g. dither=off)
//   (defaults: 1280x720, 3 rounds, 3 frames timed per configuration and round,
//   bench-results/browser-resolution.csv)
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startServer } from '../serve-web.mjs';
import { chromiumLaunchOptions, median, parseOptions, parseSizes } from '../headless-chromium.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
const options = { sizes: '1280x720', rounds: 3, frames: 3, state: '',
                  csv: path.join(root, 'bench-results', 'browser-resolution.csv') };
parseOptions(process.argv.slice(2), {
  '--sizes': (v) => { options.sizes = v; },
  '--rounds': (v) => { options.rounds = Number(v); },
  '--frames': (v) => { options.frames = Number(v); },
  '--state': (v) => { options.state = v; },
  '--csv': (v) => { options.csv = path.resolve(v); },
}, path.basename(import.meta.url));
const sizes = parseSizes(options.sizes);
if (!sizes.every(([w, h]) => w > 0 && h > 0) || !(options.rounds > 0 && options.frames > 0)) {
  throw new Error('--sizes WxH,..., --rounds N and --frames N must be positive');
}

const configurations = [
  { name: 'full size', state: 'resolution.scale=1' },
  { name: 'scale 0.5, edge', state: 'resolution.scale=0.5&resolution.upscale=edge' },
  { name: 'scale 0.5, bilinear', state: 'resolution.scale=0.5&resolution.upscale=bilinear' },
];

const server = await startServer(process.env.OBSCURA_WEB_SITE ?? path.join(root, 'build-web', 'site'));
const browser = await chromium.launch(chromiumLaunchOptions);
const rows = [];
const targets = [];
try {
  for (const [width, height] of sizes) {
    const page = await (await browser.newContext({ viewport: { width, height }, deviceScaleFactor: 1 })).newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    // Dynamic resolution off: each configuration at its own scale.
    await page.goto(`http://127.0.0.1:${server.address().port}/?resolution.dynamic=off&resolution.quick-start=off`);
    await page.waitForFunction(() => document.body.dataset.shown !== undefined, null, { timeout: 180000 });
    await page.addStyleTag({ content: '#panel { display: none !important; }' });
    const renderer = await page.evaluate(() => window.obscura.context.renderer);
    console.log(`${width}x${height}, ${renderer}, the built-in scene at its defaults, ${options.rounds} rounds`);
    const measure = (state) => page.evaluate(async ({ state, frames, extra }) => {
      const o = window.obscura;
      o.setState(`${state}&resolution.dynamic=off${extra ? `&${extra}` : ''}`);
      o.setContinuous(true);
      const next = async (after) => {
        while (o.stats().frames <= after) await new Promise((r) => setTimeout(r, 20));
        return o.stats();
      };
      let s = await next(o.stats().frames + 1);  // the change drawn, and one more
      const gpu = [], interval = [], passes = [];
      let seenTimes = JSON.stringify(s.passMs);
      let last = { frames: s.frames, time: performance.now() };
      while (interval.length < frames) {
        s = await next(last.frames);
        const now = performance.now();
        interval.push((now - last.time) / (s.frames - last.frames));
        last = { frames: s.frames, time: now };
        const times = JSON.stringify(s.passMs);
        if (s.passMs && times !== seenTimes) {
          gpu.push(Object.values(s.passMs).filter((v) => v !== null).reduce((a, b) => a + b, 0));
          passes.push(s.passMs);
          seenTimes = times;
        }
      }
      o.setContinuous(false);
      const shot = o.snapshot();
      return { gpu, interval, passes, pixels: Array.from(shot.pixels), scale: o.stats().render.scale };
    }, { state, frames: options.frames, extra: options.state });
    const results = configurations.map(() => ({ gpu: [], interval: [], passes: [], pixels: null }));
    for (let round = 0; round < options.rounds; ++round) {
      for (let c = 0; c < configurations.length; ++c) {
        const r = await measure(configurations[c].state);
        results[c].gpu.push(...r.gpu);
        results[c].interval.push(...r.interval);
        results[c].passes.push(...r.passes);
        results[c].pixels = r.pixels;
      }
    }
    const mae = (a, b) => {
      let sum = 0;
      for (let i = 0; i < a.length; ++i) if (i % 4 !== 3) sum += Math.abs(a[i] - b[i]);
      return sum / (a.length * 0.75);
    };
    const full = results[0];
    const fullGpu = median(full.gpu), fullInterval = median(full.interval);
    const bilinearMae = mae(full.pixels, results[2].pixels);
    for (let c = 0; c < configurations.length; ++c) {
      const r = results[c];
      const gpu = r.gpu.length ? median(r.gpu) : NaN, interval = median(r.interval);
      const error = c === 0 ? 0 : mae(full.pixels, r.pixels);
      rows.push({ width, height, name: configurations[c].name, gpu, interval, gpuRatio: gpu / fullGpu,
                  intervalRatio: interval / fullInterval, mae: error });
      const versus = c ? ` (${(error / bilinearMae).toFixed(3)} x bilinear's)` : '';
      console.log(`  ${configurations[c].name.padEnd(20)} GPU ${gpu.toFixed(1).padStart(8)} ms (${(gpu / fullGpu)
        .toFixed(3)} x full)   frame ${interval.toFixed(0).padStart(6)} ms (${(interval / fullInterval).toFixed(3)}` +
                  ` x full)   MAE ${error.toFixed(3)}${versus}`);
      // Where the time goes: each pass's median GPU ms (the passes that ran).
      const names = [...new Set(r.passes.flatMap((p) => Object.keys(p).filter((k) => p[k] !== null)))];
      console.log(`    passes: ${names.map((n) => `${n} ${median(r.passes.map((p) => p[n] ?? 0)).toFixed(0)}`)
        .join(', ')}`);
    }
    targets.push(`${width}x${height}: scale 0.5 + edge ${rows.at(-2).gpuRatio.toFixed(3)} x the full frame's GPU ` +
                 `time, ${rows.at(-2).intervalRatio.toFixed(3)} x its frame interval (target <= 0.35); its MAE ` +
                 `${(rows.at(-2).mae / bilinearMae).toFixed(3)} x bilinear's (target <= 0.8)`);
    if (errors.length) throw new Error(`page errors: ${errors.join('; ')}`);
    await page.context().close();
  }
  console.log('Targets:');
  for (const line of targets) console.log(`  ${line}`);
  fs.mkdirSync(path.dirname(options.csv), { recursive: true });
  fs.writeFileSync(options.csv, 'width,height,configuration,gpu_ms,frame_ms,gpu_over_full,frame_over_full,mae\n' +
    rows.map((r) => [r.width, r.height, `"${r.name}"`, r.gpu.toFixed(2), r.interval.toFixed(1), r.gpuRatio.toFixed(4),
                     r.intervalRatio.toFixed(4), r.mae.toFixed(4)].join(',')).join('\n') + '\n');
  console.log(`wrote ${path.relative(root, options.csv)}`);
} finally {
  await browser.close();
  server.stop();
}
