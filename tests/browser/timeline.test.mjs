// The timeline in the page, on Debian's simple_skin (a skinned strip, one unnamed 5.5 s animation) loaded through the
// API: the Animation controls, space playing and pausing (frames change while playing, not while paused), the arrows
// stepping frames, the URL's state reproducing a frame pixel for pixel in a new page, the JS API (animations,
// setAnimation, setTime, timeupdate), a still scene hiding the controls, and the timeline surviving a WebGL context
// loss. Where the page's built-in scene moves (BuiltinSceneOptions), the URL alone reproduces its frame too.
import assert from 'node:assert/strict';
import { after, before, describe, test } from 'node:test';
import { compareImages, openPage, readModel, snapshot, startBrowser, waitForDrawn } from './harness.mjs';

let session;
let page;

const timeline = (p = page) => p.evaluate(() => window.obscura.timeline());
const skin = Array.from(readModel('simple_skin/simple_skin.gltf'));
const loadSkin = (p) => p.evaluate(async (bytes) => {
  await window.obscura.loadScene(new Uint8Array(bytes), 'simple_skin.gltf');
}, skin);

describe('timeline', () => {
  before(async () => {
    session = await startBrowser();
    page = await openPage(await session.newContext(), session.baseUrl);
    await loadSkin(page);
    await waitForDrawn(page);
  });
  after(async () => {
    if (page) assert.deepEqual(page.errors, [], 'console errors during the timeline tests');
    await session?.close();
  });

  test('starts paused at 0 s with the controls shown', { timeout: 120000 }, async () => {
    const t = await timeline();
    assert.deepEqual(t.animations, [''], 'one unnamed animation');
    assert.equal(t.animation, '0');
    assert.equal(t.duration, 5.5);
    assert.equal(t.time, 0);
    assert.equal(t.playing, false);
    assert.equal(t.loop, true);
    assert.equal(t.speed, 1);
    assert.equal(t.frameInterval, 1 / 60);
    assert.equal(await page.locator('#timeline').isVisible(), true);
    assert.equal(await page.locator('#play').textContent(), 'Play');
    assert.equal(await page.locator('#animation option:checked').textContent(), 'animation 0');
    // Idle: no frame is drawn while paused.
    const frames = (await page.evaluate(() => window.obscura.stats())).frames;
    await page.waitForTimeout(300);
    assert.equal((await page.evaluate(() => window.obscura.stats())).frames, frames);
  });

  test('space plays and pauses: frames change while playing, not while paused', { timeout: 120000 }, async () => {
    const still = await snapshot(page);
    const framesBefore = (await page.evaluate(() => window.obscura.stats())).frames;
    await page.locator('#view').click({ position: { x: 10, y: 10 } });  // the canvas has the focus, not a control
    await page.keyboard.press(' ');
    assert.equal(await page.evaluate(() => window.obscura.playing), true);
    await page.waitForFunction(() => window.obscura.time > 0.4, null, { timeout: 60000, polling: 50 });
    const drawn = (await page.evaluate(() => window.obscura.stats())).frames;
    assert.ok(drawn >= framesBefore + 3, `frames drawn while playing: ${framesBefore} -> ${drawn}`);
    assert.equal(await page.locator('#play').textContent(), 'Pause');
    await page.keyboard.press(' ');
    await waitForDrawn(page);
    const paused = await timeline();
    assert.equal(paused.playing, false);
    assert.ok(paused.time > 0.4, `time ${paused.time}`);

    const moved = await snapshot(page);
    assert.ok(compareImages(still, moved).max > 0, 'the scene moved');
    await page.waitForTimeout(300);
    assert.equal((await timeline()).time, paused.time, 'paused: the time stands');
    assert.equal(compareImages(moved, await snapshot(page)).max, 0, 'and so does the image');

    // The arrows step one frame (1/60 s) from the nearest frame, and pause.
    await page.keyboard.press('ArrowRight');
    const frame = Math.round(paused.time * 60);
    assert.equal((await timeline()).time, (frame + 1) / 60);
    await page.keyboard.press('ArrowLeft');
    await page.keyboard.press('ArrowLeft');
    assert.equal((await timeline()).time, (frame - 1) / 60);
    await page.evaluate((t) => window.obscura.setTime(t), paused.time);  // back where it was paused
  });

  test('the URL holds the time, and its state reproduces the frame in a new page', { timeout: 120000 }, async () => {
    const t = await timeline();
    assert.ok(t.time > 0 && !t.playing, JSON.stringify(t));
    await page.waitForFunction((time) => new URLSearchParams(location.search).get('time') === String(time), t.time);
    const url = await page.evaluate(() => location.href);
    const here = await snapshot(page);
    // The scene is not in the URL: the new page loads the file, then applies the URL's state (as a user who has the
    // file would), and draws the same pixels.
    const other = await openPage(await session.newContext(), url);
    try {
      await loadSkin(other);
      const state = new URL(url).searchParams;
      state.delete('debug-gl');  // a page flag, not state
      await other.evaluate((query) => window.obscura.setState(query), state.toString());
      await waitForDrawn(other);
      const reopened = await timeline(other);
      assert.equal(reopened.time, t.time, 'the same double');
      assert.equal(reopened.playing, false);
      const there = await snapshot(other);
      const difference = compareImages(here, there);
      assert.equal(difference.max, 0, `the same pixels (max difference ${difference.max})`);
      assert.deepEqual(other.errors, []);
    } finally {
      await other.close();
    }
  });

  test('where the built-in scene moves, its URL alone reproduces the frame', { timeout: 120000 }, async (t) => {
    const probe = await openPage(await session.newContext(), session.baseUrl);
    try {
      const builtin = await timeline(probe);
      if (builtin.duration <= 0) {
        t.skip('the built-in scene has no animation');
        return;
      }
      await probe.evaluate(() => {
        window.obscura.setTime(1.2345);
        window.obscura.stepFrames(1);
      });
      await probe.waitForFunction(() => new URLSearchParams(location.search).has('time'));
      const here = await snapshot(probe);
      const other = await openPage(await session.newContext(), await probe.evaluate(() => location.href));
      assert.equal((await timeline(other)).time, (await timeline(probe)).time);
      assert.equal(compareImages(here, await snapshot(other)).max, 0, 'the same pixels');
      await other.close();
    } finally {
      await probe.close();
    }
  });

  test('the API: choices, times, speed, loop and timeupdate', { timeout: 120000 }, async () => {
    const result = await page.evaluate(async () => {
      const o = window.obscura;
      const out = {};
      o.setAnimation('none');
      out.none = o.timeline();
      o.play();
      out.playsNone = o.playing;
      o.setAnimation(0);
      o.setTime(o.duration + 0.25);
      out.wrapped = o.time;
      o.setLoop(false);
      o.setTime(o.duration + 0.25);
      out.clamped = o.time === o.duration;
      o.setLoop(true);
      o.setSpeed(2);
      try {
        o.setAnimation('no such animation');
      } catch (e) {
        out.badAnimation = `${e.name}: ${e.message}`;
      }
      try {
        o.setSpeed(0);
      } catch (e) {
        out.badSpeed = e.message;
      }
      let updates = 0;
      o.addEventListener('timeupdate', () => { updates += 1; });
      o.setTime(0);
      o.play();
      await new Promise((resolve) => setTimeout(resolve, 500));
      o.pause();
      out.updates = updates;
      out.state = o.state();
      o.setSpeed(1);
      o.setTime(0);
      return out;
    });
    assert.equal(result.none.animation, 'none');
    assert.equal(result.none.duration, 0);
    assert.equal(result.playsNone, false, 'nothing plays');
    assert.ok(Math.abs(result.wrapped - 0.25) < 1e-9, `wrapped to ${result.wrapped}`);
    assert.equal(result.clamped, true);
    assert.match(result.badAnimation,
                 /^ObscuraError: animation 'no such animation' is not in the scene; choices: none, all, 0$/);
    assert.match(result.badSpeed, /speed: 0 is out of range/);
    assert.ok(result.updates >= 3, `timeupdate events while playing: ${result.updates}`);
    assert.match(result.state, /&speed=2&/);
  });

  test('a still scene hides the controls and has nothing to play', { timeout: 120000 }, async () => {
    const t = await page.evaluate(async (bytes) => {
      await window.obscura.loadScene(new Uint8Array(bytes), 'BoxTextured.glb');
      window.obscura.play();
      return window.obscura.timeline();
    }, Array.from(readModel('BoxTextured-glTF-Binary/BoxTextured.glb')));
    assert.deepEqual(t.animations, []);
    assert.equal(t.playing, false);
    assert.equal(t.duration, 0);
    await page.waitForFunction(() => document.querySelector('#timeline').hidden);
    await page.locator('#view').click({ position: { x: 10, y: 10 } });
    await page.keyboard.press(' ');
    await page.waitForFunction(() => document.querySelector('#error').textContent.includes('nothing to play'));
    await loadSkin(page);
    await page.waitForFunction(() => !document.querySelector('#timeline').hidden);
  });
});

describe('timeline and context loss', () => {
  test('the time survives a lost context, and playing goes on after it', { timeout: 120000 }, async () => {
    const session = await startBrowser();
    try {
      const page = await openPage(await session.newContext(), `${session.baseUrl}?view=split`);
      await loadSkin(page);
      await page.evaluate(() => window.obscura.setTime(0.25));  // the strip bends from 0 to 1 s
      await waitForDrawn(page);
      assert.equal((await timeline(page)).time, 0.25);
      const before = await snapshot(page);
      await page.evaluate(() => {
        window.loseContext = document.querySelector('#view').getContext('webgl').getExtension('WEBGL_lose_context');
        window.loseContext.loseContext();
      });
      await page.waitForFunction(() => window.obscura.stats().contextLost, null, { timeout: 30000 });
      await page.evaluate(() => window.loseContext.restoreContext());
      await page.waitForFunction(() => window.obscura.stats().contextRestores === 1, null, { timeout: 30000 });
      await waitForDrawn(page);
      assert.equal((await timeline(page)).time, 0.25);
      const after = await snapshot(page);
      assert.equal(compareImages(before, after).max, 0, 'the same frame after the restore');

      const frames = (await page.evaluate(() => window.obscura.stats())).frames;
      await page.evaluate(() => window.obscura.play());
      await page.waitForFunction((f) => window.obscura.stats().frames > f + 3 && window.obscura.time > 0.6, frames,
                                 { timeout: 60000, polling: 50 });
      await page.evaluate(() => window.obscura.pause());
      assert.ok(compareImages(after, await snapshot(page)).max > 0, 'the restored context plays the animation');
      assert.deepEqual(page.errors, []);
    } finally {
      await session.close();
    }
  });
});
