// The depth hierarchy's three storages on WebGL 1 (src/effects/ao/DepthHierarchyPass.h): separate textures and the
// atlas (core WebGL 1) and the mip chain (OES_fbo_render_mipmap + EXT_shader_texture_lod) hold the same bytes, so the
// raw AO must agree within 1/255 whichever one the shader reads.
import assert from 'node:assert/strict';
import { after, before, describe, test } from 'node:test';
import { compareImages, openPage, snapshot, startBrowser, waitForDrawn } from './harness.mjs';

let session;
let page;

describe('depth hierarchy storages on WebGL 1', () => {
  before(async () => {
    session = await startBrowser();
    // A 3 m radius sends far taps to levels 3 to 5; with one layer the hierarchy is built only when asked for.
    page = await openPage(await session.newContext(), `${session.baseUrl}?view=ao-raw&radius=3&ao.hierarchy=on`);
  });
  after(async () => {
    if (page) assert.deepEqual(page.errors, []);
    await session?.close();
  });

  test('separate textures, atlas and mip chain give the same AO', { timeout: 180000 }, async (t) => {
    // The mip chain needs both extensions; where the browser offers them it must be used (Debian's Chromium does,
    // on SwiftShader too), and only where it does not is that storage skipped, visibly.
    const extensions = await page.evaluate(() => document.createElement('canvas').getContext('webgl')
      .getSupportedExtensions());
    const mipChainPossible = ['OES_fbo_render_mipmap', 'EXT_shader_texture_lod'].every((e) => extensions.includes(e));
    const storages = mipChainPossible ? ['separate', 'atlas', 'mipchain'] : ['separate', 'atlas'];
    if (!mipChainPossible) t.diagnostic('this WebGL 1 context lacks the mip-chain extensions: mipchain not compared');
    const images = {};
    for (const storage of storages) {
      const used = await page.evaluate((s) => window.obscura.setHierarchyStorage(s), storage);
      assert.equal(used, storage, `asked for ${storage}, got ${used}`);
      await waitForDrawn(page);
      images[storage] = await snapshot(page);
    }
    assert.ok(images.separate && images.atlas);
    const names = Object.keys(images);
    for (const other of names.slice(1)) {
      const difference = compareImages(images[names[0]], images[other]);
      console.log(`${other} vs ${names[0]}: mean ${difference.mean.toFixed(4)}, max ${difference.max}`);
      assert.ok(difference.max <= 1, `${other} differs from ${names[0]} by up to ${difference.max}/255`);
    }
    // Back to the context's own choice, which the rest of the page uses.
    const chosen = await page.evaluate(() => window.obscura.setHierarchyStorage('auto'));
    assert.equal(chosen, mipChainPossible ? 'mipchain' : 'atlas');
  });
});
