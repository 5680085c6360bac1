// The cameras in the page (issue 31): the free camera made orthographic (the page's box, the key x, the JS API) and a
// glTF file's own cameras (Debian's Cameras.gltf: a perspective and an orthographic camera on nodes) in the Camera
// menu, the key v and the JS API; the URL keeps each (projection=orthographic&ymag=, camera=), its state reproduces
// the frame pixel for pixel in a new page, and the file's orthographic camera draws what obscura-render
// --camera-node draws.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, describe, test } from 'node:test';
import { decodePng } from './png.mjs';
import {
  artifactDir, assimpModels, compareImages, openPage, readModel, renderBinary, snapshot, startBrowser, waitForDrawn,
} from './harness.mjs';

let session;
let page;

const cameraGltf = Array.from(readModel('cameras/Cameras.gltf'));
const cameraBin = Array.from(readModel('cameras/simpleSquare.bin'));
const loadCameras = (p) => p.evaluate(async ([gltf, bin]) => {
  await window.obscura.loadScene(new Uint8Array(gltf), 'Cameras.gltf', { 'simpleSquare.bin': new Uint8Array(bin) });
}, [cameraGltf, cameraBin]);
const camera = (p = page) => p.evaluate(() => window.obscura.camera());

// The page's URL once it holds `key=value` (it follows changes a few times a second).
async function urlWith(p, key, value) {
  await p.waitForFunction(([k, v]) => new URLSearchParams(location.search).get(k) === v, [key, value]);
  return p.evaluate(() => location.href);
}

// Opens the URL in a new page (which loads Cameras.gltf first when `withFile`, as a user who has the file would, then
// applies the URL's state) and checks it draws `expected`'s pixels with the same camera.
async function reproduces(url, expected, withFile) {
  const other = await openPage(await session.newContext(), url);
  try {
    if (withFile) {
      await loadCameras(other);
      const state = new URL(url).searchParams;
      state.delete('debug-gl');
      await other.evaluate((query) => window.obscura.setState(query), state.toString());
    }
    await waitForDrawn(other);
    const difference = compareImages(expected.image, await snapshot(other));
    assert.equal(difference.max, 0, `the same pixels (max difference ${difference.max})`);
    const there = await camera(other);
    assert.equal(there.choice, expected.camera.choice);
    assert.equal(there.orthographic, expected.camera.orthographic);
    assert.deepEqual(other.errors, []);
  } finally {
    await other.close();
  }
}

describe('cameras', () => {
  before(async () => {
    session = await startBrowser();
    page = await openPage(await session.newContext(), session.baseUrl);
  });
  after(async () => {
    if (page) assert.deepEqual(page.errors, [], 'console errors during the camera tests');
    await session?.close();
  });

  test('the free camera made orthographic: box, key and API, kept by the URL', { timeout: 180000 }, async () => {
    const start = await camera();
    assert.equal(start.choice, 'free');
    assert.equal(start.orthographic, false);
    assert.deepEqual(start.cameras, [], 'the built-in scene has no cameras of its own');
    assert.equal(await page.locator('#camera').isDisabled(), true);
    const perspective = await snapshot(page);
    await page.locator('#orthographic').check();
    await waitForDrawn(page);
    const ortho = await camera();
    assert.equal(ortho.orthographic, true);
    // The same view at the target: ymag is the perspective view's half height there.
    const distance = Math.hypot(...ortho.eye.map((e, i) => e - ortho.target[i]));
    assert.ok(Math.abs(ortho.ymag - distance * Math.tan((ortho.fovy * Math.PI) / 360)) < 1e-3 * ortho.ymag,
              JSON.stringify(ortho));
    const image = await snapshot(page);
    assert.ok(compareImages(perspective, image).max > 0, 'the projection changed the image');
    const url = await urlWith(page, 'projection', 'orthographic');
    assert.ok(new URL(url).searchParams.has('ymag'), url);
    await reproduces(url, { image, camera: ortho }, false);

    // The key x and the API switch it back; the box follows.
    await page.locator('#view').click({ position: { x: 10, y: 10 } });
    await page.keyboard.press('x');
    await waitForDrawn(page);
    assert.equal((await camera()).orthographic, false);
    assert.equal(await page.locator('#orthographic').isChecked(), false);
    // The same eye again (to float rounding); the planes refitted to the scene, as after any move, so the frame
    // differs by depth quantisation only.
    const back = await camera();
    const size = Math.hypot(...start.eye);
    assert.ok(back.eye.every((e, i) => Math.abs(e - start.eye[i]) < 1e-4 * size), JSON.stringify(back));
    const difference = compareImages(perspective, await snapshot(page));
    assert.ok(['r', 'g', 'b'].every((c) => difference[c].mean < 0.5), JSON.stringify(difference));
    await page.evaluate(() => window.obscura.setOrthographic(true));
    assert.equal(await page.locator('#orthographic').isChecked(), true);
    await page.evaluate(() => window.obscura.setOrthographic(false));
    const refused = await page.evaluate(() => {
      try {
        window.obscura.setCamera('0');
        return '';
      } catch (e) {
        return `${e.name}: ${e.message}`;
      }
    });
    assert.match(refused, /ObscuraError: camera '0': the scene has no cameras of its own/);
  });

  test("a file's cameras in the Camera menu, the key v and the API, kept by the URL", { timeout: 180000 }, async () => {
    await loadCameras(page);
    await waitForDrawn(page);
    const loaded = await camera();
    assert.equal(loaded.choice, 'free', 'a scene loaded starts on the free camera');
    assert.deepEqual(loaded.cameras, [{ name: 'camera 0', orthographic: false },
                                      { name: 'camera 1', orthographic: true }]);
    assert.equal(await page.locator('#camera').isDisabled(), false);
    assert.deepEqual(await page.locator('#camera option').allTextContents(),
                     ['Free (orbit)', 'camera 0', 'camera 1 (orthographic)']);
    const free = await snapshot(page);

    // The menu.
    await page.locator('#camera').selectOption('1');
    await waitForDrawn(page);
    const through = await camera();
    assert.equal(through.choice, '1');
    assert.equal(through.orthographic, true);
    assert.equal(await page.locator('#orthographic').isChecked(), true, 'the box shows the projection shown');
    const image = await snapshot(page);
    assert.ok(compareImages(free, image).max > 0);
    const url = await urlWith(page, 'camera', '1');
    await reproduces(url, { image, camera: through }, true);

    // The key v goes on to the free camera, then the first of the file's.
    await page.locator('#view').click({ position: { x: 10, y: 10 } });
    await page.keyboard.press('v');
    assert.equal((await camera()).choice, 'free');
    await page.keyboard.press('v');
    assert.equal((await camera()).choice, '0');
    assert.equal(await page.locator('#camera').inputValue(), '0');
    // A drag takes the view over as the free camera.
    await page.evaluate(() => window.obscura.orbit(20, 0));
    assert.equal((await camera()).choice, 'free');
    await page.evaluate(() => window.obscura.setCamera('free'));
  });

  test("the file's orthographic camera draws what obscura-render --camera-node draws", { timeout: 180000 },
    async () => {
      await page.evaluate(() => {
        window.obscura.setView('normals');
        window.obscura.setCamera(1);
      });
      await waitForDrawn(page);
      const browser = await snapshot(page);
      const out = path.join(artifactDir, 'native_camera_node.png');
      execFileSync(renderBinary, ['--scene', path.join(assimpModels, 'cameras', 'Cameras.gltf'), '--camera-node', '1',
                                  '--view', 'normals', '--size', `${browser.width}x${browser.height}`, '--out', out]);
      const native = decodePng(fs.readFileSync(out));
      const difference = compareImages(browser, native);
      for (const channel of ['r', 'g', 'b']) {
        assert.ok(difference[channel].mean <= 1.0, `${channel}: mean ${difference[channel].mean}`);
      }
      await page.evaluate(() => window.obscura.setView('final'));
    });
});
