// The AO radius follows the scene on the demo page and through the JS API (scene/SceneScale.h): a scene loaded gets
// 5 % of its bounding-sphere diameter, to two significant figures (42 for 2CylinderEngine.glb, in centimetres; the
// built-in scene its own 1 m), unless the URL gave a radius; the radius slider spans that default / 100 .. x 100 on
// a logarithmic scale, widened for a value typed outside it.
import assert from 'node:assert/strict';
import path from 'node:path';
import { after, before, describe, test } from 'node:test';
import { assimpModels, openPage, startBrowser, waitForDrawn } from './harness.mjs';

const engineFile = path.join(assimpModels, '2CylinderEngine-glTF-Binary', '2CylinderEngine.glb');

let session;
let context;

// What the page shows of the radius: the core's value, the scene's default, the number box, the slider's position
// (0 .. 1000) and the span it covers.
async function radiusControl(page) {
  return page.evaluate(() => {
    const slider = document.querySelector('#param-ao-radius');
    return {
      radius: window.obscura.get('ao.radius'),
      defaultRadius: window.obscura.defaultRadius,
      scene: window.obscura.scene(),
      number: document.querySelector('#param-ao-radius + input').value,
      position: Number(slider.value),
      low: Number(slider.dataset.low),
      high: Number(slider.dataset.high),
    };
  });
}

async function loadEngineWithThePicker(page) {
  await page.locator('#file-input').setInputFiles(engineFile);
  await page.waitForFunction(
    () => document.querySelector('#scene-name').textContent.startsWith('2CylinderEngine.glb'), null,
    { timeout: 60000 });
  await waitForDrawn(page);
}

describe('the AO radius follows the scene', () => {
  before(async () => {
    session = await startBrowser();
    context = await session.newContext();
    // The model under the site's address, for the JS API's loadScene(bytes).
    await context.route((url) => url.pathname === '/model/2CylinderEngine.glb',
                        (route) => route.fulfill({ path: engineFile }));
  });
  after(async () => { await session?.close(); });

  test('a scene loaded gets its default radius, and the slider spans it', { timeout: 180000 }, async () => {
    const page = await openPage(context, session.baseUrl);
    try {
      let shown = await radiusControl(page);
      assert.equal(shown.radius, '1', 'the built-in scene: its own metre');
      assert.equal(shown.defaultRadius, 1);
      assert.deepEqual([shown.low, shown.high, shown.position], [0.01, 100, 500]);
      assert.match(await page.locator('#scene-name').textContent(), /AO radius 1 by default/);

      await loadEngineWithThePicker(page);
      shown = await radiusControl(page);
      assert.equal(shown.radius, '42', '5 % of the engine\'s 836 cm bounding-sphere diameter, two figures');
      assert.equal(shown.defaultRadius, 42);
      assert.equal(shown.scene.defaultRadius, 42);
      assert.equal(shown.scene.radiusGiven, false);
      assert.equal(shown.number, '42');
      assert.deepEqual([shown.low, shown.high, shown.position], [0.42, 4200, 500], 'default / 100 .. x 100');
      assert.match(await page.locator('#scene-name').textContent(), /AO radius 42 by default/);
      // The URL leaves out a radius that is the scene's default.
      await page.waitForTimeout(300);  // the URL follows changes within 150 ms
      assert.doesNotMatch(await page.evaluate(() => location.search), /radius/);

      // The slider's ends are the span's.
      const slider = page.locator('#param-ao-radius');
      await slider.fill('0');
      assert.equal((await radiusControl(page)).radius, '0.42');
      await slider.fill('1000');
      assert.equal((await radiusControl(page)).radius, '4200');
      // A value typed outside the span is taken, and the span widens to it.
      const number = page.locator('#param-ao-radius + input');
      await number.fill('100000');
      await number.dispatchEvent('change');
      shown = await radiusControl(page);
      assert.equal(shown.radius, '100000');
      assert.deepEqual([shown.low, shown.high, shown.position], [0.42, 100000, 1000]);

      // Another scene: its own default again, the span re-centred on it.
      await page.locator('#builtin-scene').click();
      shown = await radiusControl(page);
      assert.equal(shown.radius, '1');
      assert.deepEqual([shown.low, shown.high, shown.position], [0.01, 100, 500]);

      // The JS API's loadScene does the same.
      const loaded = await page.evaluate(async () => {
        const bytes = await (await fetch('/model/2CylinderEngine.glb')).arrayBuffer();
        const scene = await window.obscura.loadScene(bytes, '2CylinderEngine.glb');
        return { scene, radius: window.obscura.get('radius') };
      });
      assert.equal(loaded.scene.defaultRadius, 42);
      assert.equal(loaded.radius, '42');
      assert.deepEqual(page.errors, []);
    } finally {
      await page.close();
    }
  });

  test('a radius in the URL is kept when a scene is loaded', { timeout: 180000 }, async () => {
    const page = await openPage(context, `${session.baseUrl}?view=ao&radius=3`);
    try {
      let shown = await radiusControl(page);
      assert.equal(shown.radius, '3');
      assert.equal(shown.scene.radiusGiven, true);
      await loadEngineWithThePicker(page);
      shown = await radiusControl(page);
      assert.equal(shown.radius, '3', 'the URL\'s radius, not the engine\'s 42');
      assert.equal(shown.defaultRadius, 42);
      assert.equal(shown.number, '3');
      // The slider spans the engine's default and shows 3 within it (0.42 .. 4200, logarithmic).
      assert.deepEqual([shown.low, shown.high], [0.42, 4200]);
      assert.equal(shown.position, Math.round(1000 * Math.log(3 / 0.42) / Math.log(10000)));
      await page.waitForTimeout(300);
      assert.match(await page.evaluate(() => location.search), /ao\.radius=3&/, 'and stays in the URL');

      // A value outside the default span from the URL widens it at once.
      const wide = await openPage(context, `${session.baseUrl}?radius=5000`);
      try {
        shown = await radiusControl(wide);
        assert.equal(shown.radius, '5000');
        assert.deepEqual([shown.low, shown.high, shown.position], [0.01, 5000, 1000]);
        assert.deepEqual(wide.errors, []);
      } finally {
        await wide.close();
      }
      assert.deepEqual(page.errors, []);
    } finally {
      await page.close();
    }
  });
});
