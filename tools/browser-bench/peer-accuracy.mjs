// How close each renderer's AO comes to the ray-traced reference, Obscura's estimators beside three.js's SAOPass and
// N8AO, on the same views, radii and cameras. The AO of each comes from the browser (Obscura's page in its "ao" view,
// WebGL 1; three.js's passes in their AO-only debug outputs, WebGL 2; all on SwiftShader); the reference from
// obscura-reference (Embree, 256 rays per pixel); the figures from obscura-compare (docs/accuracy.md defines them).
// Pearson correlation is the fair figure across renderers: it does not depend on how strong each one's AO is made
// (N8AO's intensity 5, SAOPass's intensity), only on whether it darkens where the reference darkens.
//
// Usage: node tools/browser-bench/peer-accuracy.mjs [--size WxH] [--out DIR] [--csv FILE] [--build DIR]
//   (defaults 640x360; build/peer-accuracy: the images; bench-results/peer-accuracy.csv; build: where
//   obscura-reference and obscura-compare are, tools/build.sh). The site comes from tools/build-web.sh, or
//   OBSCURA_WEB_SITE.
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startServer } from '../serve-web.mjs';
import { chromiumLaunchOptions, fixedScaleUrl, parseOptions, parseSize } from '../headless-chromium.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, '..', '..');
const siteDir = process.env.OBSCURA_WEB_SITE ?? path.join(root, 'build-web', 'site');

// Each view: a model, its AO radius (5 % of the bounding sphere's diameter, as the browser benchmark uses, or the
// scene's default), and a camera (a file, or Obscura's own framing of the model when it loads it).
const VIEWS = [
  { name: 'engine', model: '/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb',
    radius: 41.8025 },
  { name: 'room-table', model: path.join(root, 'assets/scenes/room-mm.glb'), radius: 430,
    camera: path.join(root, 'assets/cameras/room-mm-table.json') },
];
const RENDERERS = [
  { id: 'obscura-gtao', label: 'Obscura, GTAO (default)', kind: 'obscura', estimator: 'gtao' },
  { id: 'obscura-sao', label: 'Obscura, SAO', kind: 'obscura', estimator: 'sao' },
  { id: 'obscura-hbao', label: 'Obscura, HBAO', kind: 'obscura', estimator: 'hbao' },
  { id: 'three-sao', label: 'three.js SAOPass', kind: 'three' },
  { id: 'three-n8ao', label: 'three.js N8AOPass', kind: 'three' },
];

const options = { size: '640x360', out: path.join(root, 'build', 'peer-accuracy'),
                  csv: path.join(root, 'bench-results', 'peer-accuracy.csv'), build: path.join(root, 'build') };
parseOptions(process.argv.slice(2), {
  '--size': (v) => { options.size = v; },
  '--out': (v) => { options.out = path.resolve(v); },
  '--csv': (v) => { options.csv = path.resolve(v); },
  '--build': (v) => { options.build = path.resolve(v); },
}, path.basename(import.meta.url));
const [width, height] = parseSize(options.size);
if (!(width > 0 && height > 0)) throw new Error('--size WxH');
fs.mkdirSync(options.out, { recursive: true });

// The camera in a state() text (eye, target, up, fovy, near, far), as obscura-reference's camera JSON.
function cameraJson(state) {
  const params = new URLSearchParams(state);
  const vector = (key) => params.get(key).split(',').map(Number);
  return { eye: vector('eye'), target: vector('target'), up: vector('up'), fovy_deg: Number(params.get('fovy')),
           near: Number(params.get('near')), far: Number(params.get('far')), width, height };
}

// In the page: the red channel of RGBA rows (top to bottom) as a grey PNG (data URL), sRGB-decoded if asked (the
// three.js passes encode their output for the canvas; Obscura's "ao" view writes the visibility as it is).
async function greyPng(page, pixels, decodeSrgb) {
  return page.evaluate(({ pixels, width, height, decodeSrgb }) => {
    const canvas = document.createElement('canvas');
    canvas.width = width;
    canvas.height = height;
    const context = canvas.getContext('2d');
    const image = context.createImageData(width, height);
    for (let i = 0; i < width * height; ++i) {
      let v = pixels[4 * i] / 255;
      if (decodeSrgb) v = v <= 0.04045 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4;
      const byte = Math.round(v * 255);
      image.data.set([byte, byte, byte, 255], 4 * i);
    }
    context.putImageData(image, 0, 0);
    return canvas.toDataURL('image/png');
  }, { pixels, width, height, decodeSrgb });
}

function writeDataUrl(file, url) {
  fs.writeFileSync(file, Buffer.from(url.slice(url.indexOf(',') + 1), 'base64'));
}

const server = await startServer(null, 0, { '/site/': siteDir, '/bench/': here });
const base = `http://127.0.0.1:${server.address().port}`;
const browser = await chromium.launch(chromiumLaunchOptions);
const rows = [];
try {
  for (const view of VIEWS) {
    const modelBytes = fs.readFileSync(view.model);
    let camera = null;
    for (const renderer of RENDERERS) {
      const context = await browser.newContext({ viewport: { width, height }, deviceScaleFactor: 1 });
      const page = await context.newPage();
      const errors = [];
      page.on('pageerror', (e) => errors.push(String(e)));
      await page.route(`${base}/model.glb`, (route) => route.fulfill({ body: modelBytes }));
      let pixels;
      if (renderer.kind === 'obscura') {
        await page.goto(fixedScaleUrl(`${base}/site/index.html`));
        await page.waitForFunction(() => document.body.dataset.ready === 'true', null, { timeout: 120000 });
        await page.addStyleTag({ content: '#panel { display: none !important; }' });
        const result = await page.evaluate(async ({ estimator, radius, camera, name }) => {
          const o = window.obscura;
          await o.loadScene(await (await fetch('/model.glb')).arrayBuffer(), `${name}.glb`);
          o.set('ao.radius', radius);
          o.set('ao.estimator', estimator);
          if (camera) {
            o.setState(`eye=${camera.eye}&target=${camera.target}&up=${camera.up}&fovy=${camera.fovy_deg}` +
                       `&near=${camera.near}&far=${camera.far}`);
          }
          o.setView('ao');
          const shot = o.snapshot();
          return { state: o.state(), pixels: Array.from(shot.pixels), width: shot.width, height: shot.height };
        }, { estimator: renderer.estimator, radius: view.radius, name: view.name,
             camera: view.camera ? JSON.parse(fs.readFileSync(view.camera, 'utf8')) : null });
        if (result.width !== width || result.height !== height) {
          throw new Error(`snapshot ${result.width}x${result.height}`);
        }
        camera ??= cameraJson(result.state);
        pixels = result.pixels;
      } else {
        await page.goto(`${base}/bench/three.html`);
        await page.waitForFunction(() => document.body.dataset.ready === 'true', null, { timeout: 120000 });
        const c = { eye: camera.eye, target: camera.target, up: camera.up, fovy: camera.fovy_deg, near: camera.near,
                    far: camera.far };
        await page.evaluate((o) => window.benchSetup(o),
                            { mode: renderer.id, modelUrl: '/model.glb', camera: c, aoRadius: view.radius,
                              aoOnly: true });
        // A few frames (N8AO settles its configuration on its first frames), then one read in the same task as its
        // draw, before the canvas is presented and cleared.
        pixels = await page.evaluate(() => {
          for (let i = 0; i < 3; ++i) window.benchDraw();
          window.benchDraw();
          const gl = window.benchGl;
          const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
          const bottomUp = new Uint8Array(w * h * 4);
          gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, bottomUp);
          const rows = new Uint8Array(w * h * 4);
          for (let y = 0; y < h; ++y) rows.set(bottomUp.subarray((h - 1 - y) * w * 4, (h - y) * w * 4), y * w * 4);
          return Array.from(rows);
        });
      }
      if (errors.length) throw new Error(`${renderer.id}: ${errors.join('; ')}`);
      writeDataUrl(path.join(options.out, `${view.name}-${renderer.id}.png`),
                   await greyPng(page, pixels, renderer.kind === 'three'));
      await context.close();
    }

    // The reference with the same camera, size and radius.
    const cameraFile = path.join(options.out, `${view.name}-camera.json`);
    fs.writeFileSync(cameraFile, JSON.stringify(camera, null, 2));
    const stem = path.join(options.out, `${view.name}-reference`);
    execFileSync(path.join(options.build, 'obscura-reference'),
                 ['--scene', view.model, '--camera', cameraFile, '--size', options.size,
                  '--radius', String(view.radius),
                  '--out', `${stem}.png`, '--mask-out', `${stem}-mask.png`, '--depth-out', `${stem}-depth.png`],
                 { stdio: ['ignore', 'ignore', 'inherit'] });
    console.log(`${view.name}: ${options.size}, r = ${view.radius}, eye (${camera.eye.map((x) => x.toFixed(1))}) ` +
                `target (${camera.target.map((x) => x.toFixed(1))})`);
    for (const renderer of RENDERERS) {
      const image = path.join(options.out, `${view.name}-${renderer.id}.png`);
      const figures = JSON.parse(execFileSync(path.join(options.build, 'obscura-compare'),
        [`${stem}.png`, image, '--mask', `${stem}-mask.png`, '--depth', `${stem}-depth.png`, '--halo-width', '4',
         '--side-by-side', path.join(options.out, `${view.name}-${renderer.id}-sbs.png`), '--json'],
        { encoding: 'utf8' }));
      rows.push({ view: view.name, renderer: renderer.id, ...figures });
      console.log(`  ${renderer.label.padEnd(26)} MAE ${figures.mae.toFixed(4)}  SSIM ${figures.ssim.toFixed(3)}  ` +
                  `Pearson ${figures.pearson.toFixed(3)}  halo ${figures.halo_mae.toFixed(4)}  ` +
                  `interior ${figures.interior_mae.toFixed(4)}`);
    }
  }
} finally {
  await browser.close();
  server.stop();
}
const header = 'view,renderer,mae,ssim,pearson,halo_mae,interior_mae';
const csv = [header, ...rows.map((r) => [r.view, r.renderer, r.mae, r.ssim, r.pearson, r.halo_mae, r.interior_mae]
  .join(','))].join('\n') + '\n';
fs.mkdirSync(path.dirname(options.csv), { recursive: true });
fs.writeFileSync(options.csv, csv);
console.log(`wrote the images in ${options.out} and the figures in ${options.csv}`);
