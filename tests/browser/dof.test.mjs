// Depth of field in the page (effects/dof/DepthOfFieldEffect.h): its section of controls built from the effect table,
// the JS API's focusAt, a click on the canvas focusing there (a drag does not), the URL carrying the focus point into a
// new page that draws the same pixels, and the passes in the stats.
import assert from 'node:assert/strict';
import { after, before, describe, test } from 'node:test';
import { compareImages, openPage, snapshot, startBrowser, waitForDrawn } from './harness.mjs';

let session;
let context;
let page;

describe('depth of field', () => {
  before(async () => {
    session = await startBrowser();
    context = await session.newContext();
    page = await openPage(context, session.baseUrl);
  });
  after(async () => {
    if (page) assert.deepEqual(page.errors, [], 'console errors during the depth of field tests');
    await session?.close();
  });

  test('the controls come from the effect table', { timeout: 120000 }, async () => {
    for (const name of ['dof', 'dof-focus', 'dof-fstop', 'dof-focal-length', 'dof-max-radius', 'dof-preset']) {
      assert.equal(await page.locator(`#param-${name}`).count(), 1, `#param-${name}`);
    }
    assert.equal(await page.evaluate(() => window.obscura.get('dof')), 'off');
    await page.locator('#param-dof').check();
    assert.equal(await page.evaluate(() => window.obscura.get('dof')), 'on');
    await waitForDrawn(page);
    const stats = await page.evaluate(() => window.obscura.stats());
    const passes = await page.evaluate(() => window.obscura.passes);
    for (const pass of ['dof-coc', 'dof-near', 'dof-far', 'dof-composite']) assert.ok(passes.includes(pass), pass);
    assert.ok(stats.frames > 0);
  });

  test('focusAt sets the autofocus point, and the image follows it', { timeout: 120000 }, async () => {
    await page.evaluate(() => {
      window.obscura.set('dof.fstop', '0.7');
      window.obscura.focusAt(0, 0);  // top left: the far background
    });
    await waitForDrawn(page);
    const far = await snapshot(page);
    const size = await page.evaluate(() => [window.obscura.canvas.clientWidth, window.obscura.canvas.clientHeight]);
    await page.evaluate(([w, h]) => window.obscura.focusAt(w / 2, h * 0.75), size);  // the floor, near
    assert.equal(await page.evaluate(() => window.obscura.get('dof.focus')), 'auto');
    assert.equal(await page.evaluate(() => window.obscura.get('dof.focus-x')), '0.5');
    assert.equal(await page.evaluate(() => window.obscura.get('dof.focus-y')), '0.75');
    await waitForDrawn(page);
    const near = await snapshot(page);
    const difference = compareImages(far, near);
    assert.ok(difference.mean > 1, `refocusing changes the image (mean difference ${difference.mean})`);
  });

  test('a click focuses where it lands; a drag does not', { timeout: 120000 }, async () => {
    const box = await page.locator('#view').boundingBox();
    await page.mouse.click(box.x + box.width * 0.25, box.y + box.height * 0.5);
    assert.equal(await page.evaluate(() => window.obscura.get('dof.focus-x')), '0.25');
    assert.equal(await page.evaluate(() => window.obscura.get('dof.focus-y')), '0.5');
    // A drag orbits the camera and leaves the focus point.
    await page.mouse.move(box.x + box.width * 0.6, box.y + box.height * 0.3);
    await page.mouse.down();
    await page.mouse.move(box.x + box.width * 0.7, box.y + box.height * 0.35, { steps: 4 });
    await page.mouse.up();
    assert.equal(await page.evaluate(() => window.obscura.get('dof.focus-x')), '0.25');
    await waitForDrawn(page);
  });

  test('the URL carries the focus point into a new page', { timeout: 120000 }, async () => {
    await page.waitForFunction(() => location.search.includes('dof.focus-x=0.25'), null, { timeout: 10000 });
    await page.waitForTimeout(300);  // the URL follows changes within 150 ms
    const url = await page.evaluate(() => location.href);
    assert.match(url, /dof=on/);
    const original = await snapshot(page);
    const shared = await openPage(context, url);
    try {
      assert.equal(await shared.evaluate(() => window.obscura.get('dof.focus-x')), '0.25');
      const difference = compareImages(original, await snapshot(shared));
      assert.equal(difference.max, 0, `the shared URL draws the same pixels (max difference ${difference.max})`);
      assert.deepEqual(shared.errors, []);
    } finally {
      await shared.close();
    }
  });
});
