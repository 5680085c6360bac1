// The renderer's host time per frame in the browser: stats().lastHostMs (the page's "host" line: the wall time of
// the renderer's render call on the page's thread, WebGL calls included, the GPU's own work not; builds before it had
// only lastCpuMs, which also holds the page's canvas work) over frames of the demo page's built-in scene, each drawn
// alone (a step of the animation, obscura.draw(), gl.finish()), at each size asked: the defaults (with and without
// static batches) and every effect on. The page is served cross-origin isolated, so its clock has microseconds.
// Prints the median and the tenth percentile, writes a CSV; docs/benchmarks.md ("Host time per frame") shows the
// figures.
//
// Usage: node tools/browser-bench/host-time.mjs [--sizes 1280x720,640x360] [--samples N] [--settle MS] [--csv FILE]
//   (defaults: both sizes, 30 frames per case, 2500 ms for each case's shaders to compile, bench-results/
//   browser-host.csv)
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startServer } from '../serve-web.mjs';
import {
  applyBenchmarkState, chromiumLaunchOptions, median, openDemoPage,
  parseOptions, parseSizes,
} from '../headless-chromium.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
const options = { sizes: '1280x720,640x360', samples: 30, settle: 2500,
                  csv: path.join(root, 'bench-results', 'browser-host.csv') };
parseOptions(process.argv.slice(2), {
  '--sizes': (v) => { options.sizes = v; },
  '--samples': (v) => { options.samples = Number(v); },
  '--settle': (v) => { options.settle = Number(v); },
  '--csv': (v) => { options.csv = path.resolve(v); },
}, path.basename(import.meta.url));
const sizes = parseSizes(options.sizes);
if (!sizes.every(([w, h]) => w > 0 && h > 0) || !(options.samples > 0 && options.settle >= 0))
  throw new Error('--sizes WxH,... and --samples N must be positive, --settle MS not negative');

const rows = [];
const server = await startServer(process.env.OBSCURA_WEB_SITE ?? path.join(root, 'build-web', 'site'), 0, {},
                                 { isolated: true });
const browser = await chromium.launch(chromiumLaunchOptions);
try {
  for (const [width, height] of sizes) {
    const demo = `http://127.0.0.1:${server.address().port}/`;
    const { page, errors } = await openDemoPage(browser, demo, width, height);
    const effects = await page.evaluate(() => window.obscura.effects.filter((e) => e.switch).map((e) => e.name));
    // The defaults also with every instance drawn alone (no static batches: gpu/GpuScene.h), before and after.
    const cases = [{ label: 'defaults', state: '' },
                   { label: 'defaults, unbatched', state: '', batches: false },
                   { label: 'defaults (again)', state: '' },
                   { label: 'every effect on', state: effects.map((e) => `${e}=on`).join('&') }];
    console.log(`${width}x${height}, ${await page.evaluate(() => window.obscura.context.renderer)}`);
    for (const c of cases) {
      await page.evaluate((batches) => window.obscura.setStaticBatches(batches), c.batches ?? true);
      await page.evaluate(applyBenchmarkState, c.state);
      const result = await page.evaluate(async ({ samples, settle }) => {
        const o = window.obscura;
        // The shaders compile and the first frames settle in the page's own loop.
        o.setContinuous(true);
        await new Promise((r) => setTimeout(r, settle));
        o.setContinuous(false);
        o.pause();
        await new Promise((r) => setTimeout(r, 200));
        // Then each frame alone: a step of the animation, the frame drawn, and gl.finish before the next, so that
        // the render call does not share the cores with the rasteriser's work on an earlier frame (SwiftShader
        // rasterises on the CPU: on two cores that work doubles or triples a render call's wall time).
        const gl = document.querySelector('canvas').getContext('webgl');
        gl.finish();
        const host = [];
        for (let i = 0; i < samples; ++i) {
          o.stepFrames(1);
          o.draw();
          const stats = o.stats();
          host.push(stats.lastHostMs ?? stats.lastCpuMs);
          gl.finish();
          await new Promise((r) => setTimeout(r, 0));
        }
        return { host, passes: o.stats().passesRun };
      }, { samples: options.samples, settle: options.settle });
      const sorted = [...result.host].sort((a, b) => a - b);
      const row = { label: c.label, width, height, hostMs: median(result.host), frames: result.host.length,
                    passes: result.passes.length, low: sorted[0], high: sorted[sorted.length - 1],
                    tenth: sorted[Math.floor(0.1 * (sorted.length - 1))] };
      rows.push(row);
      console.log(`${c.label.padEnd(20)} host ${row.hostMs.toFixed(2).padStart(7)} ms  (median of ${row.frames} ` +
                  `frames, ${row.low.toFixed(2)} .. ${row.high.toFixed(2)}, ` +
                  `tenth percentile ${row.tenth.toFixed(2)}; ` +
                  `${row.passes} passes: ` +
                  `${result.passes.join(', ')})`);
    }
    if (errors.length) throw new Error(`page errors: ${errors.join('; ')}`);
    await page.context().close();
  }
  fs.mkdirSync(path.dirname(options.csv), { recursive: true });
  fs.writeFileSync(options.csv, 'configuration,width,height,host_ms,tenth_percentile_ms,frames,passes\n' +
    rows.map((r) => [r.label, r.width, r.height, r.hostMs.toFixed(3), r.tenth.toFixed(3), r.frames, r.passes].join(','))
      .join('\n') +
    '\n');
  console.log(`wrote ${path.relative(root, options.csv)}`);
} finally {
  await browser.close();
  server.stop();
}
