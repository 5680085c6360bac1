// WebGL calls per frame on the demo page, by method: every method of WebGLRenderingContext counted while the page draws
// the built-in scene, playing, for four seconds (tests/browser/calls.test.mjs holds the default frame to a bound).
// Usage: node tools/browser-bench/gl-calls.mjs [WxH] [state | every]   ('every': every effect with a switch on)
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startServer } from '../serve-web.mjs';
import {
  applyBenchmarkState, chromiumLaunchOptions, countWebGlCalls, parsePositional, parseSize,
} from '../headless-chromium.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
const [size = '640x360', state = ''] = parsePositional(process.argv.slice(2), path.basename(import.meta.url), 2);
const [width, height] = parseSize(size);
const server = await startServer(process.env.OBSCURA_WEB_SITE ?? path.join(root, 'build-web', 'site'));
const browser = await chromium.launch(chromiumLaunchOptions);
try {
  const context = await browser.newContext({ viewport: { width, height }, deviceScaleFactor: 1 });
  await context.addInitScript(countWebGlCalls);
  const page = await context.newPage();
  await page.goto(`http://127.0.0.1:${server.address().port}/?resolution.dynamic=off&resolution.quick-start=off`);
  await page.waitForFunction(() => document.body.dataset.ready === 'true', null, { timeout: 120000 });
  await page.evaluate(applyBenchmarkState, state);
  const result = await page.evaluate(async () => {
    const o = window.obscura;
    o.setContinuous(true);
    await new Promise((r) => setTimeout(r, 3000));
    const f0 = o.stats().frames;
    window.glCalls = {};
    await new Promise((r) => setTimeout(r, 4000));
    const frames = o.stats().frames - f0;
    o.setContinuous(false);
    return { frames, counts: window.glCalls };
  });
  const entries = Object.entries(result.counts).sort((a, b) => b[1] - a[1]);
  const total = entries.reduce((s, [, n]) => s + n, 0);
  const perFrame = (total / result.frames).toFixed(1);
  console.log(`${size} '${state}': ${result.frames} frames, ${perFrame} WebGL calls per frame`);
  for (const [k, n] of entries) console.log(`  ${(n / result.frames).toFixed(1).padStart(7)}  ${k}`);
} finally {
  await browser.close();
  server.stop();
}
