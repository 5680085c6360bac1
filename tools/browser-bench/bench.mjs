#!/usr/bin/env node
// Browser benchmark: Obscura's demo page (WebGL 1) against three.js (WebGL 2) with and without N8AO, and against
// pmndrs/postprocessing with every effect, on the same model, camera, sizes and AO radius, in headless Debian
// chromium on SwiftShader (the browser tests' flags). Run through tools/browser-bench.sh, which builds the web version
// and installs this folder's npm packages first. The renderers and the three comparisons (issue 26): RENDERERS below.
//
//   node tools/browser-bench/bench.mjs [--frames N] [--rounds R] [--warmup W] [--sizes 640x360,1280x720]
//                                      [--quick] [--extras | --no-extras] [--csv FILE] [--shots DIR]
//
// --quick: the smoke run (640x360, 1 warm-up frame, 2 rounds of 2 frames, no extras, CSV in the shots folder).
// --extras: also the renderers that explain figures (Obscura with the SAO estimator, three.js + SAOPass, three.js
// plain with antialias: true, N8AOPostPass through pmndrs/postprocessing); off by default.
//
// Each measured frame is draw + gl.finish() + a 1-pixel gl.readPixels on the renderer's own context. Every renderer
// has its own page (its own window of the exact size, deviceScaleFactor 1); after a warm-up they take turns, N frames
// each per turn, R rounds, the first renderer of a round rotating, so a slow spell of the shared machine falls on all
// of them alike. Reported: the median of the R x N frames per renderer and size, the ratios of those medians, and
// beside each ratio the median over the rounds of the ratio within a round (the two renderers measured seconds apart);
// beside each figure, how many full-screen and geometry passes the renderer's frame ran (pass-counter.mjs, counted
// from the WebGL calls the same way for every renderer).
// Screenshots of every renderer go to build/browser-bench/ and are checked automatically (model visible, same
// framing as Obscura, AO darker than its AO-off counterpart); a failed check fails the run.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import zlib from 'node:zlib';
import { chromium } from 'playwright-core';
import { glbBoundingSphere } from './glb-bounds.mjs';
import { decodePng } from '../../tests/browser/png.mjs';
import { startServer } from '../serve-web.mjs';
import {
  chromiumFlags, chromiumLaunchOptions, expectFullScale, fixedScaleUrl, parseOptions,
} from '../headless-chromium.mjs';
import { installPassCounter } from './pass-counter.mjs';

const benchDir = path.dirname(fileURLToPath(import.meta.url));
const sourceDir = path.resolve(benchDir, '..', '..');
const siteDir = process.env.OBSCURA_WEB_SITE ?? path.join(sourceDir, 'build-web', 'site');
const modelPath = '/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb';
const modelName = path.basename(modelPath);
const AO_RADIUS_FRACTION = 0.05;  // of the bounding sphere's diameter, for every renderer


// --- Options ---------------------------------------------------------------------------------------------------------
function parseArgs(argv) {
  const options = { frames: 2, rounds: 5, warmup: 2, sizes: ['640x360', '1280x720'], extras: false, quick: false,
                    csv: path.join(sourceDir, 'bench-results', 'browser-bench.csv'),
                    shots: path.join(sourceDir, 'build', 'browser-bench') };
  const given = new Set();
  const count = (name) => (text) => {
    const n = Number(text);
    if (!Number.isInteger(n) || n < 1) throw new Error(`--${name}: a whole number >= 1, please`);
    options[name] = n;
    given.add(name);
  };
  const set = (name, value) => { options[name] = value; given.add(name); };
  parseOptions(argv, {
    '--frames': count('frames'),
    '--rounds': count('rounds'),
    '--warmup': count('warmup'),
    '--sizes': (v) => set('sizes', v.split(',')),
    '--extras': () => set('extras', true),
    '--no-extras': () => set('extras', false),
    '--quick': () => { options.quick = true; },
    '--csv': (v) => set('csv', path.resolve(v)),
    '--shots': (v) => { options.shots = path.resolve(v); },
  }, path.basename(import.meta.url));
  if (options.quick) {
    // Smoke run: one size, a few frames; the figures are not meant to be read.
    if (!given.has('sizes')) options.sizes = ['640x360'];
    if (!given.has('frames')) options.frames = 2;
    if (!given.has('rounds')) options.rounds = 2;
    if (!given.has('warmup')) options.warmup = 1;
    if (!given.has('extras')) options.extras = false;
    if (!given.has('csv')) options.csv = path.join(sourceDir, 'build', 'browser-bench', 'browser-bench-quick.csv');
  }
  options.sizes = options.sizes.map((text) => {
    const match = /^(\d+)x(\d+)$/.exec(text);
    if (!match) throw new Error(`--sizes: ${text} is not WxH`);
    return { width: Number(match[1]), height: Number(match[2]), label: text };
  });
  return options;
}

// --- Renderers -------------------------------------------------------------------------------------------------------
// kind 'obscura': the demo page build-web/site/index.html with `state` applied over its defaults (its own lighting:
// the built-in sky, the medium tier); kind 'three': tools/browser-bench/three.html in the given mode. Three groups,
// as issue 26 sets them:
//   - the same lighting work on both sides: Obscura's defaults against three.js with the file's materials under a
//     PMREM of three's RoomEnvironment and the same sun ('three-env-*');
//   - Obscura's preset low against three.js's benchmark default (the file's materials under a hemisphere light and
//     the sun: 'three-plain', 'three-n8ao');
//   - every effect on: Obscura with AO, bloom, depth of field, fog, tone mapping and FXAA against pmndrs/
//     postprocessing with N8AOPostPass, DepthOfFieldEffect, BloomEffect, ToneMappingEffect, FXAAEffect and three's
//     fog, under the same environment ('pmndrs-all').
// `checks`: the screenshot checks that apply (framing against Obscura's AO-off frame, AO visible against the
// renderer's AO-off counterpart); the every-effect frames blur and fog the model, so only its coverage is checked.
const ALL_EFFECTS = 'bloom=on&dof=on&fog=on&fog.mode=exp2';
const RENDERERS = [
  { id: 'obscura-ao', label: 'Obscura, defaults (AO on)', kind: 'obscura', state: '' },
  { id: 'obscura-off', label: 'Obscura, AO off', kind: 'obscura', state: 'ao=off' },
  { id: 'obscura-low', label: 'Obscura, preset low (AO on)', kind: 'obscura', state: 'preset=low' },
  { id: 'obscura-low-off', label: 'Obscura, preset low, AO off', kind: 'obscura', state: 'preset=low&ao=off' },
  { id: 'obscura-all', label: 'Obscura, AO, bloom, DoF, fog, tone mapping, FXAA', kind: 'obscura',
    state: ALL_EFFECTS, fog: true, checks: false },
  { id: 'three-env-plain', label: 'three.js plain, RoomEnvironment', kind: 'three' },
  { id: 'three-env-n8ao', label: 'three.js + N8AOPass, RoomEnvironment', kind: 'three' },
  { id: 'three-plain', label: 'three.js plain', kind: 'three' },
  { id: 'three-n8ao', label: 'three.js + N8AOPass', kind: 'three' },
  { id: 'pmndrs-all', label: 'pmndrs: N8AO, DoF, bloom, tone mapping, FXAA, fog', kind: 'three', fog: true,
    checks: false },
  { id: 'obscura-sao', label: 'Obscura, AO on with the SAO estimator', kind: 'obscura', state: 'ao.estimator=sao',
    extra: true },
  { id: 'three-sao', label: 'three.js + SAOPass', kind: 'three', extra: true },
  { id: 'three-plain-aa', label: 'three.js plain, antialias: true', kind: 'three', extra: true },
  { id: 'three-n8ao-pp', label: 'three.js + N8AOPostPass (postprocessing)', kind: 'three', extra: true },
];
// Which renderer each AO renderer is checked against (its frame without AO) in the screenshots.
const AO_OFF_COUNTERPART = { 'obscura-ao': 'obscura-off', 'obscura-low': 'obscura-low-off',
                             'three-env-n8ao': 'three-env-plain', 'three-n8ao': 'three-plain',
                             'obscura-sao': 'obscura-off', 'three-sao': 'three-plain',
                             'three-n8ao-pp': 'three-plain' };
// The ratios reported, as [numerator, denominator, targets by size label ('*': every size) or null]. Targets:
// issue 26.
const RATIOS = [
  ['obscura-ao', 'three-env-n8ao', { '1280x720': 0.5, '640x360': 0.4 }],
  ['obscura-off', 'three-env-plain', { '*': 1.0 }],
  ['obscura-low', 'three-n8ao', { '*': 0.45 }],
  ['obscura-low-off', 'three-plain', { '*': 1.2 }],
  ['obscura-all', 'pmndrs-all', { '1280x720': 0.35 }],
  ['obscura-off', 'obscura-ao', { '*': 1.0 }],
  ['obscura-ao', 'three-n8ao', null],
  ['obscura-off', 'three-plain', null],
  ['three-env-n8ao', 'three-env-plain', null],
  ['three-n8ao', 'three-plain', null],
  ['obscura-ao', 'three-sao', null],
  ['obscura-ao', 'three-n8ao-pp', null],
  ['obscura-off', 'three-plain-aa', null],
];
// The every-effect comparison's fog, on both sides: exp2, reaching 20 % at the camera target's distance.
const FOG_AT_TARGET = 0.2;
const FOG_COLOR = [0.55, 0.6, 0.66];  // linear

// --- A static server: the site, this folder (pages and node_modules) and the model, on 127.0.0.1 only -----------
function startBenchServer() {
  return startServer(null, 0, { '/site/': siteDir, '/bench/': benchDir, [`/model/${modelName}`]: modelPath });
}

// --- Pages -----------------------------------------------------------------------------------------------------------
function watchErrors(page, name) {
  page.errors = [];
  page.on('console', (message) => {
    if (message.type() === 'error' || (message.type() === 'warning' && /GL_INVALID_|GL_OUT_OF_MEMORY|WebGL: INVALID_/
      .test(message.text()))) page.errors.push(`${name}: ${message.text()}`);
  });
  page.on('pageerror', (error) => page.errors.push(`${name}: uncaught: ${error.message}`));
  page.on('response', (response) => {
    if (response.status() >= 400) page.errors.push(`${name}: HTTP ${response.status()} for ${response.url()}`);
  });
}

// Obscura's demo page, as a visitor gets it (no debug-gl: no glGetError after every pass), controls panel hidden.
async function openObscura(browser, base, size, renderer, aoRadius, fogDensity) {
  const context = await browser.newContext({ viewport: { width: size.width, height: size.height },
                                             deviceScaleFactor: 1 });
  const page = await context.newPage();
  watchErrors(page, renderer.id);
  await page.goto(fixedScaleUrl(`${base}/site/index.html`));
  await page.waitForFunction(() => document.body.dataset.ready === 'true', null, { timeout: 120000 });
  await page.addStyleTag({ content: '#panel { display: none !important; }' });
  await page.waitForFunction(() => window.obscura.stats().frames > 0, null, { timeout: 120000, polling: 50 });
  const info = await page.evaluate(async ({ modelUrl, name, radius, state, fog, fogColor }) => {
    const obscura = window.obscura;
    const bytes = await (await fetch(modelUrl)).arrayBuffer();
    const scene = await obscura.loadScene(bytes, name);
    // The camera Obscura chose, before any state is applied: three.js gets the same.
    const camera = obscura.state();
    // The radius through set() (an alias of ao.radius that stays), then the renderer's state text over it.
    obscura.set('radius', radius);
    if (state) obscura.setState(`${obscura.state()}&${state}`);
    if (fog) {
      obscura.set('fog.density', fog);
      obscura.set('fog.color', fogColor.join(','));
    }
    const gl = obscura.canvas.getContext('webgl');  // Obscura's own context
    window.benchDraw = () => obscura.draw();
    window.benchGl = gl;
    obscura.draw();
    return { scene, state: camera, settings: obscura.state(), context: obscura.context,
             radius: obscura.get('radius'), ao: obscura.get('ao'), estimator: obscura.get('ao.estimator'),
             drawingBuffer: [gl.drawingBufferWidth, gl.drawingBufferHeight],
             contextAttributes: gl.getContextAttributes() };
  }, { modelUrl: `${base}/model/${modelName}`, name: modelName, radius: aoRadius, state: renderer.state,
       fog: renderer.fog ? fogDensity : 0, fogColor: FOG_COLOR });
  await expectFullScale(page, renderer.id);
  await page.evaluate(`(${installPassCounter.toString()})(window.benchGl)`);
  return { context, page, info };
}

// The model's pixels in Obscura's frame: its 'mask' view (geometry white, background black), drawn once.
async function obscuraMask(page) {
  await page.evaluate(() => {
    window.obscura.setView('mask');
    window.benchDraw();
  });
  const png = await page.screenshot();
  await page.evaluate(() => {
    window.obscura.setView('final');
    window.benchDraw();
  });
  return png;
}

async function openThree(browser, base, size, renderer, camera, aoRadius, fogDensity) {
  const context = await browser.newContext({ viewport: { width: size.width, height: size.height },
                                             deviceScaleFactor: 1 });
  const page = await context.newPage();
  watchErrors(page, renderer.id);
  await page.goto(`${base}/bench/three.html`);
  await page.waitForFunction(() => document.body.dataset.ready === 'true', null, { timeout: 120000 });
  const info = await page.evaluate((options) => window.benchSetup(options),
                                   { mode: renderer.id, modelUrl: `${base}/model/${modelName}`, camera, aoRadius,
                                     fog: renderer.fog ? { density: fogDensity, color: FOG_COLOR } : null });
  return { context, page, info };
}

// The camera Obscura chose for the model (state() after loadScene): eye, target, up, vertical fov (degrees), near, far.
function parseCamera(state) {
  const params = new URLSearchParams(state);
  const vector = (key) => {
    const v = (params.get(key) ?? '').split(',').map(Number);
    if (v.length !== 3 || v.some((x) => !Number.isFinite(x))) throw new Error(`state() has no usable ${key}: ${state}`);
    return v;
  };
  const scalar = (key) => {
    const x = Number(params.get(key));
    if (!params.has(key) || !Number.isFinite(x)) throw new Error(`state() has no usable ${key}: ${state}`);
    return x;
  };
  return { eye: vector('eye'), target: vector('target'), up: vector('up'), fovy: scalar('fovy'),
           near: scalar('near'), far: scalar('far') };
}

// One turn of a renderer: `frames` timed frames, each draw + finish + 1-pixel readPixels. Earlier work (the page's
// own animation frame, compositing) is drained first, outside the timing. The same function runs in every page.
function timeFrames(frames) {
  const gl = window.benchGl, draw = window.benchDraw, pixel = new Uint8Array(4);
  gl.finish();
  gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
  const times = [];
  for (let i = 0; i < frames; ++i) {
    const start = performance.now();
    draw();
    gl.finish();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
    times.push(performance.now() - start);
  }
  return { times, error: gl.getError() };
}

// --- Statistics and images ----------------------------------------------------------------------------------------
function quantile(sorted, q) {
  const position = (sorted.length - 1) * q, below = Math.floor(position), above = Math.ceil(position);
  return sorted[below] + (sorted[above] - sorted[below]) * (position - below);
}
function summarise(times) {
  const sorted = [...times].sort((a, b) => a - b);
  return { frames: sorted.length, median: quantile(sorted, 0.5), q1: quantile(sorted, 0.25),
           q3: quantile(sorted, 0.75), min: sorted[0], max: sorted[sorted.length - 1] };
}

// The model's pixels: those unlike the background in any channel. The background is read from the top-left pixel
// (the framing keeps the model away from the corners); all renderers clear to Obscura's sky colour.
const isModel = (image, background, i) => [0, 1, 2].some((c) => Math.abs(image.pixels[i * 4 + c] - background[c]) > 6);
const backgroundOf = (image) => [...image.pixels.subarray(0, 3)];
// maskPng: Obscura's 'mask' view of the same frame (its background is the sky, not a flat colour).
function imageFacts(png, maskPng = null) {
  const image = decodePng(png);
  const maskImage = maskPng ? decodePng(maskPng) : null;
  const background = backgroundOf(image);
  const count = image.width * image.height;
  const mask = new Uint8Array(count);
  let covered = 0, luminance = 0;
  for (let i = 0; i < count; ++i) {
    const p = image.pixels.subarray(i * 4, i * 4 + 3);
    if (maskImage ? maskImage.pixels[i * 4] > 127 : isModel(image, background, i)) {
      mask[i] = 1;
      covered += 1;
      luminance += (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / 255;
    }
  }
  return { width: image.width, height: image.height, mask, coverage: covered / count, background,
           meanLuminance: covered ? luminance / covered : 0 };
}
function intersectionOverUnion(a, b) {
  let both = 0, either = 0;
  for (let i = 0; i < a.length; ++i) {
    both += a[i] & b[i];
    either += a[i] | b[i];
  }
  return either ? both / either : 0;
}

// How much darker an AO frame is than its AO-off counterpart over the model's pixels (the counterpart's mask):
// the mean relative darkening, the share of model pixels at least 4/255 darker, and an image of the darkening
// (grey, amplified 8x, white = none) to see where the AO lands.
function aoDarkening(on, off, mask) {
  const a = decodePng(on), b = decodePng(off);
  const count = a.width * a.height;
  const grey = Buffer.alloc(count, 255);
  let model = 0, visible = 0;
  for (let i = 0; i < count; ++i) {
    if (!mask[i]) continue;
    model += 1;
    const drop = Math.max(...[0, 1, 2].map((c) => b.pixels[i * 4 + c] - a.pixels[i * 4 + c]));
    if (drop >= 4) visible += 1;
    grey[i] = 255 - Math.min(255, Math.max(0, drop) * 8);
  }
  return { visibleShare: model ? visible / model : 0, image: encodeGreyPng(a.width, a.height, grey) };
}

const CRC_TABLE = Array.from({ length: 256 }, (_, n) => {
  let c = n;
  for (let k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c >>> 0;
});
function crc32(buffer) {
  let c = 0xffffffff;
  for (const byte of buffer) c = CRC_TABLE[(c ^ byte) & 255] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}
function encodeGreyPng(width, height, grey) {
  const chunk = (type, data) => {
    const head = Buffer.alloc(8);
    head.writeUInt32BE(data.length, 0);
    head.write(type, 4, 'latin1');
    const crc = Buffer.alloc(4);
    crc.writeUInt32BE(crc32(Buffer.concat([head.subarray(4), data])), 0);
    return Buffer.concat([head, data, crc]);
  };
  const header = Buffer.alloc(13);
  header.writeUInt32BE(width, 0);
  header.writeUInt32BE(height, 4);
  header[8] = 8;  // bit depth; colour type 0 (grey), no interlace
  const raw = Buffer.alloc((width + 1) * height);
  for (let y = 0; y < height; ++y) grey.copy(raw, y * (width + 1) + 1, y * width, (y + 1) * width);
  return Buffer.concat([Buffer.from('89504e470d0a1a0a', 'hex'), chunk('IHDR', header),
                        chunk('IDAT', zlib.deflateSync(raw)), chunk('IEND', Buffer.alloc(0))]);
}

const f2 = (x) => x.toFixed(2);
const pad = (text, width) => String(text).padEnd(width);

// --- Main ------------------------------------------------------------------------------------------------------------
async function main() {
  const options = parseArgs(process.argv.slice(2));
  if (!fs.existsSync(path.join(siteDir, 'obscura-core.wasm'))) {
    throw new Error(`${siteDir} has no obscura-core.wasm: build the web version first (tools/build-web.sh)`);
  }
  const renderers = RENDERERS.filter((r) => options.extras || !r.extra);
  fs.mkdirSync(options.shots, { recursive: true });
  const failures = [];

  const sphere = glbBoundingSphere(fs.readFileSync(modelPath));
  const aoRadius = AO_RADIUS_FRACTION * sphere.diameter;
  const v3 = (v) => v.map((x) => x.toFixed(3)).join(', ');
  console.log(`model: ${modelPath} (${sphere.vertices} vertices, centimetres, not rescaled)`);
  console.log(`bounding sphere (centre of the world-space AABB, radius = half its diagonal; glb-bounds.mjs):`);
  console.log(`  AABB min (${v3(sphere.min)}) max (${v3(sphere.max)})`);
  console.log(`  centre (${v3(sphere.center)}), radius ${sphere.radius.toFixed(4)}, diameter ${sphere.diameter.toFixed(4)}`);
  console.log(`AO radius for every renderer: ${AO_RADIUS_FRACTION * 100} % of the diameter = ${aoRadius.toFixed(4)} ` +
              'model units (cm)');
  console.log(`timing: ${options.warmup} warm-up frames each, then ${options.rounds} rounds x ${options.frames} ` +
              'frames per renderer, round-robin; each frame = draw + gl.finish() + 1-pixel gl.readPixels');

  const server = await startBenchServer();
  const base = `http://127.0.0.1:${server.address().port}`;
  const browser = await chromium.launch(chromiumLaunchOptions);
  console.log(`browser: ${browser.version()} (headless, ${chromiumFlags.join(' ')})`);
  console.log(`machine: ${os.cpus().length} cores (${os.cpus()[0]?.model ?? '?'}), ${Math.round(os.totalmem() / 2 ** 30)} GiB`);

  const results = [];  // {size, renderer, summary}
  try {
    for (const size of options.sizes) {
      console.log(`\n=== ${size.label} (drawing-buffer pixels, deviceScaleFactor 1) ===`);
      const opened = new Map();
      // Obscura first: its framing of the model is the camera for three.js. The fog reaches FOG_AT_TARGET at the
      // camera target's distance.
      let fogDensity = 0;
      for (const r of renderers.filter((r) => r.kind === 'obscura')) {
        opened.set(r.id, await openObscura(browser, base, size, r, aoRadius, fogDensity));
        if (!fogDensity) {
          const c = parseCamera(opened.get(r.id).info.state);
          const distance = Math.hypot(...c.eye.map((e, i) => e - c.target[i]));
          fogDensity = Math.sqrt(-Math.log(1 - FOG_AT_TARGET)) / distance;
        }
      }
      const obscuraInfo = opened.get('obscura-ao').info;
      const camera = parseCamera(obscuraInfo.state);
      console.log(`Obscura ${obscuraInfo.context.version} on ${obscuraInfo.context.renderer}; scene ` +
                  `${obscuraInfo.scene.name}, ${obscuraInfo.scene.triangles} triangles; radius ${obscuraInfo.radius}, ` +
                  `antialias ${obscuraInfo.contextAttributes.antialias}`);
      console.log(`camera (Obscura's own framing, state()): eye (${v3(camera.eye)}) target (${v3(camera.target)}) ` +
                  `up (${v3(camera.up)}) fovy ${camera.fovy} near ${camera.near.toFixed(3)} far ${camera.far.toFixed(3)}`);
      // Obscura frames the model on the same sphere: its target is the centre.
      const targetOff = Math.hypot(...camera.target.map((t, i) => t - sphere.center[i]));
      if (targetOff > 1e-4 * sphere.radius) {
        failures.push(`${size.label}: Obscura's camera target is ${targetOff} units from the bounding sphere's centre`);
      }
      console.log(`fog (every-effect frames): exp2, density ${fogDensity.toExponential(4)} per model unit (` +
                  `${FOG_AT_TARGET * 100} % at the camera target), colour ${FOG_COLOR.join(', ')} linear`);
      for (const r of renderers.filter((r) => r.kind === 'obscura'))
        console.log(`  ${r.label}: state ${opened.get(r.id).info.settings}`);
      for (const r of renderers.filter((r) => r.kind === 'three')) {
        opened.set(r.id, await openThree(browser, base, size, r, camera, aoRadius, fogDensity));
      }
      for (const r of renderers) {
        const { info } = opened.get(r.id);
        const [w, h] = info.drawingBuffer;
        if (w !== size.width || h !== size.height) failures.push(`${r.id}: drawing buffer ${w}x${h}, not ${size.label}`);
        if (r.kind !== 'three') continue;
        const b = info.bounds;
        const radiusOff = Math.abs(b.radius - sphere.radius) / sphere.radius;
        const centreOff = Math.hypot(...b.center.map((c, i) => c - sphere.center[i])) / sphere.radius;
        if (radiusOff > 1e-5 || centreOff > 1e-5) {
          failures.push(`${r.id}: three.js's Box3 sphere (centre ${b.center}, radius ${b.radius}) differs from ` +
                        `glb-bounds.mjs's`);
        }
        if (r.id === renderers.find((x) => x.kind === 'three').id) {
          console.log(`three.js r${info.three}, ${info.webgl} on ${info.glRenderer}; Box3.setFromObject(model, true): ` +
                      `centre (${v3(b.center)}), radius ${b.radius.toFixed(4)} (agrees with glb-bounds.mjs)`);
        }
        console.log(`  ${r.label}: ${info.setup.pipeline}; antialias ${info.contextAttributes.antialias}`);
        if (info.setup.saoParams) {
          const p = info.setup.saoParams;
          console.log(`    SAOPass params: kernelRadius ${f2(p.saoKernelRadius)} px, scale ${p.saoScale.toFixed(3)}, ` +
                      `intensity ${p.saoIntensity.toFixed(5)}, bias ${p.saoBias.toFixed(3)}, blur ${p.saoBlur} ` +
                      `(radius ${p.saoBlurRadius}, std dev ${p.saoBlurStdDev}, depth cutoff ${p.saoBlurDepthCutoff}), ` +
                      `resolution ${info.setup.saoResolution.join('x')}`);
        }
        if (info.setup.configuration) {
          const c = info.setup.configuration;
          console.log(`    N8AO configuration: aoRadius ${c.aoRadius.toFixed(4)}, distanceFalloff ${c.distanceFalloff}, ` +
                      `intensity ${c.intensity}, aoSamples ${c.aoSamples}, denoiseSamples ${c.denoiseSamples}, ` +
                      `denoiseRadius ${c.denoiseRadius}, denoiseIterations ${c.denoiseIterations}, halfRes ` +
                      `${c.halfRes}, screenSpaceRadius ${c.screenSpaceRadius}, gammaCorrection ${c.gammaCorrection}, ` +
                      `neuralDenoise ${c.neuralDenoise}, accumulate ${c.accumulate}`);
        }
      }

      // Warm-up (shader compilation, first uploads), then the round-robin.
      for (const r of renderers) {
        const { times, error } = await opened.get(r.id).page.evaluate(timeFrames, options.warmup);
        if (error !== 0) failures.push(`${size.label} ${r.id}: GL error 0x${error.toString(16)} after the warm-up`);
        console.log(`  warm-up ${pad(r.id, 16)} ${times.map(f2).join(' ')} ms`);
        const after = await opened.get(r.id).page.evaluate(() => window.benchAfterWarmup?.() ?? null);
        if (after) console.log(`    after warm-up: ${JSON.stringify(after)}`);
        // The passes one frame runs (pass-counter.mjs), counted the same way for every renderer.
        opened.get(r.id).passes = await opened.get(r.id).page.evaluate(() => {
          window.benchPasses.reset();
          window.benchDraw();
          return window.benchPasses.read();
        });
      }
      const times = new Map(renderers.map((r) => [r.id, []]));
      const perRound = new Map(renderers.map((r) => [r.id, []]));  // each round's frames, for per-round ratios
      const started = Date.now(), loadBefore = os.loadavg()[0];
      for (let round = 0; round < options.rounds; ++round) {
        for (let k = 0; k < renderers.length; ++k) {
          const r = renderers[(round + k) % renderers.length];
          const turn = await opened.get(r.id).page.evaluate(timeFrames, options.frames);
          if (turn.error !== 0) failures.push(`${size.label} ${r.id}: GL error 0x${turn.error.toString(16)}`);
          times.get(r.id).push(...turn.times);
          perRound.get(r.id)[round] = turn.times;
        }
      }
      // The machine's 1-minute load average before and after (2 cores: above ~2, something else competed).
      console.log(`  ${options.rounds} rounds in ${((Date.now() - started) / 1000).toFixed(1)} s; load average ` +
                  `${loadBefore.toFixed(2)} before, ${os.loadavg()[0].toFixed(2)} after`);
      for (const r of renderers) {
        results.push({ size: size.label, renderer: r, summary: summarise(times.get(r.id)), rounds: perRound.get(r.id),
                       passes: opened.get(r.id).passes });
      }

      // Screenshots: one more frame each, then what the window shows.
      const facts = new Map(), pngs = new Map();
      for (const r of renderers) {
        const { page } = opened.get(r.id);
        await page.evaluate(() => window.benchDraw());
        const file = path.join(options.shots, `${size.label}-${r.id}.png`);
        const png = await page.screenshot({ path: file });
        pngs.set(r.id, png);
        facts.set(r.id, imageFacts(png, r.kind === 'obscura' ? await obscuraMask(page) : null));
      }
      const reference = facts.get('obscura-off');
      for (const r of renderers) {
        const fact = facts.get(r.id);
        const iou = intersectionOverUnion(fact.mask, reference.mask);
        const counterpart = r.checks === false ? null : AO_OFF_COUNTERPART[r.id];
        const darker = counterpart ? 1 - fact.meanLuminance / facts.get(counterpart).meanLuminance : null;
        const ao = counterpart ? aoDarkening(pngs.get(r.id), pngs.get(counterpart), facts.get(counterpart).mask)
                               : null;
        if (ao) fs.writeFileSync(path.join(options.shots, `${size.label}-${r.id}-ao-x8.png`), ao.image);
        console.log(`  image ${pad(r.id, 16)} model covers ${(fact.coverage * 100).toFixed(1)} %, mean luminance ` +
                    `${fact.meanLuminance.toFixed(3)}, background ${fact.background}, overlap with Obscura AO off ` +
                    `${(iou * 100).toFixed(1)} %` +
                    (ao ? `; vs ${counterpart}: ${(darker * 100).toFixed(1)} % darker on average, ` +
                          `${(ao.visibleShare * 100).toFixed(1)} % of the model's pixels >= 4/255 darker` : ''));
        if (r.checks === false) continue;
        if (fact.coverage < 0.05) failures.push(`${size.label} ${r.id}: the model covers only ${fact.coverage} of the frame`);
        if (iou < 0.9) failures.push(`${size.label} ${r.id}: framing differs from Obscura's (overlap ${iou})`);
        // AO must show somewhere (Obscura's defaults darken little on a centimetre model: docs/benchmarks.md).
        if (ao && !(ao.visibleShare > 0.01)) {
          failures.push(`${size.label} ${r.id}: no visible AO (${(ao.visibleShare * 100).toFixed(2)} % of the model's ` +
                        `pixels >= 4/255 darker than ${counterpart})`);
        }
      }
      for (const { context, page } of opened.values()) {
        failures.push(...page.errors);
        await context.close();
      }
    }
  } finally {
    await browser.close();
    server.stop();
  }

  // --- Report ----------------------------------------------------------------------------------------------------
  const median = (size, id) => results.find((x) => x.size === size && x.renderer.id === id)?.summary.median;
  // The ratio within each round (the two renderers measured seconds apart), then the median over the rounds: less
  // sensitive than the ratio of the medians to the load of the shared machine changing during the run.
  const perRoundRatio = (size, a, b) => {
    const ra = results.find((x) => x.size === size && x.renderer.id === a).rounds;
    const rb = results.find((x) => x.size === size && x.renderer.id === b).rounds;
    const middle = (values) => summarise(values).median;
    return middle(ra.map((frames, k) => middle(frames) / middle(rb[k])));
  };
  console.log('\nMedian ms per frame (draw + finish + 1-pixel readPixels) [q1 .. q3], fastest frame, frames; passes per ' +
              'frame: full-screen + geometry (pass-counter.mjs)');
  console.log('| renderer | ' + options.sizes.map((s) => s.label).join(' | ') + ' |');
  console.log('|---|' + options.sizes.map(() => '---|').join(''));
  const passesOf = (size, id) => {
    const p = results.find((y) => y.size === size && y.renderer.id === id).passes;
    return `${p.fullscreen} + ${p.geometry}`;
  };
  for (const r of renderers) {
    const cells = options.sizes.map((s) => {
      const x = results.find((y) => y.size === s.label && y.renderer.id === r.id).summary;
      return `**${f2(x.median)}** [${f2(x.q1)} .. ${f2(x.q3)}], ${f2(x.min)}, ${x.frames}; ${passesOf(s.label, r.id)}`;
    });
    console.log(`| ${r.label} | ${cells.join(' | ')} |`);
  }
  const ratioRows = [];
  console.log('\nRatios of the medians (in brackets: the median of the per-round ratios)');
  console.log('| ratio | ' + options.sizes.map((s) => s.label).join(' | ') + ' |');
  console.log('|---|' + options.sizes.map(() => '---|').join(''));
  for (const [a, b, targets] of RATIOS) {
    if (!renderers.some((r) => r.id === a) || !renderers.some((r) => r.id === b)) continue;
    const label = (id) => renderers.find((r) => r.id === id).label;
    const cells = options.sizes.map((s) => {
      const value = median(s.label, a) / median(s.label, b);
      const target = targets ? (targets[s.label] ?? targets['*'] ?? null) : null;
      const rounds = perRoundRatio(s.label, a, b);
      ratioRows.push({ size: s.label, numerator: a, denominator: b, value, rounds, target,
                       a: median(s.label, a), b: median(s.label, b) });
      const verdict = target === null ? '' : value <= target ? `; target <= ${target}: met` : `; target <= ${target}: not met`;
      return `**${f2(value)}** [${f2(rounds)}] (${f2(median(s.label, a))} ms, ${passesOf(s.label, a)} / ` +
             `${f2(median(s.label, b))} ms, ${passesOf(s.label, b)}${verdict})`;
    });
    console.log(`| ${label(a)} / ${label(b)} | ${cells.join(' | ')} |`);
  }
  // AO cost alone: the frame minus the same renderer's frame without AO (a difference of medians).
  for (const s of options.sizes) {
    const obscura = median(s.label, 'obscura-ao') - median(s.label, 'obscura-off');
    const n8ao = median(s.label, 'three-env-n8ao') - median(s.label, 'three-env-plain');
    console.log(`AO alone at ${s.label} (difference of medians): Obscura ${f2(obscura)} ms, N8AO ${f2(n8ao)} ms ` +
                `(frame minus three.js plain, RoomEnvironment), ratio ${f2(obscura / n8ao)}`);
  }

  const when = new Date().toISOString();
  fs.mkdirSync(path.dirname(options.csv), { recursive: true });
  const lines = ['date,size,renderer,label,frames,median_ms,q1_ms,q3_ms,min_ms,max_ms,fullscreen_passes,geometry_passes'];
  for (const { size, renderer, summary: x, passes } of results) {
    lines.push([when, size, renderer.id, `"${renderer.label}"`, x.frames, f2(x.median), f2(x.q1), f2(x.q3), f2(x.min),
                f2(x.max), passes.fullscreen, passes.geometry].join(','));
  }
  fs.writeFileSync(options.csv, lines.join('\n') + '\n');
  const ratiosCsv = options.csv.replace(/\.csv$/, '') + '-ratios.csv';
  fs.writeFileSync(ratiosCsv, ['date,size,numerator,denominator,ratio,per_round_ratio,numerator_ms,denominator_ms,target']
    .concat(ratioRows.map((x) => [when, x.size, x.numerator, x.denominator, x.value.toFixed(3), x.rounds.toFixed(3),
                                  f2(x.a), f2(x.b), x.target ?? ''].join(','))).join('\n') + '\n');
  // Every frame's time, by size, renderer and round, for a closer look.
  const raw = path.join(options.shots, 'browser-bench-frames.json');
  fs.writeFileSync(raw, JSON.stringify({ date: when, options: { ...options, sizes: options.sizes.map((x) => x.label) },
                                         results: results.map((x) => ({ size: x.size, renderer: x.renderer.id,
                                                                        rounds: x.rounds })) }) + '\n');
  console.log(`\nwrote ${path.relative(process.cwd(), options.csv)}, ${path.relative(process.cwd(), ratiosCsv)}, ` +
              `${path.relative(process.cwd(), raw)}; ` +
              `screenshots in ${path.relative(process.cwd(), options.shots)}/`);

  if (failures.length) {
    console.error(`\nFAILED checks:\n  ${failures.join('\n  ')}`);
    process.exitCode = 1;
  }
}

main().catch((error) => {
  console.error(error.stack ?? String(error));
  process.exitCode = 1;
});
