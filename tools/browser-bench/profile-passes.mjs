// Per-pass GPU milliseconds of Obscura's page frame on 2CylinderEngine.glb, from EXT_disjoint_timer_query (SwiftShader
// offers it): where the frame's time goes. Usage: node tools/browser-bench/profile-passes.mjs [WxH] [state ...]
// Each state is applied over the defaults (AO radius 41.8, the engine's), not over the state before it.
// A state `@unbatched` draws every instance alone from then on, `@batched` in static batches again (gpu/GpuScene.h).
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startServer } from '../serve-web.mjs';
import {
  applyBenchmarkState, chromiumLaunchOptions, fixedScaleUrl, parsePositional, parseSize,
} from '../headless-chromium.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
const model = '/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb';
const [size = '1280x720', ...states] = parsePositional(process.argv.slice(2), path.basename(import.meta.url), Infinity);
const [width, height] = parseSize(size);
const server = await startServer(process.env.OBSCURA_WEB_SITE ?? path.join(root, 'build-web', 'site'));
const browser = await chromium.launch(chromiumLaunchOptions);
const page = await (await browser.newContext({ viewport: { width, height }, deviceScaleFactor: 1 })).newPage();
await page.goto(fixedScaleUrl(`http://127.0.0.1:${server.address().port}/`));
await page.waitForFunction(() => document.body.dataset.ready === 'true', null, { timeout: 120000 });
await page.addStyleTag({ content: '#panel { display: none !important; }' });
const bytes = [...fs.readFileSync(model)];
await page.evaluate(async (data) => { await window.obscura.loadScene(new Uint8Array(data), 'engine.glb'); }, bytes);
for (const state of states.length ? states : ['']) {
  // The defaults (every parameter; the engine's AO radius), then the state: whatever ran before it.
  await page.evaluate(applyBenchmarkState, `${state.startsWith('@') ? '' : state}&ao.radius=41.8`);
  const result = await page.evaluate(async (s) => {
    const o = window.obscura;
    if (s.startsWith('@')) o.setStaticBatches(s === '@batched');
    const sums = {};
    let n = 0;
    o.setContinuous(true);
    await new Promise((r) => setTimeout(r, 1500));
    for (let i = 0; i < 12; ++i) {
      await new Promise((r) => setTimeout(r, 400));
      const p = o.stats().passMs;
      if (!p) continue;
      n += 1;
      for (const [k, v] of Object.entries(p)) if (v !== null) sums[k] = (sums[k] ?? 0) + v;
    }
    o.setContinuous(false);
    return { n, passes: Object.fromEntries(Object.entries(sums).map(([k, v]) => [k, +(v / n).toFixed(1)])),
             ran: o.stats().passesRun };
  }, state);
  const total = Object.values(result.passes).reduce((a, b) => a + b, 0);
  console.log(`${size} ${state || '(defaults)'}: total ${total.toFixed(1)} ms`, JSON.stringify(result.passes));
}
await browser.close();
server.stop();
