// Compressed glTF in the browser (web/gltf-decoders.js): the Draco copy of 2CylinderEngine, decoded by the npm
// draco3d decoder the site carries, shows the same mask as the uncompressed .glb; without the decoder the file is
// refused with one line naming what is missing, and the previous scene stays.
import assert from 'node:assert/strict';
import { after, before, describe, test } from 'node:test';
import fs from 'node:fs';
import path from 'node:path';
import { openPage, readModel, snapshot, sourceDir, startBrowser, waitForDrawn } from './harness.mjs';

let session;

// Loads a scene from bytes handed over as base64 (side files likewise); resolves to the scene or the error message.
async function load(page, name, bytes, sideFiles = {}) {
  const encoded = Object.fromEntries(Object.entries(sideFiles).map(([uri, data]) => [uri, data.toString('base64')]));
  return page.evaluate(async ({ name: n, base64, side }) => {
    const decode = (text) => Uint8Array.from(atob(text), (c) => c.charCodeAt(0));
    const files = Object.fromEntries(Object.entries(side).map(([uri, text]) => [uri, decode(text)]));
    try {
      return { scene: await window.obscura.loadScene(decode(base64), n, files) };
    } catch (e) {
      return { error: e.message, kind: e.name };
    }
  }, { name, base64: bytes.toString('base64'), side: encoded });
}

function maskFraction(image) {
  let covered = 0;
  for (let i = 0; i < image.pixels.length; i += 4) covered += image.pixels[i] > 127;
  return covered;
}

describe('compressed glTF in the browser', () => {
  before(async () => { session = await startBrowser(); });
  after(async () => { await session?.close(); });

  test('the Draco engine looks as the uncompressed one', { timeout: 180000 }, async () => {
    const page = await openPage(await session.newContext(), `${session.baseUrl}?view=mask`);
    try {
      const draco = await load(page, '2CylinderEngine.gltf', readModel('draco/2CylinderEngine.gltf'),
                               { '2CylinderEngine.bin': readModel('draco/2CylinderEngine.bin') });
      assert.equal(draco.error, undefined, draco.error);
      await waitForDrawn(page);
      const dracoMask = await snapshot(page);
      const plain = await load(page, '2CylinderEngine.glb', readModel('2CylinderEngine-glTF-Binary/2CylinderEngine.glb'));
      assert.equal(plain.error, undefined, plain.error);
      await waitForDrawn(page);
      const plainMask = await snapshot(page);
      let differing = 0;
      for (let i = 0; i < plainMask.pixels.length; i += 4) {
        differing += (dracoMask.pixels[i] > 127) !== (plainMask.pixels[i] > 127);
      }
      const covered = maskFraction(plainMask);
      console.log(`Draco vs .glb mask: ${differing} of ${covered} covered pixels differ`);
      assert.ok(covered > 2000, `the engine covers only ${covered} pixels`);
      assert.ok(differing <= 0.01 * covered, `${differing} pixels differ`);
      assert.deepEqual(page.errors, []);
    } finally {
      await page.close();
    }
  });

  test('a meshopt file with quantized attributes, and points and lines, are drawn', { timeout: 180000 }, async () => {
    const page = await openPage(await session.newContext(), `${session.baseUrl}?view=mask`);
    try {
      // The fuzzer's seed (tests/fuzz/seeds/make-compressed-seeds.mjs): a meshopt grid, u16 positions, octahedral
      // normals, data only compressed.
      const seed = fs.readFileSync(path.join(sourceDir, 'tests', 'fuzz', 'seeds', 'meshopt-quantized.glb'));
      const grid = await load(page, 'meshopt-quantized.glb', seed);
      assert.equal(grid.error, undefined, grid.error);
      assert.equal(grid.scene.triangles, 128);
      await waitForDrawn(page);
      const covered = maskFraction(await snapshot(page));
      assert.ok(covered > 2000, `the meshopt grid covers only ${covered} pixels`);
      // Lines: white on the background in the final image, and nothing in the G-buffer's mask.
      const lines = await load(page, 'Mesh_PrimitiveMode_01.gltf',
                               readModel('glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_01.gltf'),
                               { 'Mesh_PrimitiveMode_01.bin':
                                 readModel('glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_01.bin') });
      assert.equal(lines.error, undefined, lines.error);
      await waitForDrawn(page);
      assert.equal(maskFraction(await snapshot(page)), 0, 'lines are not in the G-buffer');
      await page.evaluate(() => window.obscura.setView('final'));
      await waitForDrawn(page);
      const image = await snapshot(page);
      let white = 0;
      for (let i = 0; i < image.pixels.length; i += 4) {
        white += image.pixels[i] > 200 && image.pixels[i + 1] > 200 && image.pixels[i + 2] > 200;
      }
      console.log(`lines: ${white} white pixels of ${image.pixels.length / 4}`);
      assert.ok(white > 100, `only ${white} pixels of the lines`);
      assert.deepEqual(page.errors, []);
    } finally {
      await page.close();
    }
  });

  test('without the decoder, a Draco file is refused with one line', { timeout: 180000 }, async () => {
    const context = await session.newContext();
    await context.route((url) => url.pathname.includes('/decoders/draco'), (route) => route.fulfill({ status: 404 }));
    const page = await openPage(context, session.baseUrl);
    try {
      const before = await page.evaluate(() => window.obscura.scene());
      const result = await load(page, '2CylinderEngine.gltf', readModel('draco/2CylinderEngine.gltf'),
                                { '2CylinderEngine.bin': readModel('draco/2CylinderEngine.bin') });
      assert.equal(result.kind, 'ObscuraError');
      assert.match(result.error, /^2CylinderEngine\.gltf: KHR_draco_mesh_compression: the Draco decoder .* could not be loaded$/);
      assert.doesNotMatch(result.error, /\n/);
      assert.deepEqual(await page.evaluate(() => window.obscura.scene()), before, 'the previous scene stays');
      // The 404s this test arranged are the only errors.
      assert.ok(page.errors.every((e) => /decoders\/draco|404|Failed to load resource/.test(e)), page.errors.join('\n'));
    } finally {
      await page.close();
    }
  });
});
