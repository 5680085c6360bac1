// The demo page end to end in headless Chromium (WebGL 1 on SwiftShader, GL errors checked after every pass):
// start-up without console errors, a WebGL 1 context, a picture that is not blank, the AO controls changing the
// image, the stats, loading a glTF file with a progress bar (and refusing a malformed one while keeping the previous
// scene), the URL reproducing a view (a changed preset included), and the page screenshots.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, describe, test } from 'node:test';
import { artifactDir, assimpModels, compareImages, fractionUnlike, luminanceStats, openPage, readModel, snapshot,
         sourceDir, startBrowser, waitForDrawn } from './harness.mjs';

let session;
let context;
let page;

describe('demo page', () => {
  before(async () => {
    session = await startBrowser();
    context = await session.newContext();
    page = await openPage(context, session.baseUrl);
  });
  after(async () => {
    if (page) assert.deepEqual(page.errors, [], 'console errors during the page tests');
    await session?.close();
  });

  test('starts without console errors on a WebGL 1 context', { timeout: 120000 }, async () => {
    const context = await page.evaluate(() => {
      const canvas = document.querySelector('#view');
      const gl = canvas.getContext('webgl');  // the context Obscura created, returned again
      return {
        api: window.obscura.context.version,
        isWebGl1: gl instanceof WebGLRenderingContext,
        isWebGl2: typeof WebGL2RenderingContext !== 'undefined' && gl instanceof WebGL2RenderingContext,
        version: gl.getParameter(gl.VERSION),
        antialias: gl.getContextAttributes().antialias,
        samples: gl.getParameter(gl.SAMPLES),
      };
    });
    assert.equal(context.isWebGl1, true);
    assert.equal(context.isWebGl2, false);
    assert.match(context.version, /^WebGL 1\.0/);
    assert.match(context.api, /WebGL 1\.0/);
    // Every pass draws into textures and FXAA antialiases: the canvas is not multisampled (effects/fxaa/FxaaEffect.h).
    assert.equal(context.antialias, false, 'the back buffer is not multisampled');
    assert.equal(context.samples, 0);
    assert.deepEqual(page.errors, []);
  });

  test('the canvas is not blank and follows the window size and devicePixelRatio', { timeout: 120000 }, async () => {
    const shot = await snapshot(page);
    assert.equal(shot.width, 320);
    assert.equal(shot.height, 180);
    const stats = luminanceStats(shot);
    assert.ok(stats.deviation > 0.05, `luminance deviation ${stats.deviation}`);
    assert.ok(stats.max - stats.min > 0.3, 'a range of tones');
    // What the browser composites (not only what the core reads back) is the scene too.
    const composited = await page.locator('#view').screenshot({ clip: { x: 0, y: 0, width: 300, height: 360 } });
    fs.writeFileSync(path.join(artifactDir, 'page-composited.png'), composited);
    assert.ok(composited.length > 5000, 'a screenshot with content compresses to more than a flat colour');

    // A resize alone brings a new frame at the new size.
    await page.setViewportSize({ width: 500, height: 300 });
    await page.waitForFunction(() => window.obscura.stats().width === 250 && window.obscura.stats().height === 150);
    await waitForDrawn(page);
    await page.setViewportSize({ width: 640, height: 360 });
    await page.waitForFunction(() => window.obscura.stats().width === 320);
  });

  test('the AO view differs from AO off, and AO only darkens', { timeout: 120000 }, async () => {
    await page.locator('#view-ao').check();
    const aoView = await snapshot(page);
    const aoStats = luminanceStats(aoView);
    assert.ok(aoStats.min < 0.5, `the AO view has occluded pixels (min ${aoStats.min})`);
    assert.ok(aoStats.max > 0.95, 'and open ones');

    await page.locator('#view-final').check();
    const withAo = await snapshot(page);
    await page.locator('#param-ao').uncheck();
    const withoutAo = await snapshot(page);
    await page.locator('#param-ao').check();

    const difference = compareImages(withAo, withoutAo);
    assert.ok(difference.r.differing > 0.1, `AO changes ${difference.r.differing} of the pixels`);
    assert.ok(luminanceStats(withoutAo).mean - luminanceStats(withAo).mean > 0.01, 'AO darkens the image');
    assert.notDeepEqual(aoView.pixels, withAo.pixels);
  });

  test('issue 30: ao.layers and gbuffer.normals through the page and the JS API', { timeout: 120000 }, async () => {
    await page.locator('#view-ao').check();
    const oneLayer = await snapshot(page);
    // The second depth layer, through the JS API: a peel pass more, and a different AO.
    await page.evaluate(() => window.obscura.set('ao.layers', '2'));
    assert.equal(await page.evaluate(() => window.obscura.get('ao.layers')), '2');
    const twoLayers = await snapshot(page);
    assert.ok(compareImages(oneLayer, twoLayers).r.differing > 0.01, 'two layers change the AO');
    // Normals from depth, through the page's control in the G-buffer's section.
    await page.locator('#effect-gbuffer #param-gbuffer-normals').selectOption('reconstructed');
    assert.equal(await page.evaluate(() => window.obscura.get('gbuffer.normals')), 'reconstructed');
    assert.ok(compareImages(twoLayers, await snapshot(page)).r.differing > 0.001, 'the reconstructed normals too');
    // The G-buffer's view of them.
    await page.locator('#view-normals-from-depth').check();
    assert.ok(luminanceStats(await snapshot(page)).max > 0.5, 'the normals-from-depth view draws');
    await page.evaluate(() => {
      window.obscura.set('ao.layers', '1');
      window.obscura.set('gbuffer.normals', 'stored');
    });
    await page.locator('#view-final').check();
  });

  test('gbuffer.lod through the page and the JS API: fewer triangles, the image within a level',
    { timeout: 120000 },
    async () => {
      // A snapshot draws a frame; the stats then count its geometry pass's triangles.
      const triangles = () => page.evaluate(() => window.obscura.stats().triangles);
      await page.evaluate(() => window.obscura.set('gbuffer.lod', '0'));
      const fullImage = await snapshot(page);
      const full = await triangles();
      // The box beside the slider, under the G-buffer's "more".
      const more = page.locator('#effect-gbuffer details.more');
      if (!(await more.evaluate((details) => details.open))) await more.locator('summary').click();
      const number = page.locator('#effect-gbuffer #param-gbuffer-lod + input');
      await number.fill('2');
      await number.dispatchEvent('change');
      assert.equal(await page.evaluate(() => window.obscura.get('gbuffer.lod')), '2');
      const difference = compareImages(fullImage, await snapshot(page));
      const coarse = await triangles();
      assert.ok(coarse < full, `${coarse} triangles at 2 pixels, ${full} in full detail`);
      assert.ok(difference.mean < 1, `the image moves by ${difference.mean} levels of 255 on average`);
      await page.evaluate(() => window.obscura.set('gbuffer.lod', '0'));
    });

  test('the panel groups the controls by effect, from the effect table', { timeout: 120000 }, async () => {
    const table = await page.evaluate(() => window.obscura.effects.map((e) => ({
      name: e.name, title: e.title, parameters: e.parameters })));
    const sections = await page.locator('#effects > details.effect').evaluateAll(
      (nodes) => nodes.map((n) => ({ id: n.id, title: n.querySelector('summary').textContent, open: n.open })));
    // One section per effect with parameters, in frame order, open, titled from the table.
    const withParameters = table.filter((e) => e.parameters.length);
    assert.deepEqual(sections.map((s) => s.id), withParameters.map((e) => `effect-${e.name}`));
    assert.deepEqual(sections.map((s) => s.title), withParameters.map((e) => e.title));
    assert.ok(sections.every((s) => s.open));
    for (const effect of withParameters) {
      for (const name of effect.parameters) {
        const id = `param-${name.replace(/\./g, '-')}`;
        assert.equal(await page.locator(`#effect-${effect.name} #${id}`).count(), 1, `${name} in its section`);
      }
    }
    // The switch sits in the heading; primary parameters up front, the rest under "more".
    assert.equal(await page.locator('#effect-tonemap > summary #param-tonemap').count(), 1);
    assert.equal(await page.locator('#effect-ao > .parameters #param-ao-radius').count(), 1);
    assert.equal(await page.locator('#effect-ao details.more #param-ao-turns').count(), 1);
    assert.equal(await page.locator('#param-ao-turns').isVisible(), false, '"more" starts folded');
    assert.equal(await page.locator('#frame-parameters #param-preset').count(), 1, "the frame's preset on top");
    // A colour (fog.color): a picker, whose sRGB value reaches the core as linear, and a text field for HDR values.
    await page.locator('#param-fog-color').fill('#ff0000');
    assert.equal(await page.evaluate(() => window.obscura.get('fog.color')), '1,0,0');
    assert.equal(await page.locator('#param-fog-color + input').inputValue(), '1,0,0');
    await page.locator('#param-fog-color + input').fill('2,1,0.5');
    await page.locator('#param-fog-color + input').press('Enter');
    assert.equal(await page.evaluate(() => window.obscura.get('fog.color')), '2,1,0.5');
    assert.equal(await page.locator('#param-fog-color').inputValue(), '#ffffbc', 'the picker shows it clamped, sRGB');
    await page.evaluate(() => window.obscura.set('fog.color', '0.5,0.6,0.7'));
    // The edges' controls (issue 16): the switch in the heading draws lines, the style turns the shading to bands.
    await page.locator('#view-final').check();
    const unlined = await snapshot(page);
    await page.locator('#param-edges').check();
    assert.equal(await page.evaluate(() => window.obscura.get('edges')), 'on');
    const lined = await snapshot(page);
    assert.ok(compareImages(unlined, lined).r.differing > 0.01, 'the lines change the image');
    await page.locator('#param-edges-style').selectOption('toon');
    assert.equal(await page.evaluate(() => window.obscura.get('edges.style')), 'toon');
    assert.ok(compareImages(lined, await snapshot(page)).r.differing > 0.1, 'the toon bands change the shading');
    await page.locator('#param-edges').uncheck();
    await page.evaluate(() => window.obscura.set('edges.style', 'lines'));

    // The controls act: an operator, the exposure, the switch in the heading; folding a section hides its controls.
    await page.locator('#view-final').check();
    const neutral = await snapshot(page);
    await page.locator('#param-tonemap-operator').selectOption('aces');
    assert.equal(await page.evaluate(() => window.obscura.get('tonemap.operator')), 'aces');
    const aces = await snapshot(page);
    assert.ok(compareImages(neutral, aces).r.differing > 0.3, 'another tone curve changes the image');
    await page.locator('#param-tonemap').uncheck();
    assert.equal(await page.evaluate(() => window.obscura.get('tonemap')), 'off');
    assert.equal(await page.locator('#effect-tonemap').evaluate((n) => n.open), true, 'the switch does not fold it');
    await page.locator('#param-tonemap').check();
    await page.locator('#param-tonemap-operator').selectOption('neutral');
    await page.locator('#effect-fxaa > summary').click({ position: { x: 12, y: 6 } });
    assert.equal(await page.locator('#param-fxaa-preset').isVisible(), false);
    await page.locator('#effect-fxaa > summary').click({ position: { x: 12, y: 6 } });
    assert.equal(await page.locator('#param-fxaa-preset').isVisible(), true);
    assert.deepEqual(page.errors, []);
  });

  test('moving the radius slider changes the AO image', { timeout: 120000 }, async () => {
    await page.locator('#view-ao').check();
    const before = await snapshot(page);
    const slider = page.locator('#param-ao-radius');
    const position = Number(await slider.inputValue());
    await slider.fill(String(position + 75));  // logarithmic, 1000 steps over 0.01 .. 100: x2 in radius
    const radius = Number(await page.evaluate(() => window.obscura.get('radius')));
    assert.ok(radius > 1.5 && radius < 3, `radius now ${radius}`);
    assert.equal(Number(await page.locator('#param-ao-radius + input').inputValue()), radius, 'the number box follows');
    const after = await snapshot(page);
    const difference = compareImages(before, after);
    assert.ok(difference.r.differing > 0.05, `${difference.r.differing} of the pixels changed`);
    assert.ok(luminanceStats(after).mean < luminanceStats(before).mean, 'a larger radius finds more occluders');
  });

  test("a slow parameter (the sun's elevation: the sky is made again) is applied when its slider is released",
    { timeout: 120000 }, async () => {
      const info = await page.evaluate(
        () => window.obscura.parameters.find((p) => p.name === 'lighting.sun-elevation'));
      assert.equal(info.slow, true);
      assert.equal(await page.evaluate(
        () => window.obscura.parameters.find((p) => p.name === 'lighting.sun-azimuth').slow), false);
      const before = await page.evaluate(() => window.obscura.get('lighting.sun-elevation'));
      const slider = page.locator('#param-lighting-sun-elevation');
      // A drag: 'input' events only. The number box follows; the renderer keeps the old value.
      await slider.evaluate((s) => {
        s.value = String(Number(s.value) - 200);
        s.dispatchEvent(new Event('input', { bubbles: true }));
      });
      const shown = Number(await page.locator('#param-lighting-sun-elevation + input').inputValue());
      assert.notEqual(shown, Number(before));
      assert.equal(await page.evaluate(() => window.obscura.get('lighting.sun-elevation')), before);
      // The release: 'change'.
      await slider.evaluate((s) => s.dispatchEvent(new Event('change', { bubbles: true })));
      assert.equal(Number(await page.evaluate(() => window.obscura.get('lighting.sun-elevation'))), shown);
      await page.evaluate((value) => window.obscura.set('lighting.sun-elevation', value), before);
      assert.deepEqual(page.errors, []);
    });

  test('keyboard shortcuts are listed and act', { timeout: 120000 }, async () => {
    const listed = await page.locator('#shortcuts td:first-child').allTextContents();
    // As a person reads them: 'space', 'left arrow' (keyBindings' labels), the others as typed.
    const bindings = await page.evaluate(() => window.obscura.keyBindings.map((b) => b.label));
    for (const key of [...bindings, 'h', 'o']) assert.ok(listed.includes(key), `shortcut ${key} is listed`);
    assert.ok(listed.includes('space') && listed.includes('right arrow'), listed.join(' '));
    const radius = Number(await page.evaluate(() => window.obscura.get('radius')));
    await page.locator('#view').click({ position: { x: 100, y: 100 } });
    await page.keyboard.press(']');
    const larger = Number(await page.evaluate(() => window.obscura.get('radius')));
    assert.equal(larger, Number((radius * 1.25).toPrecision(7)));
    await page.keyboard.press('1');
    assert.equal(await page.locator('#view-final').isChecked(), true);
    await page.keyboard.press('h');
    assert.equal(await page.locator('#panel-body').isVisible(), false);
    await page.keyboard.press('h');
    assert.equal(await page.locator('#panel-body').isVisible(), true);
  });

  test('stats show frame times, and per-pass GPU times where EXT_disjoint_timer_query exists',
       { timeout: 120000 }, async () => {
    // Drawn on change only: the stats show the last drawn frame's time in the renderer, as measured.
    await page.evaluate(() => {
      window.obscura.setView('depth');
      window.obscura.setView('final');
    });
    await waitForDrawn(page);
    const drawn = await page.evaluate(() => window.obscura.stats());
    assert.ok(drawn.lastCpuMs > 0, `last frame ${drawn.lastCpuMs} ms`);
    assert.ok(drawn.lastHostMs > 0 && drawn.lastHostMs <= drawn.lastCpuMs, `host ${drawn.lastHostMs} ms`);
    await page.waitForFunction((ms) => document.querySelector('#stats').textContent
      .includes(`host   ${ms} ms in the renderer, last frame`), drawn.lastHostMs.toFixed(2));
    if (drawn.frameMs === 0) {
      assert.match(await page.locator('#stats').textContent(), /frame {2}- \(drawn on change only/);
    }
    const timerQuery = await page.evaluate(() => window.obscura.context.timerQuery);
    if (timerQuery) {
      await page.waitForFunction(() => window.obscura.stats().passMs !== null, null, { timeout: 30000 });
      const { passMs: passes, passesDoneBy } = await page.evaluate(() => window.obscura.stats());
      for (const pass of ['gbuffer', 'sao', 'lighting', 'fxaa']) assert.ok(passes[pass] > 0, `${pass}: ${passes[pass]} ms`);
      // Nothing else reads the HDR colour at the defaults: the lighting applies the tone curve, and the page says so.
      assert.equal(passes.tonemap, null);
      assert.deepEqual(passesDoneBy, { tonemap: 'lighting', dither: 'lighting' });
      await page.waitForFunction(() => /tonemap +- ms \(done by lighting\)/.test(document.querySelector('#stats').textContent));
    } else {
      await page.waitForFunction(() => document.querySelector('#stats').textContent.includes('needs EXT_disjoint'));
    }
    // Frames are drawn on change only; continuous mode draws back to back, which gives the frame time.
    await page.locator('#continuous').check();
    await page.waitForFunction((before) => window.obscura.stats().frames >= before + 3, drawn.frames,
                               { timeout: 60000 });
    await page.locator('#continuous').uncheck();
    const stats = await page.evaluate(() => window.obscura.stats());
    assert.ok(stats.frameMs > 0, 'frame time measured');
    await page.waitForFunction(() => /frame +\d+\.\d ms \(\d+ fps\)/
      .test(document.querySelector('#stats').textContent));
    await waitForDrawn(page);
    const idle = await page.evaluate(() => window.obscura.stats().frames);
    await page.waitForTimeout(500);
    assert.equal(await page.evaluate(() => window.obscura.stats().frames), idle, 'no frames drawn without a change');
  });

  test('a malformed file shows an error and leaves the previous scene on screen', { timeout: 120000 }, async () => {
    const before = await snapshot(page);
    await page.locator('#file-input').setInputFiles(path.join(assimpModels, 'BoxWithInfinites-glTF-Binary',
                                                              'BoxWithInfinites.glb'));
    await page.locator('#error').waitFor({ state: 'visible', timeout: 30000 });
    assert.match(await page.locator('#error').textContent(),
                 /BoxWithInfinites\.glb: mesh 0 primitive 0 POSITION 0 is not finite/);
    assert.match(await page.locator('#scene-name').textContent(), /^built-in scene/);
    assert.deepEqual((await snapshot(page)).pixels, before.pixels, 'the previous scene is still drawn');

    // The same by drag and drop, with a .gltf and its buffer dropped together (indices out of range).
    const files = ['IndexOutOfRange.gltf', 'IndexOutOfRange.bin'].map((name) => ({
      name, base64: readModel(`IndexOutOfRange/${name}`).toString('base64') }));
    await page.evaluate((list) => {
      const transfer = new DataTransfer();
      for (const { name, base64 } of list) {
        transfer.items.add(new File([Uint8Array.from(atob(base64), (c) => c.charCodeAt(0))], name));
      }
      for (const type of ['dragenter', 'dragover', 'drop']) {
        window.dispatchEvent(new DragEvent(type, { dataTransfer: transfer, bubbles: true, cancelable: true }));
      }
    }, files);
    await page.waitForFunction(() => document.querySelector('#error').textContent.includes('IndexOutOfRange.gltf'),
                               null, { timeout: 30000 });
    assert.match(await page.locator('#error').textContent(), /index 255 but only 24 vertices/);
    assert.equal(await page.locator('#drop-overlay').isVisible(), false);
    assert.deepEqual((await snapshot(page)).pixels, before.pixels, 'still the built-in scene');
  });

  test('an .hdr file opened becomes the environment, and the list goes back to the sky', { timeout: 120000 },
    async () => {
      const sky = await snapshot(page);
      // A 16 x 8 Radiance file, flat RGBE (stb reads unencoded scanlines): radiance (2, 0.5, 0.5) everywhere, bytes
      // floor(c 2^(8 - 2)) with the exponent 2 + 128.
      const header = Buffer.from('#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 16\n');
      const texels = Buffer.alloc(16 * 8 * 4);
      for (let i = 0; i < texels.length; i += 4) texels.set([128, 32, 32, 130], i);
      await page.locator('#file-input').setInputFiles({ name: 'red.hdr', mimeType: 'application/octet-stream',
                                                         buffer: Buffer.concat([header, texels]) });
      await page.waitForFunction(() => window.obscura.get('lighting.environment') === '/environments/red.hdr', null,
                                 { timeout: 60000 });
      assert.equal(await page.locator('#param-lighting-environment').inputValue(), '/environments/red.hdr');
      await waitForDrawn(page);
      const red = await snapshot(page);
      const difference = compareImages(sky, red);
      assert.ok(difference.r.differing > 0.5, `the environment lights the scene and fills the background (${
        difference.r.differing})`);
      assert.match(await page.locator('#scene-name').textContent(), /^built-in scene/, 'the scene stays');

      await page.locator('#param-lighting-environment').selectOption('sky');
      assert.equal(await page.evaluate(() => window.obscura.get('lighting.environment')), 'sky');
      await waitForDrawn(page);
      assert.deepEqual((await snapshot(page)).pixels, sky.pixels, 'the sky again');

      // The prefiltered levels in an atlas (no EXT_shader_texture_lod) give the image the mip chain gives.
      const layout = await page.evaluate(() => window.obscura.setEnvironmentLayout('mipchain'));
      await waitForDrawn(page);
      const fromMips = await snapshot(page);
      assert.equal(await page.evaluate(() => window.obscura.setEnvironmentLayout('atlas')), 'atlas');
      await waitForDrawn(page);
      const fromAtlas = await snapshot(page);
      // Half floats the hardware filters (the default where OES_texture_half_float_linear exists): the same levels,
      // rounded to 11 significant bits where RGB9E5 keeps 9.
      const half = await page.evaluate(() => window.obscura.setEnvironmentLayout('halffloat'));
      await waitForDrawn(page);
      const fromHalf = await snapshot(page);
      const auto = await page.evaluate(() => window.obscura.setEnvironmentLayout('auto'));
      const between = compareImages(fromMips, fromAtlas);
      const halfAgainstAtlas = compareImages(fromHalf, fromAtlas);
      let overOne = 0;
      for (let i = 0; i < fromHalf.pixels.length; i += 4) {
        if ([0, 1, 2].some((c) => Math.abs(fromHalf.pixels[i + c] - fromAtlas.pixels[i + c]) > 1)) overOne += 1;
      }
      const overOneFraction = overOne / (fromHalf.width * fromHalf.height);
      console.log(`environment layouts on WebGL 1: ${layout} against atlas, largest difference ${between.r.max}, ` +
                  `${between.g.max}, ${between.b.max} of 255; ${half} against atlas ${halfAgainstAtlas.r.max}, ` +
                  `${halfAgainstAtlas.g.max}, ${halfAgainstAtlas.b.max}, ${overOne} pixels ` +
                  `(${(100 * overOneFraction).toFixed(3)} %) more than 1 apart; auto is ${auto}`);
      assert.ok(Math.max(between.r.max, between.g.max, between.b.max) <= 1, 'the same texels, filtered alike');
      assert.equal(half, 'halffloat', 'SwiftShader filters half floats');
      assert.equal(auto, 'halffloat', 'the half-float atlas is the default where the context has it');
      // Within a level of 255 but at the sun's rim, where the hardware's filter weights (fewer fractional bits than
      // the hand filter's floats) blend the disc's 40 with the sky's 1: 4 pixels (0.007 %), up to 6 levels, here.
      assert.ok(overOneFraction <= 0.0005, 'half floats filtered by the hardware give the image RGB9E5 filtered by ' +
                `hand gives: ${overOne} pixels more than a level apart`);
      assert.ok(Math.max(halfAgainstAtlas.r.max, halfAgainstAtlas.g.max, halfAgainstAtlas.b.max) <= 12,
                'and nowhere far apart');
    });

  test('loading 2CylinderEngine.glb with the file picker shows it, with a progress bar meanwhile',
       { timeout: 120000 }, async () => {
    const builtin = await snapshot(page);
    // Every state the progress bar goes through, recorded as it changes (a load is over too soon to poll).
    await page.evaluate(() => {
      const progress = document.querySelector('#load-progress');
      window.progressSeen = [];
      new MutationObserver(() => window.progressSeen.push({ hidden: progress.hidden, value: progress.value }))
        .observe(progress, { attributes: true, attributeFilter: ['hidden', 'value'] });
    });
    await page.locator('#file-input').setInputFiles(path.join(assimpModels, '2CylinderEngine-glTF-Binary',
                                                              '2CylinderEngine.glb'));
    await page.waitForFunction(
      () => document.querySelector('#scene-name').textContent.startsWith('2CylinderEngine.glb'), null,
      { timeout: 60000 });
    assert.equal(await page.locator('#error').isVisible(), false);
    assert.equal(await page.locator('#load-progress').isVisible(), false, 'the progress bar is gone when done');
    const seen = await page.evaluate(() => window.progressSeen);
    assert.ok(seen.some((s) => !s.hidden), `the progress bar was shown during the load: ${JSON.stringify(seen)}`);
    assert.ok(seen.some((s) => !s.hidden && s.value === 1), 'and reached the end of the reading');
    assert.equal(seen.at(-1).hidden, true, 'its last change hid it');
    const scene = await page.evaluate(() => window.obscura.scene());
    assert.ok(scene.triangles > 100000, `${scene.triangles} triangles`);
    await page.locator('#view-final').check();
    const engine = await snapshot(page);
    assert.notDeepEqual(engine.pixels, builtin.pixels);
    // The engine fills a good part of the frame: pixels unlike the background (the top-left corner).
    const corner = Array.from(engine.pixels.subarray(0, 3));
    const covered = fractionUnlike(engine, corner, 6);
    assert.ok(covered > 0.1 && covered < 0.95, `${covered} of the frame is engine`);

    // Back to the built-in scene (the error line clears, and SwiftShader need not draw 120k triangles any more).
    await page.locator('#builtin-scene').click();
    assert.equal(await page.locator('#error').isVisible(), false);
    assert.match(await page.locator('#scene-name').textContent(), /^built-in scene/);
  });

  test('the glass sample: glass, blended panes and clear coat drawn; transparency off leaves the layer out',
       { timeout: 180000 }, async () => {
    const description = await page.evaluate(() => ({
      effects: window.obscura.effects.map((e) => ({ name: e.name, switch: e.switch, passes: e.passes })),
      parameters: window.obscura.parameters.map((p) => p.name) }));
    const transparency = description.effects.find((e) => e.name === 'transparency');
    assert.ok(transparency && transparency.switch, 'the table has the transparency switch');
    assert.deepEqual(transparency.passes, ['transmission-levels', 'transparency']);
    assert.ok(description.parameters.includes('lighting.sun'), 'and lighting.sun');
    assert.equal(await page.locator('#effect-transparency > summary #param-transparency').count(), 1,
                 'the panel has the Transparency section, its switch in the heading');
    assert.equal(await page.locator('#effect-lighting #param-lighting-sun').count(), 1);
    await page.locator('#file-input').setInputFiles(path.join(sourceDir, 'assets', 'scenes', 'glass-samples.glb'));
    await page.waitForFunction(
      () => document.querySelector('#scene-name').textContent.startsWith('glass-samples.glb'), null,
      { timeout: 60000 });
    assert.equal(await page.locator('#error').isVisible(), false);
    const scene = await page.evaluate(() => window.obscura.scene());
    assert.deepEqual(scene.warnings, [], 'every extension of the sample is implemented');
    await page.locator('#view-final').check();
    await waitForDrawn(page);
    const on = await snapshot(page);
    if (await page.evaluate(() => window.obscura.context.timerQuery)) {
      await page.waitForFunction(() => window.obscura.stats().passMs?.transparency > 0, null, { timeout: 30000 });
      const { passMs } = await page.evaluate(() => window.obscura.stats());
      assert.ok(passMs['transmission-levels'] > 0, `transmission-levels: ${passMs['transmission-levels']} ms`);
    }
    await page.evaluate(() => window.obscura.set('transparency', 'off'));
    await waitForDrawn(page);
    const off = await snapshot(page);
    const difference = compareImages(on, off);
    // The glass, the panes and the clear-coated spheres cover about 5 % of the fitted frame (its mean difference is
    // about 0.4 of 255): the layer shows as that share of pixels changed, some by much.
    const changed = Math.max(difference.r.differing, difference.g.differing, difference.b.differing);
    assert.ok(changed > 0.02 && difference.max > 40, `the layer shows: ${JSON.stringify(difference)}`);
    await page.evaluate(() => window.obscura.set('transparency', 'on'));
    await page.locator('#builtin-scene').click();
    assert.match(await page.locator('#scene-name').textContent(), /^built-in scene/);
  });

  test('a URL with camera and parameters reproduces the same image', { timeout: 120000 }, async () => {
    await page.locator('#view-split').check();
    await page.locator('#compare').selectOption('ao.blur');  // the split view compares the AO's blur
    await page.locator('#param-ao-samples').fill('16');
    await page.locator('#param-ao-intensity').fill('650');  // 0 .. 20 linear: 13
    // Orbit and zoom with the mouse, as a user would.
    await page.mouse.move(100, 200);
    await page.mouse.down();
    await page.mouse.move(140, 185, { steps: 4 });
    await page.mouse.up();
    await page.mouse.wheel(0, -200);
    await page.waitForFunction(() => location.search.includes('samples=16') && location.search.includes('view=split') &&
                               location.search.includes('compare=ao.blur'));
    await page.waitForTimeout(300);  // the URL follows changes within 150 ms
    const url = await page.evaluate(() => location.href);
    assert.match(url, /eye=[-\d.]+,[-\d.]+,[-\d.]+/);
    assert.doesNotMatch(url, /eye=3\.2,2\.6,6\.2&/, 'the camera moved');
    const original = await snapshot(page);

    const shared = await openPage(context, url);
    try {
      const state = await page.evaluate(() => window.obscura.state());
      assert.equal(await shared.evaluate(() => window.obscura.state()), state);
      assert.equal(await shared.locator('#view-split').isChecked(), true);
      assert.equal(await shared.locator('#compare').inputValue(), 'ao.blur');
      assert.equal(await shared.locator('#split-on').textContent(), 'ao.blur on');
      assert.equal(await shared.locator('#param-ao-samples + input').inputValue(), '16');
      const reproduced = await snapshot(shared);
      const difference = compareImages(original, reproduced);
      assert.equal(difference.max, 0, `the shared URL draws the same pixels (max difference ${difference.max})`);
      assert.deepEqual(shared.errors, []);
    } finally {
      await shared.close();
    }
  });

  test('a URL keeps a changed preset, so its fitted values and the image come back', { timeout: 120000 }, async () => {
    await page.evaluate(() => window.obscura.setState('preset=ultra&intensity=auto&bias=auto&contrast=auto'));
    await page.locator('#view').click({ position: { x: 100, y: 100 } });
    await page.keyboard.press('p');  // the next preset: low
    await page.keyboard.press('.');  // one sample more: the values no longer match the preset
    assert.equal(await page.evaluate(() => window.obscura.get('preset')), '');
    await page.waitForFunction(() => location.search.includes('preset=low') && location.search.includes('samples=9'));
    await waitForDrawn(page);
    const original = await snapshot(page);
    const shown = () => ({ state: window.obscura.state(),
                           fitted: ['intensity', 'bias', 'contrast'].map((name) => window.obscura.effective(name)) });
    const shared = await openPage(context, await page.evaluate(() => location.href));
    try {
      assert.deepEqual(await shared.evaluate(shown), await page.evaluate(shown), 'the same state and fitted values');
      assert.equal(compareImages(original, await snapshot(shared)).max, 0, 'the same pixels');
      assert.deepEqual(shared.errors, []);
    } finally {
      await shared.close();
    }
  });

  test('touch: two fingers pinch to zoom, one finger orbits', { timeout: 120000 }, async () => {
    const touchContext = await session.newContext({ hasTouch: true });
    try {
      const touchPage = await openPage(touchContext, session.baseUrl);
      // Real touch input through the DevTools protocol: the browser turns it into touch pointer events.
      const cdp = await touchContext.newCDPSession(touchPage);
      const touch = (type, points) => cdp.send('Input.dispatchTouchEvent',
                                               { type, touchPoints: points.map(([x, y], id) => ({ x, y, id })) });
      const camera = () => touchPage.evaluate(() => {
        const state = new URLSearchParams(window.obscura.state());
        const [eye, target] = ['eye', 'target'].map((key) => state.get(key).split(',').map(Number));
        return { eye, target, distance: Math.hypot(...eye.map((e, i) => e - target[i])) };
      });
      const start = await camera();
      await touch('touchStart', [[200, 180], [260, 180]]);
      for (let i = 1; i <= 5; ++i) await touch('touchMove', [[200 - 10 * i, 180], [260 + 10 * i, 180]]);
      await touch('touchEnd', []);
      const pinched = await camera();
      // Fingers spread from 60 to 160 pixels apart: the eye comes 160/60 times closer.
      assert.ok(Math.abs(start.distance / pinched.distance - 160 / 60) < 0.05,
                `distance ${start.distance} -> ${pinched.distance}`);
      await touch('touchStart', [[200, 180]]);
      for (let i = 1; i <= 5; ++i) await touch('touchMove', [[200 + 10 * i, 180]]);
      await touch('touchEnd', []);
      const orbited = await camera();
      assert.notDeepEqual(orbited.eye, pinched.eye, 'one finger moved the eye');
      assert.deepEqual(orbited.target, pinched.target, 'around the same target');
      assert.ok(Math.abs(orbited.distance - pinched.distance) < 1e-3 * pinched.distance);
      assert.deepEqual(touchPage.errors, []);
    } finally {
      await touchContext.close();
    }
  });

  test('debug-gl: a GL error stops the frame and is reported, naming where it was raised', { timeout: 120000 },
    async () => {
      const checked = await openPage(context, `${session.baseUrl}?view=ao`);
      try {
        // An error the page's own script leaves pending on Obscura's context (GL_INVALID_ENUM), then a change.
        await checked.evaluate(() => {
          document.querySelector('#view').getContext('webgl').enable(0x1234);
          window.obscura.set('radius', 1.5);
        });
        await checked.waitForFunction(() => window.obscura.stats().error !== '', null, { timeout: 60000 });
        const error = await checked.evaluate(() => window.obscura.stats().error);
        assert.match(error, /GL error 0x0500 outside the passes \(pending before the frame/);
        assert.ok(checked.errors.some((e) => /cannot render: GL error 0x0500/.test(e)), checked.errors.join('\n'));
        assert.ok(checked.errors.some((e) => /INVALID_ENUM/.test(e)), 'Chrome\'s own warning is collected too');
        // The next change draws again.
        await checked.evaluate(() => window.obscura.set('radius', 1.0));
        await waitForDrawn(checked);
        assert.equal(await checked.evaluate(() => window.obscura.stats().error), '');
      } finally {
        await checked.close();
      }
    });

  test('a bad URL is reported and the default view shown', { timeout: 120000 }, async () => {
    const bad = await openPage(context, `${session.baseUrl}?radius=-4&view=ao`);
    try {
      assert.match(await bad.locator('#error').textContent(), /radius: -4 is out of range/);
      assert.equal(await bad.evaluate(() => window.obscura.view), 'final', 'nothing of the bad link was applied');
      assert.deepEqual(bad.errors, [], 'a refused link is shown in the page, not thrown or logged as an error');
    } finally {
      await bad.close();
    }
  });

  test('page screenshots: AO off, AO on and split', { timeout: 180000 }, async () => {
    // At devicePixelRatio 1, and README-sized when they are to replace docs/images/web_*.png (slow on SwiftShader,
    // hence only then). Either way the split halves must match the AO-off and AO-on images exactly.
    const size = process.env.OBSCURA_UPDATE_SCREENSHOTS ? { width: 960, height: 540 } : { width: 480, height: 270 };
    const largeContext = await session.newContext({ viewport: size, deviceScaleFactor: 1 });
    try {
      const large = await openPage(largeContext, session.baseUrl);
      await large.evaluate(() => document.querySelector('#shortcuts-section').removeAttribute('open'));
      const pictures = {};
      // The controls panel is shown in one picture only, so the others show the AO unobstructed.
      for (const [name, state, panel] of [['ao_off', 'view=final&ao=off', false], ['ao_on', 'view=final&ao=on', true],
                                          ['split', 'view=split', false]]) {
        const collapsed = await large.evaluate(() => document.querySelector('#panel').classList.contains('collapsed'));
        if (collapsed === panel) await large.locator('#panel-toggle').click();
        await large.evaluate((query) => window.obscura.setState(query), state);
        pictures[name] = await snapshot(large);
        await waitForDrawn(large);
        const png = await large.screenshot();
        fs.writeFileSync(path.join(artifactDir, `web_${name}.png`), png);
        if (process.env.OBSCURA_UPDATE_SCREENSHOTS) {
          fs.writeFileSync(path.join(sourceDir, 'docs', 'images', `web_${name}.png`), png);
        }
      }
      const { ao_off: off, ao_on: on, split } = pictures;
      assert.equal(split.width, size.width);
      let left = 0, right = 0;
      const half = split.width / 2;
      for (let y = 0; y < split.height; ++y) {
        for (let x = 0; x < split.width; ++x) {
          const i = (y * split.width + x) * 4;
          for (let c = 0; c < 3; ++c) {
            if (x < half - 1) left += split.pixels[i + c] !== off.pixels[i + c];
            if (x > half) right += split.pixels[i + c] !== on.pixels[i + c];
          }
        }
      }
      assert.equal(left, 0, `${left} channel values differ from AO off on the left half`);
      assert.equal(right, 0, `${right} channel values differ from AO on on the right half`);
      assert.deepEqual(large.errors, []);
    } finally {
      await largeContext.close();
    }
  });
});
