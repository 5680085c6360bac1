#!/usr/bin/env node
// What the lighting's choices cost in the browser: whole frames of the demo page (draw + gl.finish() + a 1-pixel
// readPixels, as bench.mjs times them) for each case, on 2CylinderEngine.glb and the metallic-roughness sample
// (assets/scenes/pbr-samples.glb), at each size. A case is a state text applied over the page's defaults (e.g.
// "ao=off&lighting.depth=prepass"), optionally on another build of the site (--site-b DIR: its cases are marked "B",
// for an A/B of two builds in one run). The cases of one scene and size take turns frame by frame, R rounds, so a
// slow spell of the shared machine falls on all of them alike; reported are the median of each case's frames, its
// ratio to the first case, and how many full-screen and geometry passes the frame ran (pass-counter.mjs).
//
//   node tools/browser-bench/lighting-costs.mjs [--sizes 640x360,1280x720] [--scenes engine,pbr] [--rounds R]
//        [--frames N] [--site-b DIR] [--csv FILE] CASE...     (CASE: a state text; "B:" before it: on --site-b)
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startServer } from '../serve-web.mjs';
import { chromiumLaunchOptions, fixedScaleUrl, median, parseOptions, parseSize } from '../headless-chromium.mjs';
import { installPassCounter } from './pass-counter.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
const SCENES = {
  engine: '/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb',
  pbr: path.join(root, 'assets', 'scenes', 'pbr-samples.glb'),
};
const options = { sizes: ['640x360', '1280x720'], scenes: ['engine', 'pbr'], rounds: 5, frames: 2, siteB: null,
                  csv: path.join(root, 'bench-results', 'browser-lighting.csv'), cases: [] };
parseOptions(process.argv.slice(2), {
  '--sizes': (v) => { options.sizes = v.split(','); },
  '--scenes': (v) => { options.scenes = v.split(','); },
  '--rounds': (v) => { options.rounds = Number(v); },
  '--frames': (v) => { options.frames = Number(v); },
  '--site-b': (v) => { options.siteB = path.resolve(v); },
  '--csv': (v) => { options.csv = path.resolve(v); },
}, path.basename(import.meta.url), (state) => options.cases.push(state));
if (!options.cases.length) options.cases = ['', 'ao=off'];
for (const scene of options.scenes) if (!SCENES[scene]) throw new Error(`--scenes: ${scene} is not engine or pbr`);

// One page per case (its own window and context), the scene loaded, the state applied over the page's defaults.
async function openCase(browser, base, size, scene, text) {
  const [width, height] = parseSize(size);
  const context = await browser.newContext({ viewport: { width, height }, deviceScaleFactor: 1 });
  const page = await context.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  await page.goto(fixedScaleUrl(`${base}/index.html`));
  await page.waitForFunction(() => document.body.dataset.ready === 'true', null, { timeout: 120000 });
  await page.addStyleTag({ content: '#panel { display: none !important; }' });
  const bytes = [...fs.readFileSync(SCENES[scene])];
  const info = await page.evaluate(async ({ data, name, state }) => {
    const o = window.obscura;
    await o.loadScene(new Uint8Array(data), name);
    if (state) o.setState(state);
    window.benchGl = o.canvas.getContext('webgl');
    o.draw();
    return { state: o.state() };
  }, { data: bytes, name: path.basename(SCENES[scene]), state: text });
  await page.evaluate(`(${installPassCounter.toString()})(window.benchGl)`);
  info.passes = await page.evaluate(() => {
    window.benchPasses.reset();
    window.obscura.draw();
    return window.benchPasses.read();
  });
  if (errors.length) throw new Error(`${text}: ${errors.join('; ')}`);
  return { context, page, info };
}

function timeFrames(frames) {
  const gl = window.benchGl, pixel = new Uint8Array(4);
  gl.finish();
  gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
  const times = [];
  for (let i = 0; i < frames; ++i) {
    const start = performance.now();
    window.obscura.draw();
    gl.finish();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
    times.push(performance.now() - start);
  }
  return times;
}

const serverA = await startServer(path.join(root, 'build-web', 'site'));
const serverB = options.siteB ? await startServer(options.siteB) : null;
const browser = await chromium.launch(chromiumLaunchOptions);
const rows = [];
try {
  for (const scene of options.scenes)
    for (const size of options.sizes) {
      const cases = [];
      for (const text of options.cases) {
        const onB = text.startsWith('B:');
        if (onB && !serverB) throw new Error(`${text}: needs --site-b`);
        const state = onB ? text.slice(2) : text;
        const base = `http://127.0.0.1:${(onB ? serverB : serverA).address().port}`;
        cases.push({ label: text || '(defaults)', ...(await openCase(browser, base, size, scene, state)), times: [] });
      }
      for (const c of cases) await c.page.evaluate(timeFrames, 2);  // warm-up: compiles, uploads
      for (let round = 0; round < options.rounds; ++round)
        for (let k = 0; k < cases.length; ++k) {
          const c = cases[(round + k) % cases.length];
          c.times.push(...(await c.page.evaluate(timeFrames, options.frames)));
        }
      const first = median(cases[0].times);
      console.log(`\n${scene} ${size}: median ms of ${options.rounds} x ${options.frames} frames, ratio to the first`);
      for (const c of cases) {
        const ms = median(c.times);
        const passes = c.info.passes ? ` full-screen ${c.info.passes.fullscreen}, geometry ${c.info.passes.geometry}` : '';
        console.log(`  ${c.label.padEnd(56)} ${ms.toFixed(1).padStart(8)} ms  x${(ms / first).toFixed(2)}${passes}`);
        rows.push([scene, size, `"${c.label}"`, ms.toFixed(2), (ms / first).toFixed(3),
                   c.info.passes?.fullscreen ?? '', c.info.passes?.geometry ?? ''].join(','));
      }
      for (const c of cases) await c.context.close();
    }
} finally {
  await browser.close();
  serverA.stop();
  serverB?.stop();
}
fs.mkdirSync(path.dirname(options.csv), { recursive: true });
fs.writeFileSync(options.csv, 'scene,size,case,median_ms,ratio,fullscreen_passes,geometry_passes\n' +
                 rows.join('\n') + '\n');
console.log(`\nwrote ${path.relative(process.cwd(), options.csv)}`);
