// Shared set-up of the browser tests: the demo page served from 127.0.0.1, headless Debian chromium (SwiftShader
// WebGL through ANGLE) driven by playwright-core, and image helpers working on Obscura's snapshots
// ({width, height, pixels: RGBA rows top to bottom}).
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startServer } from '../../tools/serve-web.mjs';
import { chromiumLaunchOptions } from '../../tools/headless-chromium.mjs';

export const sourceDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
export const siteDir = process.env.OBSCURA_WEB_SITE ?? path.join(sourceDir, 'build-web', 'site');
export const renderBinary = process.env.OBSCURA_RENDER ?? path.join(sourceDir, 'build', 'obscura-render');
export const assimpModels = '/usr/share/assimp/models/glTF2';
// Test artefacts (snapshots, screenshots, the parity report) go here; README pictures go to docs/images when
// OBSCURA_UPDATE_SCREENSHOTS=1.
export const artifactDir = process.env.OBSCURA_BROWSER_ARTIFACTS ?? path.join(sourceDir, 'build-web', 'browser-tests');

// SwiftShader is slow: the page is 640 x 360 CSS pixels at devicePixelRatio 0.5, so the canvas draws 320 x 180.
export const viewport = { width: 640, height: 360 };
export const deviceScaleFactor = 0.5;

// Starts the server and the browser; returns {baseUrl, browser, newContext(options), close()}. Playwright launches
// Chromium with a fresh temporary profile (--user-data-dir) and deletes it on close.
export async function startBrowser() {
  if (!fs.existsSync(path.join(siteDir, 'obscura-core.wasm'))) {
    throw new Error(`${siteDir} has no obscura-core.wasm: build the web version first (tools/build-web.sh)`);
  }
  fs.mkdirSync(artifactDir, { recursive: true });
  const server = await startServer(siteDir);
  const browser = await chromium.launch(chromiumLaunchOptions);
  return {
    baseUrl: `http://127.0.0.1:${server.address().port}/`,
    browser,
    // A browser context (a window) with the tests' small viewport unless told otherwise.
    newContext: (options = {}) => browser.newContext({ viewport, deviceScaleFactor, ...options }),
    async close() {
      await browser.close();
      server.stop();
    },
  };
}

// GL errors as Chrome reports them: WebGL's own checks ("WebGL: INVALID_OPERATION: ...") and ANGLE's
// ("GL_INVALID_ENUM ..."), both as console warnings. Other warnings (SwiftShader's "GPU stall due to ReadPixels",
// the context-loss test's CONTEXT_LOST_WEBGL) are not failures.
const glErrorWarning = /GL_INVALID_|GL_OUT_OF_MEMORY|WebGL: INVALID_/;

// Opens the page at `url` and waits until Obscura has drawn its first frame. The page runs with `debug-gl`
// (glGetError after every pass; an error stops drawing and is logged as a console error naming the pass), and with
// dynamic resolution and quick start off unless the URL says otherwise (resolution.dynamic and
// resolution.quick-start: the page's defaults are on, which would change the render scale between the frames a test
// compares, and make the first frame a cheap one). Console errors, GL errors reported as warnings,
// uncaught exceptions and failed requests are collected in page.errors. `{ debugGl: false }` leaves debug-gl off,
// for a test that counts the page's WebGL calls (its checks are calls of their own).
export async function openPage(context, url, { debugGl = true } = {}) {
  const page = await context.newPage();
  page.errors = [];
  page.on('console', (message) => {
    if (message.type() === 'error' || (message.type() === 'warning' && glErrorWarning.test(message.text()))) {
      page.errors.push(message.text());
    }
  });
  page.on('pageerror', (error) => page.errors.push(`uncaught: ${error.message}`));
  page.on('response', (response) => {
    if (response.status() >= 400) page.errors.push(`HTTP ${response.status()} for ${response.url()}`);
  });
  const checked = new URL(url);
  if (debugGl) checked.searchParams.set('debug-gl', '');
  if (!checked.searchParams.has('resolution.dynamic')) checked.searchParams.set('resolution.dynamic', 'off');
  if (!checked.searchParams.has('resolution.quick-start')) checked.searchParams.set('resolution.quick-start', 'off');
  await page.goto(checked.toString());
  await page.waitForFunction(() => document.body.dataset.ready === 'true', null, { timeout: 60000 });
  await waitForDrawn(page);
  return page;
}

// Waits until the page has drawn the frame of its latest change (frames are drawn on requestAnimationFrame only
// after a change, outside continuous mode).
export async function waitForDrawn(page) {
  await page.waitForFunction(() => {
    const stats = window.obscura.stats();
    return stats.frames > 0 && !stats.pending;
  }, null, { timeout: 60000, polling: 50 });
}

export async function snapshot(page) {
  const result = await page.evaluate(() => {
    const s = window.obscura.snapshot();
    return { width: s.width, height: s.height, pixels: Array.from(s.pixels) };
  });
  return { width: result.width, height: result.height, pixels: Uint8Array.from(result.pixels) };
}

// Mean and max absolute difference per channel (R, G, B), in 0..255, of two images of the same size.
export function compareImages(a, b) {
  if (a.width !== b.width || a.height !== b.height) {
    throw new Error(`sizes differ: ${a.width}x${a.height} vs ${b.width}x${b.height}`);
  }
  const channels = ['r', 'g', 'b'].map(() => ({ mean: 0, max: 0, differing: 0 }));
  const count = a.width * a.height;
  for (let i = 0; i < count; ++i) {
    for (let c = 0; c < 3; ++c) {
      const d = Math.abs(a.pixels[i * 4 + c] - b.pixels[i * 4 + c]);
      channels[c].mean += d;
      channels[c].max = Math.max(channels[c].max, d);
      if (d > 0) channels[c].differing += 1;
    }
  }
  for (const c of channels) {
    c.mean /= count;
    c.differing /= count;  // fraction of pixels
  }
  return { r: channels[0], g: channels[1], b: channels[2],
           mean: Math.max(...channels.map((c) => c.mean)), max: Math.max(...channels.map((c) => c.max)) };
}

// Luminance statistics of an image, in 0..1.
export function luminanceStats(image) {
  const count = image.width * image.height;
  let sum = 0, squares = 0, min = 1, max = 0;
  for (let i = 0; i < count; ++i) {
    const p = image.pixels.subarray(i * 4, i * 4 + 3);
    const l = (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / 255;
    sum += l;
    squares += l * l;
    min = Math.min(min, l);
    max = Math.max(max, l);
  }
  const mean = sum / count;
  return { mean, deviation: Math.sqrt(Math.max(0, squares / count - mean * mean)), min, max };
}

// Fraction of pixels whose colour differs from `rgb` by more than `tolerance` in any channel.
export function fractionUnlike(image, rgb, tolerance = 4) {
  let unlike = 0;
  const count = image.width * image.height;
  for (let i = 0; i < count; ++i) {
    if ([0, 1, 2].some((c) => Math.abs(image.pixels[i * 4 + c] - rgb[c]) > tolerance)) unlike += 1;
  }
  return unlike / count;
}

export function readModel(relative) { return fs.readFileSync(path.join(assimpModels, relative)); }
