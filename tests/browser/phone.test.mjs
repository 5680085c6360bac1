// The demo page on a phone, in headless Chromium emulating one (390 x 844 CSS pixels, devicePixelRatio 3, touch,
// mobile viewport): the canvas draws at most 2 device pixels per CSS pixel (resolution.max-pixel-ratio), the panel
// starts closed and opens as a sheet that leaves the image's upper part in view, numbers are rounded to their
// parameter's step, one finger orbits and two pinch and pan, and dynamic resolution lowers the render scale while the
// canvas stays at the display's size, and quick start draws a cheap first frame that the full one follows by
// itself. With OBSCURA_UPDATE_SCREENSHOTS=1 it writes the README's phone screenshot
// (docs/images/web_phone.png).
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, describe, test } from 'node:test';
import { artifactDir, luminanceStats, openPage, snapshot, sourceDir, startBrowser, waitForDrawn } from './harness.mjs';

const phone = { viewport: { width: 390, height: 844 }, deviceScaleFactor: 3, isMobile: true, hasTouch: true };

let session;
let context;
let page;

describe('the page on a phone', () => {
  before(async () => {
    session = await startBrowser();
    context = await session.newContext(phone);
    // The page as a phone gets it: dynamic resolution and quick start on (its defaults; the tests' harness turns them
    // off elsewhere).
    page = await openPage(context, `${session.baseUrl}?resolution.dynamic=on&resolution.quick-start=on`);
  });
  after(async () => {
    if (page) assert.deepEqual(page.errors, [], 'console errors during the phone tests');
    await session?.close();
  });

  test('at 390 x 844 CSS pixels and devicePixelRatio 3 the canvas draws at 2x', { timeout: 120000 }, async () => {
    const stats = await page.evaluate(() => window.obscura.stats());
    assert.equal(stats.render.devicePixelRatio, 3);
    assert.equal(stats.render.pixelRatio, 2, 'resolution.max-pixel-ratio: 2 by default');
    assert.equal(stats.width, 780);
    assert.equal(stats.height, 1688);
    const canvas = await page.evaluate(() => {
      const c = document.querySelector('#view');
      return { width: c.width, height: c.height, cssWidth: c.clientWidth, cssHeight: c.clientHeight };
    });
    assert.deepEqual(canvas, { width: 780, height: 1688, cssWidth: 390, cssHeight: 844 });
    // The cap is a parameter: at 3 the canvas takes the device's full ratio.
    await page.evaluate(() => window.obscura.set('resolution.max-pixel-ratio', 3));
    await page.waitForFunction(() => window.obscura.stats().width === 1170);
    await page.evaluate(() => window.obscura.set('resolution.max-pixel-ratio', 2));
    await page.waitForFunction(() => window.obscura.stats().width === 780);
  });

  test('quick start: the first frame was a cheap one, the stats say so, and the full frame followed by itself',
    { timeout: 120000 }, async () => {
      // openPage waited until no frame was pending: a cheap frame leaves the next one pending.
      const { startup, stats } = await page.evaluate(() => ({ startup: window.obscura.startup(),
                                                             stats: window.obscura.stats() }));
      const q = startup.quickStart;
      // The cheap frame's programs were begun at start-up (Renderer::prepare): the G-buffer's, the lighting's (the
      // scene and the background) and the upscale's.
      assert.ok(startup.programsPrepared >= 3, `programs begun at start-up: ${startup.programsPrepared}`);
      assert.ok(q.cheapFrames >= 2, `the cheap first frame and one that warmed (${q.cheapFrames})`);
      assert.equal(q.firstFullFrame, q.cheapFrames, 'the full frame right after the cheap ones');
      const warmed = q.warmed.map((w) => w.pass);
      for (const pass of ['sao', 'lighting', 'fxaa']) assert.ok(warmed.includes(pass), `${pass} in ${warmed}`);
      assert.ok(q.warmed.every((w) => w.frame >= 1 && w.frame < q.cheapFrames), 'warmed after the first frame');
      assert.ok(startup.fullFrameMs > startup.firstFrameMs, `${startup.fullFrameMs} > ${startup.firstFrameMs}`);
      assert.equal(stats.cheapFrame, false);
      for (const pass of ['sao', 'fxaa']) assert.ok(stats.passesRun.includes(pass), `${pass} runs now`);
      await page.waitForFunction(() => /first frame \d+ ms \(cheap/.test(document.querySelector('#stats').textContent));
    });

  test('the panel starts closed, and opens as a sheet that leaves the image in view', { timeout: 120000 },
    async () => {
      assert.equal(await page.locator('#panel-body').isVisible(), false);
      assert.equal(await page.locator('#panel-toggle').isVisible(), true);
      const closed = await page.locator('#panel').boundingBox();
      assert.ok(closed.width < 200 && closed.height < 60, `closed: a small button (${JSON.stringify(closed)})`);
      await page.locator('#panel-toggle').tap();
      assert.equal(await page.locator('#panel-body').isVisible(), true);
      const sheet = await page.locator('#panel').boundingBox();
      assert.ok(sheet.y >= 844 * 0.5, `the sheet starts in the lower half (top at ${sheet.y})`);
      assert.ok(Math.abs(sheet.y + sheet.height - 844) < 2, 'along the bottom');
      assert.ok(Math.abs(sheet.width - 390) < 2, 'the whole width');
      // The image above the sheet is what the canvas draws.
      const view = await page.locator('#view').boundingBox();
      assert.deepEqual([view.x, view.y, view.width, view.height], [0, 0, 390, 844]);
      await page.locator('#panel-toggle').tap();
      assert.equal(await page.locator('#panel-body').isVisible(), false);
    });

  test("number fields show values rounded to their parameter's step", { timeout: 120000 }, async () => {
    const fields = await page.evaluate(() => {
      const out = {};
      for (const name of ['lighting.sun-elevation', 'tonemap.exposure', 'resolution.scale', 'ao.radius']) {
        const parameter = window.obscura.parameters.find((p) => p.name === name);
        const row = document.getElementById(`param-${name.replace(/\./g, '-')}`).closest('.parameter');
        out[name] = { shown: row.querySelector('input[type=number]').value, value: window.obscura.effective(name),
                      step: parameter.step };
      }
      return out;
    });
    const elevation = fields['lighting.sun-elevation'];
    assert.equal(elevation.step, 0.1);
    assert.notEqual(elevation.value, elevation.shown, `the value itself has more digits (${elevation.value})`);
    assert.equal(elevation.shown, String(Math.round(Number(elevation.value) * 10) / 10));
    assert.equal(fields['tonemap.exposure'].step, 0.01);
    assert.equal(fields['resolution.scale'].step, 0.0001);
    assert.equal(fields['ao.radius'].step, 0, 'a range over decades: three significant figures');
    assert.equal(fields['ao.radius'].shown, '1');
  });

  test('touch: one finger orbits, two pinch to zoom and move together to pan', { timeout: 180000 }, async () => {
    const cdp = await context.newCDPSession(page);
    const touch = (type, points) => cdp.send('Input.dispatchTouchEvent',
                                             { type, touchPoints: points.map(([x, y], id) => ({ x, y, id })) });
    const camera = () => page.evaluate(() => {
      const state = new URLSearchParams(window.obscura.state());
      const [eye, target] = ['eye', 'target'].map((key) => state.get(key).split(',').map(Number));
      return { eye, target, distance: Math.hypot(...eye.map((e, i) => e - target[i])) };
    });
    const start = await camera();
    // Pinch: fingers from 80 to 200 CSS pixels apart.
    await touch('touchStart', [[155, 300], [235, 300]]);
    for (let i = 1; i <= 6; ++i) await touch('touchMove', [[155 - 10 * i, 300], [235 + 10 * i, 300]]);
    await touch('touchEnd', []);
    const pinched = await camera();
    assert.ok(Math.abs(start.distance / pinched.distance - 200 / 80) < 0.06,
              `distance ${start.distance} -> ${pinched.distance}`);
    // Each finger's move pans by half its own (the midpoint's move); the zoom between a pinch's two moves leaves a
    // residue of a few millimetres here.
    const drift = Math.hypot(...pinched.target.map((t, i) => t - start.target[i]));
    assert.ok(drift < 0.01 * pinched.distance, `a pinch whose midpoint stays barely pans (${drift})`);
    // Pan: two fingers 80 pixels apart moving 60 pixels to the right together.
    await touch('touchStart', [[155, 400], [235, 400]]);
    for (let i = 1; i <= 6; ++i) await touch('touchMove', [[155 + 10 * i, 400], [235 + 10 * i, 400]]);
    await touch('touchEnd', []);
    const panned = await camera();
    const panDistance = Math.hypot(...panned.target.map((t, i) => t - pinched.target[i]));
    assert.ok(panDistance > 10 * drift, `the target moved (${panDistance})`);
    assert.ok(Math.abs(panned.distance - pinched.distance) < 1e-3 * pinched.distance, 'at the same distance');
    const moved = panned.eye.map((e, i) => e - pinched.eye[i]);
    const targetMoved = panned.target.map((t, i) => t - pinched.target[i]);
    for (let i = 0; i < 3; ++i) assert.ok(Math.abs(moved[i] - targetMoved[i]) < 1e-3, 'eye and target move alike');
    // Orbit: one finger.
    await touch('touchStart', [[195, 500]]);
    for (let i = 1; i <= 6; ++i) await touch('touchMove', [[195 + 10 * i, 500]]);
    await touch('touchEnd', []);
    const orbited = await camera();
    assert.notDeepEqual(orbited.eye, panned.eye, 'one finger moved the eye');
    assert.deepEqual(orbited.target, panned.target, 'around the same target');
    assert.ok(Math.abs(orbited.distance - panned.distance) < 1e-3 * panned.distance);
    await waitForDrawn(page);
  });

  test('dynamic resolution: the first frame at the smallest scale, up where frames leave room, down where not',
    { timeout: 400000 }, async () => {
      assert.equal(await page.evaluate(() => document.body.dataset.shownScale), '0.5', 'the first frame: the cheapest');
      // SwiftShader draws far slower than the 33 ms the page aims at: frames drawn back to back stay at 0.5, drawn at
      // 390 x 844 and upscaled into the 780 x 1688 canvas.
      await page.evaluate(() => window.obscura.setContinuous(true));
      await page.waitForFunction(() => window.obscura.stats().render.meanMs > 0, null,
                                 { timeout: 240000, polling: 200 });
      let stats = await page.evaluate(() => window.obscura.stats());
      assert.equal(stats.render.dynamic, true);
      assert.equal(stats.render.scale, 0.5);
      assert.deepEqual([stats.render.width, stats.render.height], [390, 844]);
      assert.deepEqual([stats.width, stats.height], [780, 1688], 'the canvas keeps its size');
      assert.ok(stats.render.meanMs > stats.render.targetMs, `measured ${stats.render.meanMs} ms`);
      await page.evaluate(() => window.obscura.setContinuous(false));
      await waitForDrawn(page);
      const shot = await snapshot(page);
      assert.deepEqual([shot.width, shot.height], [780, 1688]);
      assert.ok(luminanceStats(shot).deviation > 0.05, 'the upscaled image is the scene');
      assert.match(await page.locator('#stats').textContent(), /render 390 x 844: scale 0\.50, dynamic/);
      // Where every scale meets the target (a canvas small enough for SwiftShader: pixel ratio 0.5, 195 x 422; a
      // target of 1 s), the still view draws on by itself until it is at scale 1.
      await page.evaluate(() => {
        window.obscura.set('resolution.max-pixel-ratio', 0.5);
        window.obscura.set('resolution.target-ms', 1000);
      });
      await page.waitForFunction(() => window.obscura.stats().render.scale === 1, null,
                                 { timeout: 300000, polling: 200 });
      stats = await page.evaluate(() => window.obscura.stats());
      assert.deepEqual([stats.render.width, stats.render.height], [195, 422]);
      await page.evaluate(() => {
        window.obscura.set('resolution.target-ms', 33.3);
        window.obscura.set('resolution.max-pixel-ratio', 2);
      });
      await waitForDrawn(page);
    });

  test('a phone-sized screenshot, the sheet open', { timeout: 120000 }, async () => {
    await page.evaluate(() => window.obscura.resetCamera());  // the scene's own view, not the touch tests' one
    await waitForDrawn(page);
    await page.locator('#panel-toggle').tap();
    await page.evaluate(() => {
      for (const section of document.querySelectorAll('details.effect')) section.open = section.id === 'effect-ao';
    });
    const png = await page.screenshot({ scale: 'css' });
    fs.writeFileSync(path.join(artifactDir, 'web_phone.png'), png);
    if (process.env.OBSCURA_UPDATE_SCREENSHOTS) {
      fs.writeFileSync(path.join(sourceDir, 'docs', 'images', 'web_phone.png'), png);
    }
    assert.ok(png.length > 20000, 'the page, not a blank');
  });
});
