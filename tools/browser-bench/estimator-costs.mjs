// What each AO estimator costs in the browser, per quality preset: the GPU milliseconds of the AO passes (every pass
// between the G-buffer and the lighting: depth hierarchy, estimator, blur, upsample) of the demo page's frame on
// 2CylinderEngine.glb at its 5 % radius, from EXT_disjoint_timer_query (SwiftShader offers it), and the page's frame
// time while it redraws continuously. Writes a CSV that `obscura-tune --report --browser-ms FILE` folds into the
// estimator x preset table of docs/accuracy.md.
//
// Usage: node tools/browser-bench/estimator-costs.mjs [--size WxH] [--samples N] [--settle MS] [--csv FILE]
//   (defaults 1280x720, 9 timer readings per case, 2500 ms for each case's shaders to compile and its first timer
//   results to come back before the readings, bench-results/browser-estimators.csv)
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startServer } from '../serve-web.mjs';
import { chromiumLaunchOptions, median, openDemoPage, parseOptions, parseSize } from '../headless-chromium.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
const model = '/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb';
const estimators = ['sao', 'gtao', 'hbao', 'vo', 'crytek'];
const presets = ['low', 'medium', 'high', 'ultra'];

const options = { size: '1280x720', samples: 9, settle: 2500,
                  csv: path.join(root, 'bench-results', 'browser-estimators.csv') };
parseOptions(process.argv.slice(2), {
  '--size': (v) => { options.size = v; },
  '--samples': (v) => { options.samples = Number(v); },
  '--settle': (v) => { options.settle = Number(v); },
  '--csv': (v) => { options.csv = path.resolve(v); },
}, path.basename(import.meta.url));
const [width, height] = parseSize(options.size);
if (!(width > 0 && height > 0 && options.samples > 0 && options.settle >= 0))
  throw new Error('--size WxH and --samples N must be positive, --settle MS not negative');

// The site tools/build-web.sh builds, or the one the tests name.
const server = await startServer(process.env.OBSCURA_WEB_SITE ?? path.join(root, 'build-web', 'site'));
const browser = await chromium.launch(chromiumLaunchOptions);
try {
  const { page, errors } = await openDemoPage(browser, `http://127.0.0.1:${server.address().port}/`, width, height);
  const bytes = [...fs.readFileSync(model)];
  const info = await page.evaluate(async (data) => {
    const o = window.obscura;
    const scene = await o.loadScene(new Uint8Array(data), '2CylinderEngine.glb');
    return { timerQuery: o.context.timerQuery, renderer: o.context.renderer, passes: o.passes,
             radius: scene.defaultRadius };
  }, bytes);
  if (!info.timerQuery) throw new Error('this browser offers no EXT_disjoint_timer_query: no per-pass times');
  // The passes of the AO (those of the effect table between the G-buffer and the lighting, less the base colour,
  // which the G-buffer pass writes where WEBGL_draw_buffers exists); one that did not run (the upsample at full
  // resolution) reads null and counts nothing.
  const aoPasses = info.passes.slice(info.passes.indexOf('gbuffer') + 1, info.passes.indexOf('lighting'))
    .filter((p) => p !== 'base-color');
  if (!aoPasses.includes('sao')) throw new Error(`no 'sao' pass in ${info.passes.join(', ')}`);
  console.log(`${options.size}, ${info.renderer}, 2CylinderEngine.glb at r = ${info.radius}; AO passes: ` +
              aoPasses.join(', '));

  const rows = [];
  for (const estimator of estimators) {
    for (const preset of presets) {
      const result = await page.evaluate(async ({ estimator, preset, aoPasses, samples, settle }) => {
        const o = window.obscura;
        o.setState(`ao=on&ao.estimator=${estimator}&ao.preset=${preset}`);
        o.setContinuous(true);
        // Shader compilation and the first timer results come during the first frames: wait them out.
        await new Promise((r) => setTimeout(r, settle));
        const ao = [], frame = [];
        let last = null;
        for (let tries = 0; ao.length < samples && tries < 20 * samples; ++tries) {
          await new Promise((r) => setTimeout(r, 150));
          const s = o.stats();
          if (!s.passMs || s.frames === last) continue;
          last = s.frames;
          if (s.passMs.sao === null || s.passMs.sao === undefined) continue;
          ao.push(aoPasses.reduce((sum, p) => sum + (s.passMs[p] ?? 0), 0));
          if (s.frameMs > 0) frame.push(s.frameMs);
        }
        o.setContinuous(false);
        return { ao, frame, state: o.get('ao.estimator') + '/' + o.get('ao.preset') };
      }, { estimator, preset, aoPasses, samples: options.samples, settle: options.settle });
      if (result.ao.length === 0) throw new Error(`${estimator} ${preset}: no timer results`);
      const row = { estimator, preset, aoMs: median(result.ao),
                    frameMs: result.frame.length ? median(result.frame) : NaN,
                    readings: result.ao.length };
      rows.push(row);
      console.log(`${estimator.padEnd(7)} ${preset.padEnd(7)} AO passes ${row.aoMs.toFixed(1).padStart(7)} ms   ` +
                  `frame ${row.frameMs.toFixed(1).padStart(7)} ms   (${row.readings} readings, ${result.state})`);
    }
  }
  if (errors.length) throw new Error(`page errors: ${errors.join('; ')}`);
  fs.mkdirSync(path.dirname(options.csv), { recursive: true });
  fs.writeFileSync(options.csv, 'estimator,preset,width,height,ao_ms,frame_ms\n' +
    rows.map((r) => `${r.estimator},${r.preset},${width},${height},${r.aoMs.toFixed(2)},${r.frameMs.toFixed(2)}`)
      .join('\n') + '\n');
  console.log(`wrote ${path.relative(root, options.csv)}`);
} finally {
  await browser.close();
  server.stop();
}
