// Where the renderer's host time goes in the browser: Chrome's CPU profiler (DevTools protocol, a sample every 50 us)
// samples the page's thread while the demo page draws frames back to back, and this prints, per frame, the self and
// the inclusive time of each function within the page's animation-frame callback (wasm, Emscripten's GL glue, WebGL
// calls). Wasm functions have names in a build linked with --profiling-funcs:
//   emcmake cmake -S . -B /tmp/build-web-prof -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXE_LINKER_FLAGS=--profiling-funcs
//   cmake --build /tmp/build-web-prof --target obscura-site
//   OBSCURA_WEB_SITE=/tmp/build-web-prof/site node tools/browser-bench/host-profile.mjs 640x360 '' 10
// Usage: node tools/browser-bench/host-profile.mjs [WxH] [state] [seconds]; CALLERS=name also prints the chains of
// callers of the functions whose names contain `name`; SHOW_HOSTS=1 prints every frame's host time (stats().lastHostMs,
// microsecond resolution: the page is served cross-origin isolated).
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startServer } from '../serve-web.mjs';
import {
  applyBenchmarkState, chromiumLaunchOptions, openDemoPage, parsePositional, parseSize,
} from '../headless-chromium.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
const [size = '1280x720', state = '', seconds = '5'] =
  parsePositional(process.argv.slice(2), path.basename(import.meta.url), 3);
const [width, height] = parseSize(size);
const server = await startServer(process.env.OBSCURA_WEB_SITE ?? path.join(root, 'build-web', 'site'), 0, {},
                                 { isolated: true });
const browser = await chromium.launch(chromiumLaunchOptions);
try {
  const { page } = await openDemoPage(browser, `http://127.0.0.1:${server.address().port}/`, width, height);
  await page.evaluate(applyBenchmarkState, state);
  await page.evaluate(async () => {
    const o = window.obscura;
    o.setContinuous(true);
    await new Promise((r) => setTimeout(r, 2500));
  });
  const cdp = await page.context().newCDPSession(page);
  await cdp.send('Profiler.enable');
  await cdp.send('Profiler.setSamplingInterval', { interval: 50 });
  const framesBefore = await page.evaluate(() => window.obscura.stats().frames);
  await cdp.send('Profiler.start');
  const hosts = await page.evaluate(async (ms) => {
    const o = window.obscura, out = [];
    const end = performance.now() + ms;
    let last = null;
    while (performance.now() < end) {
      await new Promise((r) => setTimeout(r, 250));
      const s = o.stats();
      if (s.frames !== last) { last = s.frames; out.push(s.lastHostMs); }
    }
    return out;
  }, Number(seconds) * 1000);
  const { profile } = await cdp.send('Profiler.stop');
  const frames = (await page.evaluate(() => window.obscura.stats().frames)) - framesBefore;
  const byId = new Map(profile.nodes.map((n) => [n.id, n]));
  const parent = new Map();
  for (const n of profile.nodes) for (const c of n.children ?? []) parent.set(c, n.id);
  const within = new Map(), inclusive = new Map(), callers = new Map();
  const dt = profile.timeDeltas;
  let renderTotal = 0;
  for (let i = 0; i < profile.samples.length; ++i) {
    const ms = (dt[i + 1] ?? 0) / 1000;
    const id = profile.samples[i];
    const n = byId.get(id);
    const key = `${n.callFrame.functionName || '(anon)'} ${path.basename(n.callFrame.url || '')}`;
    // Only samples within the page's animation-frame callback (Emscripten's `tick`), which draws the frame.
    let inRender = false;
    const onStack = new Set();
    for (let p = id; p !== undefined; p = parent.get(p)) {
      const c = byId.get(p).callFrame;
      onStack.add(`${c.functionName || '(anon)'} ${path.basename(c.url || '')}`);
      if (c.functionName === 'tick') { inRender = true; break; }
    }
    if (inRender && process.env.CALLERS) {
      // The chain of callers (innermost first, up to 7 frames) from the first frame matching CALLERS.
      const chain = [];
      let found = false;
      for (let p = id; p !== undefined && chain.length < 7; p = parent.get(p)) {
        const f = byId.get(p).callFrame.functionName;
        if (!found && f.includes(process.env.CALLERS)) found = true;
        if (found && !/^(invoke_|js-to-wasm|wasm-to-js)/.test(f)) chain.push(f.replace(/\(.*$/, '').slice(0, 60));
      }
      if (found) { const k = chain.join(' < '); callers.set(k, (callers.get(k) ?? 0) + ms); }
    }
    if (inRender) {
      within.set(key, (within.get(key) ?? 0) + ms); renderTotal += ms;
      for (const k of onStack) inclusive.set(k, (inclusive.get(k) ?? 0) + ms);
    }
  }
  const sorted = hosts.slice().sort((a, b) => a - b);
  if (process.env.SHOW_HOSTS) console.log(sorted.map((v) => v.toFixed(3)).join(' '));
  const isolated = await page.evaluate(() => self.crossOriginIsolated);
  console.log(`${size} '${state}' (cross-origin isolated: ${isolated}): ${frames} frames, ` +
              `host median ${sorted[sorted.length >> 1]?.toFixed(2)} ms; ` +
              `sampled in the frame callback ${(renderTotal / frames).toFixed(2)} ms/frame`);
  const top = (m, label) => {
    console.log(label);
    for (const [k, v] of [...m].sort((a, b) => b[1] - a[1]).slice(0, 90))
      console.log(`  ${(v / frames).toFixed(3).padStart(8)} ms/frame  ${k.slice(0, 110)}`);
  };
  top(within, 'self time in the frame callback:');
  top(inclusive, 'inclusive time in the frame callback:');
  if (process.env.CALLERS) top(callers, `callers of ${process.env.CALLERS}:`);
} finally {
  await browser.close();
  server.stop();
}
