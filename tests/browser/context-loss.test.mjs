// WebGL context loss and restore, triggered with WEBGL_lose_context: on loss the core drops every GL object without
// deleting it (the names belong to the dead context), on restore it rebuilds the renderer and the scene's buffers
// and textures from the scene it kept on the CPU, and the page keeps drawing the same image.
import assert from 'node:assert/strict';
import { after, before, describe, test } from 'node:test';
import { compareImages, openPage, snapshot, startBrowser, waitForDrawn } from './harness.mjs';

let session;
let page;

describe('WebGL context loss', () => {
  before(async () => {
    session = await startBrowser();
    // Split view: the G-buffer, SAO, both blur passes and the lighting pass all run.
    page = await openPage(await session.newContext(), `${session.baseUrl}?view=split&radius=1.5`);
  });
  after(async () => {
    if (page) assert.deepEqual(page.errors, []);
    await session?.close();
  });

  test('lose and restore: every GL object is rebuilt and the same image comes back', { timeout: 120000 }, async () => {
    const before = await snapshot(page);
    const statsBefore = await page.evaluate(() => window.obscura.stats());
    const objectsBefore = Object.values(statsBefore.glObjects).reduce((a, b) => a + b, 0);
    assert.ok(objectsBefore > 10, `${objectsBefore} live GL objects while running`);

    await page.evaluate(() => {
      window.loseContext = document.querySelector('#view').getContext('webgl').getExtension('WEBGL_lose_context');
      window.loseContext.loseContext();
    });
    await page.waitForFunction(() => window.obscura.stats().contextLost, null, { timeout: 30000 });
    const whileLost = await page.evaluate(() => {
      let snapshotError = '';
      try {
        window.obscura.snapshot();
      } catch (e) {
        snapshotError = e.message;
      }
      window.obscura.set('radius', '1.5');  // parameters may still change while the context is away
      return { stats: window.obscura.stats(), snapshotError };
    });
    assert.deepEqual(Object.values(whileLost.stats.glObjects), [0, 0, 0, 0, 0, 0], 'every object was dropped');
    assert.match(whileLost.snapshotError, /context is lost/);
    await page.waitForFunction(() => document.querySelector('#stats').textContent.includes('context lost'));

    const framesWhileLost = whileLost.stats.frames;
    await page.evaluate(() => window.loseContext.restoreContext());
    await page.waitForFunction(() => {
      const stats = window.obscura.stats();
      return stats.contextRestores === 1 && !stats.contextLost;
    }, null, { timeout: 30000 });
    // The restored context draws by itself, without any change asked for.
    await page.waitForFunction((before) => window.obscura.stats().frames > before, framesWhileLost);
    await waitForDrawn(page);
    const statsAfter = await page.evaluate(() => window.obscura.stats());
    assert.deepEqual(statsAfter.glObjects, statsBefore.glObjects, 'as many objects of each kind as before');
    assert.equal(statsAfter.error, '');

    const after = await snapshot(page);
    const difference = compareImages(before, after);
    assert.equal(difference.max, 0, `the restored context draws the same pixels (max difference ${difference.max})`);

    // The history (the previous frame's camera, history targets) starts afresh on the new context.
    assert.ok(statsBefore.history.frames > 0, `history before the loss: ${JSON.stringify(statsBefore.history)}`);
    assert.equal(statsAfter.history.frames, 0, 'the restored context starts without history');
    assert.equal(statsAfter.history.frameIndex, 0, 'a new renderer');

    if (statsBefore.timerQueries) {
      // The timer went with the lost context (no pass times while lost); a new one measures the restored frames.
      assert.equal(whileLost.stats.passMs, null);
      await page.waitForFunction(() => window.obscura.stats().timerQueries && window.obscura.stats().passMs !== null,
                                 null, { timeout: 30000 });
    }
  });
});

describe('history', () => {
  test('survives frames and is dropped on resize and scene change', { timeout: 120000 }, async () => {
    const session = await startBrowser();
    try {
      const page = await openPage(await session.newContext(), session.baseUrl);
      const history = () => page.evaluate(() => {
        window.obscura.draw();  // a frame now, whatever the animation-frame schedule does
        return window.obscura.stats().history;
      });
      await history();
      const running = await history();
      assert.ok(running.frames >= 1, JSON.stringify(running));
      const grown = await history();
      assert.equal(grown.frames, running.frames + 1, 'one more frame of history per frame');

      await page.setViewportSize({ width: 500, height: 300 });  // a resize
      await page.waitForFunction(() => window.obscura.stats().width === 250);
      await waitForDrawn(page);
      const resized = await page.evaluate(() => window.obscura.stats().history);
      assert.ok(resized.drops > grown.drops, `dropped on resize: ${JSON.stringify(resized)}`);
      assert.ok(resized.frames < grown.frames, 'and started again');

      // A scene change, and a frame drawn right after it in the same task (no animation frame in between).
      const [before, changed] = await page.evaluate(() => {
        window.obscura.draw();
        const previous = window.obscura.stats().history;
        window.obscura.loadBuiltinScene();
        window.obscura.draw();
        return [previous, window.obscura.stats().history];
      });
      assert.equal(changed.frames, 0, `dropped on a scene change: ${JSON.stringify(changed)}`);
      assert.equal(changed.drops, before.drops + 1);
      assert.deepEqual(page.errors, []);
    } finally {
      await session.close();
    }
  });
});
