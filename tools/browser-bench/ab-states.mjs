// Obscura's page frame in several states, taking turns in one page, each timed frame after two untimed ones in its
// state (draw + gl.finish + a 1-pixel readPixels, as bench.mjs times it), on 2CylinderEngine.glb at the canvas's full
// size: the medians and the passes each state runs. A state changes only what it names (setState), so each should
// name every parameter another one sets.
// Usage: node tools/browser-bench/ab-states.mjs [--size WxH] [--frames N] STATE ...
//   e.g. ... 'preset=low&ao=off&fxaa=on' 'preset=low&ao=off&fxaa=off'   (docs/benchmarks.md, issue 26)
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startServer } from '../serve-web.mjs';
import {
  chromiumLaunchOptions, expectFullScale, openDemoPage, parseOptions, parseSize,
} from '../headless-chromium.mjs';
import { installPassCounter } from './pass-counter.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
const model = '/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb';
let size = '1280x720', frames = 12;
const states = [];
parseOptions(process.argv.slice(2), {
  '--size': (v) => { size = v; },
  '--frames': (v) => { frames = Number(v); },
}, path.basename(import.meta.url), (state) => states.push(state));
const [width, height] = parseSize(size);
const server = await startServer(path.join(root, 'build-web', 'site'));
const browser = await chromium.launch(chromiumLaunchOptions);
try {
  const { page, errors } = await openDemoPage(browser, `http://127.0.0.1:${server.address().port}/`, width, height);
  await page.evaluate(async (data) => {
    await window.obscura.loadScene(new Uint8Array(data), 'engine.glb');
    window.obscura.set('radius', 41.8);
  }, [...fs.readFileSync(model)]);
  await page.evaluate(`(${installPassCounter.toString()})(window.obscura.canvas.getContext('webgl'))`);
  const base = await page.evaluate(() => window.obscura.state());
  const times = states.map(() => []), passes = [];
  for (let frame = -2; frame < frames; ++frame) {
    for (let s = 0; s < states.length; ++s) {
      const result = await page.evaluate(({ base, state }) => {
        const o = window.obscura;
        o.setState(`${base}&${state}`);
        const gl = o.canvas.getContext('webgl');
        for (let warm = 0; warm < 2; ++warm) {  // the state's first frames (programs, targets) are not timed
          o.draw();
          gl.finish();
        }
        window.benchPasses.reset();
        const start = performance.now();
        o.draw();
        gl.finish();
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
        return { ms: performance.now() - start, passes: window.benchPasses.read() };
      }, { base, state: states[s] });
      if (frame >= 0) times[s].push(result.ms);
      passes[s] = result.passes;
      if (frame === -2) await expectFullScale(page, states[s]);
    }
  }
  const median = (v) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];
  for (let s = 0; s < states.length; ++s) {
    console.log(`${size} ${states[s]}: ${median(times[s]).toFixed(1)} ms median of ${frames}; ` +
                `${passes[s].fullscreen} + ${passes[s].geometry} passes; ratio to the first ` +
                `${(median(times[s]) / median(times[0])).toFixed(2)}`);
  }
  if (errors.length) throw new Error(errors.join('\n'));
} finally {
  await browser.close();
  server.close();
}
