// The camera's finish in the page (docs/camera-finish.md): each effect's section of controls from the effect table,
// the passes the JS API's settings run, and auto exposure adapting over real time: after a change the page keeps
// drawing, without input, until it has adapted, and a 16 times brighter sun ends near the brightness it had.
import assert from 'node:assert/strict';
import { after, before, describe, test } from 'node:test';
import { luminanceStats, openPage, snapshot, startBrowser, waitForDrawn } from './harness.mjs';

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
    await page.evaluate((s) => window.obscura.set('lighting.sun-intensity', String(16 * s)), sun);
    const start = await page.evaluate(() => window.obscura.stats().frames);
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
});
