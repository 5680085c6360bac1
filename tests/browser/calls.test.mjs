// WebGL calls per frame on the demo page's default frame. In a browser every call crosses from WebAssembly into
// JavaScript and through WebGL's validation, whatever the driver then does with it: the host time of a frame is
// largely its calls. The G-buffer pass sets face culling, the winding, a material's textures and its uniforms only
// where they differ from the draw before (gpu/GpuScene.cpp), and a uniform the program does not have costs no call
// (gl::Program::set), and where OES_vertex_array_object exists a piece's streams are bound with its object. The bound
// holds the default frame to that: it made 1006 calls before, 583 after, 450 with the objects (589 without); 286
// when each pass put back only what it set, 208 with the still room in static batches (gpu/GpuScene.h), 193 with
// the full-screen triangle's stream in a vertex array object of its own, 129 with the binding cache (gl/BindingCache.h:
// a pass's unbinds and the next one's binds of the same objects cancel) and no scissor or clear where the scene fills
// the frame.
import assert from 'node:assert/strict';
import { after, before, describe, test } from 'node:test';
import { countWebGlCalls } from '../../tools/headless-chromium.mjs';
import { compareImages, openPage, snapshot, startBrowser, waitForDrawn } from './harness.mjs';

let session;
let page;

// After `change(argument)` in the page (what it returns: `used`), the image drawn, the WebGL calls of the next
// frame, counted by method, and its stats.
async function frameWith(change, argument) {
  const used = await page.evaluate(change, argument);
  await waitForDrawn(page);
  const image = await snapshot(page);
  const frame = await page.evaluate(() => {
    const o = window.obscura;
    o.pause();
    o.draw();
    window.glCalls = {};
    o.draw();
    const calls = { ...window.glCalls };  // before stats(), which may make calls of its own
    return { calls, stats: o.stats() };
  });
  return { used, image, ...frame };
}

describe('WebGL calls per frame', () => {
  before(async () => {
    session = await startBrowser();
    const context = await session.newContext();
    await context.addInitScript(countWebGlCalls);
    // Without the harness's debug-gl: its glGetError and state checks after every pass are calls of their own.
    page = await openPage(context, session.baseUrl, { debugGl: false });
  });
  after(async () => {
    if (page) assert.deepEqual(page.errors, []);
    await session?.close();
  });

  test('the default frame makes at most 145 calls', { timeout: 120000 }, async () => {
    const { frames, calls } = await page.evaluate(() => {
      const o = window.obscura;
      o.pause();
      o.draw();  // the programs of this state are built: the frames counted draw only
      window.glCalls = {};
      const frames = 4;
      for (let i = 0; i < frames; ++i) o.draw();
      return { frames, calls: window.glCalls };
    });
    const perFrame = Object.entries(calls).map(([name, n]) => [name, n / frames]).sort((a, b) => b[1] - a[1]);
    const total = perFrame.reduce((sum, [, n]) => sum + n, 0);
    console.log(`${total} WebGL calls per frame: ` + perFrame.map(([name, n]) => `${name} ${n}`).join(', '));
    const draws = (calls.drawElements ?? 0) / frames;
    // The still room's 28 instances in 7 draws (static batches, gpu/GpuScene.h), the pendulum's 3 and the limb.
    assert.ok(draws >= 8, `the built-in scene's G-buffer pass should draw its pieces, drew ${draws}`);
    assert.ok(total <= 145, `${total} WebGL calls per frame (at most 145)`);
  });

  // OES_vertex_array_object is an extension: the draws without it (each piece's streams set per draw) stay, and
  // give the same image; with it, a draw binds its piece's object (one call) instead.
  test('vertex array objects: the same image, fewer calls', { timeout: 120000 }, async () => {
    const frame = (allow) => frameWith((a) => window.obscura.setVertexArrays(a), allow);
    const without = await frame(false);
    const withObjects = await frame(true);
    assert.equal(without.used, false);
    const extension = await page.evaluate(() => document.createElement('canvas').getContext('webgl')
      .getSupportedExtensions().includes('OES_vertex_array_object'));
    assert.equal(withObjects.used, extension, 'the objects are used wherever the extension exists');
    const difference = compareImages(without.image, withObjects.image);
    assert.equal(difference.max, 0, `the images differ by up to ${difference.max}/255`);
    const total = (calls) => Object.values(calls).reduce((sum, n) => sum + n, 0);
    console.log(`calls per frame: ${total(without.calls)} without vertex array objects, ` +
                `${total(withObjects.calls)} with (bindVertexArrayOES ${withObjects.calls.bindVertexArrayOES ?? 0})`);
    if (extension) assert.ok(total(withObjects.calls) < total(without.calls));
  });

  // Static batches: the still room's instances that share a material drawn as one piece in world space. The image is
  // the same (the vertex stage places the batch's vertices with the view alone); the calls are fewer.
  test('static batches: the same image, fewer calls', { timeout: 120000 }, async () => {
    const frame = (allow) => frameWith((a) => window.obscura.setStaticBatches(a), allow);
    const alone = await frame(false);
    const batched = await frame(true);
    assert.equal(alone.used, 0);
    assert.equal(batched.used, 4, 'the walls, the stone, the blue spheres and the wooden boxes');
    const difference = compareImages(alone.image, batched.image);
    assert.ok(difference.max <= 4, `the images differ by up to ${difference.max}/255`);
    const total = (calls) => Object.values(calls).reduce((sum, n) => sum + n, 0);
    console.log(`calls per frame: ${total(alone.calls)} with every instance drawn alone, ${total(batched.calls)} ` +
                `batched (drawElements ${alone.calls.drawElements} -> ${batched.calls.drawElements})`);
    assert.ok(batched.calls.drawElements <= alone.calls.drawElements - 21);
    // The stats count the geometry pass's draw calls (the default frame has one such pass).
    assert.equal(batched.stats.drawCalls, batched.calls.drawElements);
    assert.equal(alone.stats.drawCalls, alone.calls.drawElements);
    assert.ok(total(batched.calls) < total(alone.calls));
    // State the draws share is set once per run of draws that share it, not once per draw (the frame drawn alone
    // has a draw per instance).
    const shared = ['frontFace', 'enable', 'disable'].reduce((sum, name) => sum + (alone.calls[name] ?? 0), 0);
    assert.ok(shared <= alone.calls.drawElements,
              `${shared} frontFace/enable/disable calls for ${alone.calls.drawElements} draws`);
  });
});
