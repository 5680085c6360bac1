// Obscura's npm package (obscura-webgl) as its users get it: `npm pack` of the web build's package folder, installed
// from the tarball into a scratch project, its TypeScript declarations checked by tsc on a consumer, bundled by
// esbuild, and loaded in headless Chromium both ways: the example page examples/web (a plain <script type="module">
// with an import map; several instances sized by CSS beside other content; the page's own WebGL geometry with
// Obscura's AO), and the bundle.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { after, before, describe, test } from 'node:test';
import { chromium } from 'playwright-core';
import { chromiumLaunchOptions } from '../../tools/headless-chromium.mjs';
import { startServer } from '../../tools/serve-web.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const sourceDir = path.resolve(here, '..', '..');
const npmDir = process.env.OBSCURA_NPM_DIR ?? path.join(sourceDir, 'build-web', 'npm');
const bin = (name) => path.join(here, 'node_modules', '.bin', name);
const run = (command, args, cwd) => execFileSync(command, args, { cwd, encoding: 'utf8', stdio: 'pipe' });

let work;
let project;
let server;
let browser;

async function openPage(url) {
  const page = await (await browser.newContext({ viewport: { width: 800, height: 600 }, deviceScaleFactor: 0.5 }))
    .newPage();
  page.errors = [];
  page.on('console', (m) => {
    if (m.type() === 'error' || /GL_INVALID_|WebGL: INVALID_/.test(m.text())) page.errors.push(m.text());
  });
  page.on('pageerror', (e) => page.errors.push(`uncaught: ${e.message}`));
  page.on('response', (r) => {
    if (r.status() >= 400) page.errors.push(`HTTP ${r.status()} for ${r.url()}`);
  });
  await page.goto(url);
  await page.waitForFunction(() => document.body.dataset.ready === 'true', null, { timeout: 90000 });
  return page;
}

describe('the npm package', () => {
  before(() => {
    assert.ok(fs.existsSync(path.join(npmDir, 'obscura-core.wasm')),
              `${npmDir} has no obscura-core.wasm: build the web version first (tools/build-web.sh)`);
    work = fs.mkdtempSync(path.join(os.tmpdir(), 'obscura-npm-'));
    project = path.join(work, 'project');
    fs.mkdirSync(project);
  });
  after(async () => {
    await browser?.close();
    server?.stop();
    if (work) fs.rmSync(work, { recursive: true, force: true });
  });

  test('npm pack makes a tarball with the module, the .wasm, the decoders, the declarations, a README and a license', () => {
    const [packed] = JSON.parse(run('npm', ['pack', npmDir, '--json', '--pack-destination', work], work));
    const files = packed.files.map((f) => f.path).sort();
    assert.deepEqual(files, ['LICENSE', 'README.md', 'decoders/draco_decoder.wasm', 'decoders/draco_decoder_nodejs.js',
                             'decoders/meshopt_decoder.module.js', 'gltf-decoders.js', 'obscura-core.js',
                             'obscura-core.wasm', 'obscura.d.ts', 'obscura.js', 'obscura_gbuffer.glsl',
                             'package.json']);
    const manifest = JSON.parse(fs.readFileSync(path.join(npmDir, 'package.json'), 'utf8'));
    assert.match(manifest.version, /^\d+\.\d+\.\d+$/);
    assert.equal(manifest.exports['.'].types, './obscura.d.ts');
    // Installed from the tarball alone: no registry needed (the package has no dependencies).
    fs.writeFileSync(path.join(project, 'package.json'),
                     JSON.stringify({ name: 'consumer', private: true, type: 'module' }));
    run('npm', ['install', '--offline', '--no-audit', '--no-fund', '--loglevel=error',
                path.join(work, packed.filename)], project);
    assert.ok(fs.existsSync(path.join(project, 'node_modules', 'obscura-webgl', 'obscura-core.wasm')));
  });

  test('the TypeScript declarations describe the whole API (tsc --noEmit --strict on a consumer)', () => {
    fs.copyFileSync(path.join(here, 'consumer.ts'), path.join(project, 'consumer.ts'));
    fs.writeFileSync(path.join(project, 'tsconfig.json'), JSON.stringify({
      compilerOptions: { target: 'ES2022', module: 'ESNext', moduleResolution: 'Bundler', strict: true, noEmit: true,
                         lib: ['ES2022', 'DOM'], skipLibCheck: false, types: [] },
      files: ['consumer.ts'],
    }));
    run(bin('tsc'), ['-p', project], project);
    // A misuse is caught: the declarations are not `any`.
    fs.writeFileSync(path.join(project, 'wrong.ts'),
                     "import { createObscura } from 'obscura-webgl';\n" +
                     "const o = await createObscura(document.createElement('canvas'));\n" +
                     'o.set(42, 1);\nexport {};\n');
    assert.throws(() => run(bin('tsc'), ['--noEmit', '--strict', '--moduleResolution', 'Bundler', '--module', 'ESNext',
                                         '--target', 'ES2022', '--lib', 'ES2022,DOM', 'wrong.ts'], project),
                  (error) => /wrong\.ts\(3,7\): error TS2345/.test(error.stdout));
  });

  test('a bundle made by esbuild from the package name draws', { timeout: 180000 }, async () => {
    const dist = path.join(project, 'dist');
    fs.mkdirSync(dist);
    fs.writeFileSync(path.join(project, 'bundled.js'),
                     "import { createObscura } from 'obscura-webgl';\n" +
                     "const canvas = document.querySelector('canvas');\n" +
                     'window.obscura = await createObscura(canvas, { checkGlErrors: true });\n' +
                     "document.body.dataset.ready = 'true';\n");
    run(bin('esbuild'), ['bundled.js', '--bundle', '--format=esm', '--outfile=dist/bundled.js', '--log-level=error'],
        project);
    // esbuild leaves `new URL('./obscura-core.wasm', import.meta.url)` as it is: the .wasm goes beside the bundle.
    fs.copyFileSync(path.join(project, 'node_modules', 'obscura-webgl', 'obscura-core.wasm'),
                    path.join(dist, 'obscura-core.wasm'));
    fs.writeFileSync(path.join(dist, 'index.html'),
                     '<!doctype html><html><head><link rel="icon" href="data:,"></head><body>' +
                     '<canvas style="width: 320px; height: 200px"></canvas>' +
                     '<script type="module" src="bundled.js"></script></body></html>');
    server = await startServer(project);
    browser = await chromium.launch(chromiumLaunchOptions);
    const page = await openPage(`http://127.0.0.1:${server.address().port}/dist/index.html`);
    await page.waitForFunction(() => window.obscura.stats().frames > 0, null, { timeout: 90000, polling: 100 });
    const stats = await page.evaluate(() => window.obscura.stats());
    assert.equal(stats.width, 160);
    assert.equal(stats.height, 100);
    assert.equal(stats.error, '');
    assert.deepEqual(page.errors, []);
  });

  test('the example page: several instances sized by CSS beside other content, and AO on the page\'s own geometry',
       { timeout: 300000 }, async (t) => {
    for (const file of ['index.html', 'own-geometry.js']) {
      fs.copyFileSync(path.join(sourceDir, 'examples', 'web', file), path.join(project, file));
    }
    const page = await openPage(`http://127.0.0.1:${server.address().port}/index.html?debug-gl`);
    await page.waitForFunction(() => window.hero.stats().frames > 0 && window.aoOnly.stats().frames > 0 &&
                                     !window.hero.stats().pending && !window.aoOnly.stats().pending,
                               null, { timeout: 180000, polling: 200 });
    const shown = await page.evaluate(() => {
      const size = (id) => {
        const r = document.getElementById(id).getBoundingClientRect();
        return [Math.round(r.width * devicePixelRatio), Math.round(r.height * devicePixelRatio)];
      };
      const text = document.body.innerText;
      return {
        hero: window.hero.stats(), aoOnly: window.aoOnly.stats(), heroSize: size('hero'), aoOnlySize: size('ao-only'),
        views: [window.hero.view, window.aoOnly.view], radius: window.aoOnly.get('ao.radius'), text,
      };
    });
    assert.match(shown.text, /Three WebGL 1 canvases/);
    // Each instance follows its own canvas's CSS size (x devicePixelRatio 0.5), and keeps its own parameters.
    assert.deepEqual([shown.hero.width, shown.hero.height], shown.heroSize);
    assert.deepEqual([shown.aoOnly.width, shown.aoOnly.height], shown.aoOnlySize);
    assert.notDeepEqual(shown.heroSize, shown.aoOnlySize);
    assert.deepEqual(shown.views, ['final', 'ao']);
    assert.equal(shown.radius, '0.5');
    assert.equal(shown.hero.error, '');
    assert.equal(shown.aoOnly.error, '');

    // Resizing by CSS resizes one instance's drawing buffer and not the other's.
    await page.evaluate(() => { document.getElementById('hero').style.width = '50%'; });
    await page.waitForFunction(() => window.hero.stats().width === Math.round(document.getElementById('hero')
      .getBoundingClientRect().width * devicePixelRatio) && !window.hero.stats().pending, null, { timeout: 90000 });
    assert.equal(await page.evaluate(() => window.aoOnly.stats().width), shown.aoOnly.width);

    // The own-geometry canvas: the page's colour, darkened by Obscura's AO where a box stands on the floor and not on
    // open floor; without the composite the two are lit alike.
    const own = await page.evaluate(() => {
      const { gl, draw, setAo, project, ao } = window.own;
      const read = ([x, y]) => {
        const p = new Uint8Array(4);
        gl.readPixels(x, gl.drawingBufferHeight - 1 - y, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, p);
        return p[0] + p[1] + p[2];
      };
      const contact = project([-1.0, 0.02, 0.06]), open = project([-0.6, 0, 2.2]);
      draw();
      const withAo = [read(contact), read(open)];
      setAo(false);
      const withoutAo = [read(contact), read(open)];
      setAo(true);
      const texture = draw();
      return { withAo, withoutAo, isTexture: texture instanceof WebGLTexture, stats: ao.stats(),
               error: gl.getError(), glsl: ao.gbufferGlsl.includes('vec4 obscuraGBuffer(') };
    });
    assert.ok(own.isTexture, 'ambientOcclusion returns a WebGLTexture');
    assert.ok(own.glsl);
    assert.equal(own.error, 0, 'no GL error on the shared context');
    assert.deepEqual(own.stats.passesRun.slice(0, 2), ['gbuffer', 'sao']);
    const [contactAo, openAo] = own.withAo, [contactLit, openLit] = own.withoutAo;
    t.diagnostic(`own geometry (R+G+B): contact ${contactAo} with AO, ${contactLit} without; open floor ${openAo}, ` +
                 `${openLit}; passes ${own.stats.passesRun.join(' ')}`);
    const artifacts = process.env.OBSCURA_BROWSER_ARTIFACTS;
    if (artifacts) {
      fs.mkdirSync(artifacts, { recursive: true });
      await page.screenshot({ path: path.join(artifacts, 'npm-example-page.png'), fullPage: true });
    }
    assert.ok(contactAo < contactLit * 0.85, `the contact is darkened: ${contactAo} against ${contactLit}`);
    assert.ok(openAo > openLit * 0.95, `open floor stays lit: ${openAo} against ${openLit}`);
    assert.deepEqual(page.errors, []);
  });
});
