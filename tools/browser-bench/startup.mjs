// Where the demo page's start-up goes, in headless Chromium on SwiftShader: the built-in scene at 1280x720 CSS
// pixels (devicePixelRatio 1), each round a fresh browser context (an empty cache: a first visit), timed from the
// navigation's start (performance.now()): createObscura (the wasm fetched, compiled and instantiated; then the
// core's start: the WebGL context, the programs compiled, the sky made, the scene uploaded: obscura.startup()'s
// parts), the first frame (from createObscura's end to the animation frame after the first frame was drawn), the
// page shown (the first frame on screen), and then steady frames: the mean interval between frames drawn back to
// back (continuous mode) at the first frame's render scale (the page's dynamic resolution starts at its smallest
// scale: the first frame is a cheap one), dynamic resolution off so that every frame is at that scale, and again at
// scale 1 for reference. The page's quick start (resolution.quick-start, on by default there) makes the first frame a
// cheap one and the full frame follow after a few frames that warm its passes: each round loads the page twice, with
// quick start and without it (`?resolution.quick-start=off`), in alternating order, and prints for each the first
// frame, the frames until the full one and when it was on screen (fullFrameMs, from createObscura's end), against the
// same steady frame (the full frame, drawn back to back). Prints each round, the medians and the issue's targets
// (the first frame against a steady frame at its own scale); writes a CSV.
//
// Usage: node tools/browser-bench/startup.mjs [--rounds N] [--size WxH] [--frames N] [--settle MS] [--csv FILE]
//   (defaults: 3 rounds, 1280x720, 4 steady frames, 2000 ms between loads, bench-results/browser-startup.csv)
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startServer } from '../serve-web.mjs';
import { chromiumLaunchOptions, median, parseOptions, parseSize } from '../headless-chromium.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
const options = { rounds: 3, size: '1280x720', frames: 4, settle: 2000,
                  csv: path.join(root, 'bench-results', 'browser-startup.csv') };
parseOptions(process.argv.slice(2), {
  '--rounds': (v) => { options.rounds = Number(v); },
  '--size': (v) => { options.size = v; },
  '--frames': (v) => { options.frames = Number(v); },
  '--settle': (v) => { options.settle = Number(v); },
  '--csv': (v) => { options.csv = path.resolve(v); },
}, path.basename(import.meta.url));
const [width, height] = parseSize(options.size);
if (!(width > 0 && height > 0 && options.rounds > 0 && options.frames > 0 && options.settle >= 0)) {
  throw new Error('--size WxH, --rounds N and --frames N must be positive, --settle MS at least 0');
}

const server = await startServer(process.env.OBSCURA_WEB_SITE ?? path.join(root, 'build-web', 'site'));
const browser = await chromium.launch(chromiumLaunchOptions);
const rounds = [];
try {
  for (let load = 0; load < 2 * options.rounds; ++load) {
    const round = load >> 1;
    // Quick start on (the page's default) and off, in alternating order from round to round.
    const quick = (load + round) % 2 === 0;
    const context = await browser.newContext({ viewport: { width, height }, deviceScaleFactor: 1 });
    const page = await context.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    await page.goto(`http://127.0.0.1:${server.address().port}/${quick ? '' : '?resolution.quick-start=off'}`);
    await page.waitForFunction(() => document.body.dataset.shown !== undefined, null, { timeout: 180000 });
    const result = await page.evaluate(async (frames) => {
      const o = window.obscura;
      // The full frame on screen (with quick start, after the cheap frames), then the steady frames.
      while (o.startup().fullFrameMs === null) await new Promise((r) => setTimeout(r, 20));
      const startup = o.startup();
      const shownMs = Number(document.body.dataset.shown);
      const firstScale = Number(document.body.dataset.shownScale);
      const waitFrames = async (n) => {
        const goal = o.stats().frames + n;
        while (o.stats().frames < goal) await new Promise((r) => setTimeout(r, 20));
      };
      // Frames drawn back to back at one scale: the mean interval.
      const steady = async (scale) => {
        o.set('resolution.dynamic', 'off');
        o.set('resolution.scale', scale);
        o.setContinuous(true);
        await waitFrames(2);  // the change drawn, then one more
        const from = { frames: o.stats().frames, time: performance.now() };
        await waitFrames(frames);
        const to = { frames: o.stats().frames, time: performance.now() };
        o.setContinuous(false);
        return (to.time - from.time) / (to.frames - from.frames);
      };
      const steadyMs = await steady(firstScale);
      const fullMs = firstScale === 1 ? steadyMs : await steady(1);
      return { startup, shownMs, firstScale, steadyMs, fullMs, renderer: o.context.renderer,
               size: [o.stats().width, o.stats().height] };
    }, options.frames);
    if (errors.length) throw new Error(`page errors: ${errors.join('; ')}`);
    const s = result.startup;
    const q = s.quickStart;
    const row = { round, quick, createMs: s.createMs, wasmMs: s.wasmMs, coreMs: s.coreMs, firstFrameMs: s.firstFrameMs,
                  cheapFrames: q.cheapFrames, fullFrameMs: s.fullFrameMs, warmed: q.warmed.length,
                  shownMs: result.shownMs, firstScale: result.firstScale, steadyMs: result.steadyMs,
                  fullMs: result.fullMs, parts: s.coreParts, firstFrameParts: s.firstFrameParts };
    rounds.push(row);
    const parts = Object.entries(s.coreParts).filter(([, v]) => v >= 1).sort((a, b) => b[1] - a[1])
      .map(([name, v]) => `${name} ${v.toFixed(0)}`).join(', ');
    const firstParts = Object.entries(s.firstFrameParts).filter(([, v]) => v >= 1)
      .map(([name, v]) => `${name} ${v.toFixed(0)}`).join(', ');
    if (load === 0) console.log(`${result.size[0]}x${result.size[1]}, ${result.renderer}, the built-in scene`);
    const full = q.cheapFrames > 0 ? `; the full frame after ${q.cheapFrames} cheap frames (${q.warmed.length} ` +
                                     `passes warmed) at ${s.fullFrameMs.toFixed(0)} ms` : '';
    console.log(`round ${round + 1}, quick start ${quick ? 'on ' : 'off'}: createObscura ${s.createMs.toFixed(0)} ms ` +
                `(wasm ${s.wasmMs.toFixed(0)}, core ${s.coreMs.toFixed(0)}: ${parts}), first frame ` +
                `${s.firstFrameMs.toFixed(0)} ms${q.cheapFrames > 0 ? ' (cheap)' : ''} at scale ` +
                `${result.firstScale}${firstParts ? ` (${firstParts})` : ''}${full}, shown at ` +
                `${result.shownMs.toFixed(0)} ms; steady frame ${result.steadyMs.toFixed(0)} ms at that scale, ` +
                `${result.fullMs.toFixed(0)} ms at 1`);
    await context.close();
    // The closed page's WebGL context is torn down in the GPU process after close() returns, and a context created
    // meanwhile waits for it: loads that followed at once took 770 to 900 ms for the WebGL context alone against 17
    // to 51 ms after a pause (2026-11-27, docs/benchmarks.md). A first visit finds the browser idle, so the next
    // load waits for the teardown.
    await new Promise((resolve) => setTimeout(resolve, options.settle));
  }
  for (const quick of [true, false]) {
    const these = rounds.filter((r) => r.quick === quick);
    const m = (key) => median(these.map((r) => r[key]));
    const create = m('createMs'), shown = m('shownMs');
    const ratio = median(these.map((r) => r.firstFrameMs / r.steadyMs));
    const fullRatio = median(these.map((r) => r.fullFrameMs / r.steadyMs));
    console.log(`quick start ${quick ? 'on' : 'off'}, medians of ${these.length}: createObscura ` +
                `${create.toFixed(0)} ms (target <= 500), first frame ${m('firstFrameMs').toFixed(0)} ms = ` +
                `${ratio.toFixed(2)} x a steady frame at its scale of ${m('steadyMs').toFixed(0)} ms (target <= ` +
                `1.3; a frame at scale 1: ${m('fullMs').toFixed(0)} ms), the full frame on screen after ` +
                `${m('cheapFrames')} cheap frames at ${m('fullFrameMs').toFixed(0)} ms = ${fullRatio.toFixed(2)} x ` +
                `the steady frame, shown ${(shown / 1000).toFixed(2)} s after navigation (target <= 2.5)`);
  }
  fs.mkdirSync(path.dirname(options.csv), { recursive: true });
  const names = [...new Set(rounds.flatMap((r) => Object.keys(r.parts)))].sort();
  fs.writeFileSync(options.csv, `round,quick_start,create_ms,wasm_ms,core_ms,first_frame_ms,cheap_frames,` +
    `full_frame_ms,first_scale,shown_ms,steady_ms,` +
    `full_scale_ms,${names.map((n) => `core_${n.replace(/ /g, '_')}_ms`).join(',')}\n` +
    rounds.map((r) => [r.round, r.quick ? 'on' : 'off', r.createMs, r.wasmMs, r.coreMs, r.firstFrameMs,
                       r.cheapFrames, r.fullFrameMs, r.firstScale, r.shownMs, r.steadyMs, r.fullMs,
                       ...names.map((n) => r.parts[n] ?? 0)].map((v) => (typeof v === 'number' ? v.toFixed(1) : v))
      .join(',')).join('\n') + '\n');
  console.log(`wrote ${path.relative(root, options.csv)}`);
} finally {
  await browser.close();
  server.stop();
}
