// Another page embeds Obscura through its JavaScript API alone (web/README.md, "Embedding"): tests/browser/embed.html
// has its own canvas and imports obscura.js, without the demo page's app.js, index.html or style.css. It is served
// at the site's root (so './obscura.js' resolves to the built module) by intercepting its URL.
import assert from 'node:assert/strict';
import path from 'node:path';
import { after, before, describe, test } from 'node:test';
import { luminanceStats, openPage, snapshot, sourceDir, startBrowser, waitForDrawn } from './harness.mjs';

let session;
let page;

describe('embedding with obscura.js alone', () => {
  before(async () => {
    session = await startBrowser();
    const context = await session.newContext();
    await context.route((url) => url.pathname === '/embed.html',
                        (route) => route.fulfill({ path: path.join(sourceDir, 'tests', 'browser', 'embed.html') }));
    page = await openPage(context, `${session.baseUrl}embed.html`);
  });
  after(async () => {
    if (page) assert.deepEqual(page.errors, [], 'console errors on the embedding page');
    await session?.close();
  });

  test('set a parameter, choose a view, move the camera, read stats, take a snapshot', { timeout: 120000 },
       async () => {
    assert.equal(await page.evaluate(() => document.querySelector('#panel, #stats')), null, 'no demo page UI');
    const shown = await page.evaluate(() => {
      const obscura = window.obscura;
      obscura.set('radius', 1.5);
      obscura.setView('ao');
      obscura.orbit(40, 10);
      return { radius: obscura.get('radius'), view: obscura.view, state: obscura.state() };
    });
    assert.equal(shown.radius, '1.5');
    assert.equal(shown.view, 'ao');
    // Written under the full name ("radius" is its old name, still accepted).
    assert.match(shown.state, /^view=ao&ao\.radius=1\.5&eye=/);
    assert.doesNotMatch(shown.state, /eye=3\.2,2\.6,6\.2&/, 'the orbit moved the eye');

    await waitForDrawn(page);
    const stats = await page.evaluate(() => window.obscura.stats());
    // 400 x 240 CSS pixels at the tests' devicePixelRatio of 0.5.
    assert.equal(stats.width, 200);
    assert.equal(stats.height, 120);
    assert.ok(stats.frames > 0 && stats.lastCpuMs > 0, JSON.stringify(stats));
    assert.equal(stats.error, '');

    // draw() renders a frame now, outside the animation-frame schedule: the canvas holds it within the same task.
    const drawn = await page.evaluate(() => {
      const obscura = window.obscura;
      const before = obscura.stats().frames;
      obscura.draw();
      const gl = obscura.canvas.getContext('webgl');
      const pixel = new Uint8Array(4);
      gl.readPixels(100, 60, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
      return { before, after: obscura.stats().frames, pixel: Array.from(pixel) };
    });
    assert.equal(drawn.after, drawn.before, 'draw() is not an animation frame: frames counts only those');
    assert.notDeepEqual(drawn.pixel, [0, 0, 0, 0], 'the drawn frame is in the canvas');

    const shot = await snapshot(page);
    assert.equal(shot.width, 200);
    const ao = luminanceStats(shot);
    assert.ok(ao.deviation > 0.02 && ao.min < 0.6 && ao.max > 0.9,
              `an AO image, not a blank one: ${JSON.stringify(ao)}`);
  });
});
