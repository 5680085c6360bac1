// The camera's finish in the page (docs/camera-finish.md): each effect's section of controls from the effect table,
// the passes the JS API's settings run, and auto exposure adapting over real time: after a change the page keeps
// drawing, without input, until it has adapted, and a 16 times brighter sun ends near the brightness it had. The
// display colour's stages: their sections, a .cube opened on the page grading the frame inside the lighting's pass,
// and a malformed one refused with its line while the grade stays.
import assert from 'node:assert/strict';
import { after, before, describe, test } from 'node:test';
import { compareImages, luminanceStats, openPage, snapshot, startBrowser, waitForDrawn } from './harness.mjs';

let session;
let context;
let page;

describe("the camera's finish", () => {
  before(async () => {
    session = await startBrowser();
    context = await session.newContext();
    page = await openPage(context, session.baseUrl);
  });
  after(async () => {
    if (page) assert.deepEqual(page.errors, [], "console errors during the camera's finish tests");
    await session?.close();
  });

  test('each effect has its section, and the JS API runs its passes', { timeout: 120000 }, async () => {
    for (const effect of ['auto-exposure', 'lens-flare', 'glare', 'chromatic-aberration']) {
      assert.equal(await page.locator(`#effect-${effect}`).count(), 1, `#effect-${effect}`);
      assert.equal(await page.locator(`#param-${effect}`).count(), 1, `#param-${effect}`);
    }
    assert.equal(await page.locator('#param-edges-style').count(), 1);
    await page.evaluate(() => {
      const o = window.obscura;
      o.set('lens-flare', 'on');
      o.set('glare', 'on');
      o.set('chromatic-aberration', 'on');
      o.set('edges', 'on');
      o.set('edges.style', 'hatching');
    });
    await waitForDrawn(page);
    const ran = await page.evaluate(() => window.obscura.stats().passesRun);
    // bloom-down-2 writes bloom's level 2, `bloom-bright`, which the lens flare and the glare read (bloom off).
    for (const pass of ['bloom-down-2', 'lens-flare', 'glare', 'tonemap', 'chromatic-aberration', 'edges']) {
      assert.ok(ran.includes(pass), `${pass} in ${ran.join(', ')}`);
    }
    await page.evaluate(() => {
      const o = window.obscura;
      for (const effect of ['lens-flare', 'glare', 'chromatic-aberration', 'edges']) o.set(effect, 'off');
      o.set('edges.style', 'lines');
    });
    await waitForDrawn(page);
  });

  test('auto exposure adapts over time after a change, drawing on by itself', { timeout: 240000 }, async () => {
    await page.evaluate(() => {
      const o = window.obscura;
      o.set('lighting.environment', 'uniform');
      o.set('lighting.environment-intensity', '0');
      o.set('auto-exposure', 'on');
      o.set('auto-exposure.speed-up', '20');
      o.set('auto-exposure.speed-down', '20');
    });
    // Adapted to the first sun (ln 100 / 20 = 0.23 s of frames after the change).
    await page.waitForTimeout(1500);
    await waitForDrawn(page);
    const before = luminanceStats(await snapshot(page)).mean;
    const sun = Number(await page.evaluate(() => window.obscura.get('lighting.sun-intensity')));
    // The frame count read in the same task as the change: a frame the page draws between two evaluate calls (a loaded
    // machine) is one of the adaptation's.
    const start = await page.evaluate((s) => {
      const frames = window.obscura.stats().frames;
      window.obscura.set('lighting.sun-intensity', String(16 * s));
      return frames;
    }, sun);
    // No further input: the page draws on by itself while auto exposure adapts. Adapting takes at least three frames
    // (each stands for at most 0.1 s); on a loaded machine SwiftShader may need seconds for them, so the test waits
    // for the frames rather than for a fixed time.
    await page.waitForFunction((s) => window.obscura.stats().frames - s >= 3, start, { timeout: 120000 })
      .catch(() => {});
    await page.waitForTimeout(500);
    await waitForDrawn(page);
    const frames = (await page.evaluate(() => window.obscura.stats().frames)) - start;
    const after = luminanceStats(await snapshot(page)).mean;
    assert.ok(frames >= 3, `frames drawn while adapting: ${frames}`);
    assert.ok(Math.abs(after / before - 1) < 0.1, `mean luminance ${before} before, ${after} adapted`);
    await page.evaluate(() => window.obscura.set('auto-exposure', 'off'));
    await waitForDrawn(page);
    const unadapted = luminanceStats(await snapshot(page)).mean;
    assert.ok(unadapted > 1.5 * after, `without auto exposure the brighter sun shows: ${unadapted} against ${after}`);
  });

  test('a .cube opened grades the frame inside the lighting; a malformed one is refused with its line',
    { timeout: 120000 }, async () => {
      for (const effect of ['grading', 'vignette', 'grain', 'dither']) {
        assert.equal(await page.locator(`#effect-${effect}`).count(), 1, `#effect-${effect}`);
        assert.equal(await page.locator(`#param-${effect}`).count(), 1, `#param-${effect}`);
      }
      assert.equal(await page.evaluate(() => window.obscura.get('dither')), 'on', 'dithering is on by default');
      await waitForDrawn(page);
      const ungraded = await snapshot(page);
      // A 2 x 2 x 2 LUT that keeps red, darkens green a little and blue much: the frame turns warm.
      let cube = 'TITLE "warm"\nLUT_3D_SIZE 2\n';
      for (const b of [0, 1]) for (const g of [0, 1]) for (const r of [0, 1]) cube += `${r} ${0.9 * g} ${0.6 * b}\n`;
      await page.locator('#file-input').setInputFiles({ name: 'warm.cube', mimeType: 'text/plain',
                                                         buffer: Buffer.from(cube) });
      await page.waitForFunction(() => window.obscura.get('grading.lut') === '/luts/warm.cube', null,
                                 { timeout: 60000 });
      assert.equal(await page.evaluate(() => window.obscura.get('grading')), 'on');
      await waitForDrawn(page);
      const graded = await snapshot(page);
      const mean = (image, c) => {
        let sum = 0;
        for (let i = c; i < image.pixels.length; i += 4) sum += image.pixels[i];
        return sum / (image.pixels.length / 4);
      };
      assert.ok(mean(graded, 2) < 0.8 * mean(ungraded, 2), `blue ${mean(ungraded, 2)} -> ${mean(graded, 2)}`);
      assert.ok(Math.abs(mean(graded, 0) - mean(ungraded, 0)) < 2, `red ${mean(ungraded, 0)} -> ${mean(graded, 0)}`);
      const { passesRun, passesDoneBy } = await page.evaluate(() => window.obscura.stats());
      assert.ok(!passesRun.includes('grading'), `no pass of its own: ${passesRun.join(', ')}`);
      assert.ok(['lighting', 'tonemap'].includes(passesDoneBy.grading), `grading done by ${passesDoneBy.grading}`);

      // Malformed, through the JS API (text) and opened on the page: refused with the line, the grade stays.
      const message = await page.evaluate(async () => {
        try {
          await window.obscura.loadLut('LUT_3D_SIZE 2\n0 0 0\n1 0 x\n', 'bad.cube');
          return 'accepted';
        } catch (e) {
          return `${e.name}: ${e.message}`;
        }
      });
      assert.match(message, /^ObscuraError: .*bad\.cube line 3/);
      assert.ok(!message.includes('\n'), `one line: ${message}`);
      await page.locator('#file-input').setInputFiles({ name: 'short.cube', mimeType: 'text/plain',
                                                         buffer: Buffer.from('LUT_3D_SIZE 2\n0 0 0\n') });
      await page.waitForFunction(() => document.querySelector('#error').textContent.includes('short.cube'), null,
                                 { timeout: 30000 });
      assert.match(await page.locator('#error').textContent(), /short\.cube line \d+/);
      assert.equal(await page.evaluate(() => window.obscura.get('grading.lut')), '/luts/warm.cube');
      await waitForDrawn(page);
      const kept = compareImages(graded, await snapshot(page));
      assert.ok(Math.max(kept.r.max, kept.g.max, kept.b.max) === 0, 'the grade stays');

      await page.evaluate(() => {
        window.obscura.set('grading.lut', 'none');
        window.obscura.set('grading', 'off');
      });
      await waitForDrawn(page);
    });
});
