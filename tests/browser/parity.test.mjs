// Parity: the browser's AO view and final image of the built-in scene (WebGL 1 through ANGLE on SwiftShader) against
// the headless native renderer's (Mesa llvmpipe through OSMesa and through EGL/GLES 2), at the same camera, size and
// parameters.
// The figures (mean and max absolute difference per channel, 0..255) are printed and written to parity.json in the
// artefact folder; README.md quotes them.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, describe, test } from 'node:test';
import { decodePng } from './png.mjs';
import { artifactDir, compareImages, openPage, renderBinary, snapshot, startBrowser } from './harness.mjs';

// Blurred AO averages a few of SAO's noisy taps; raw AO is reported too, but only the view users see is held to
// the bound. Mean <= 1/255 per channel means the two implementations agree up to 8-bit rounding on average.
const MEAN_BOUND = 1.0;
// Where they differ they may differ a lot (a tap landing on either side of a depth edge), but only in few pixels.
const FEW_PIXELS = 0.01;
const LARGE_DIFFERENCE = 16;

let session;
let page;
const report = { size: '320x180', scene: 'built-in', camera: 'builtinSceneCamera', views: {} };

function nativeAo(view, backend) {
  const out = path.join(artifactDir, `native_${view}_${backend}.png`);
  execFileSync(renderBinary, ['--size', '320x180', '--view', view, '--backend', backend, '--out', out]);
  return decodePng(fs.readFileSync(out));
}

function largeFraction(a, b) {
  let large = 0;
  for (let i = 0; i < a.pixels.length; i += 4) {
    if ([0, 1, 2].some((c) => Math.abs(a.pixels[i + c] - b.pixels[i + c]) > LARGE_DIFFERENCE)) large += 1;
  }
  return large / (a.width * a.height);
}

describe('browser vs native parity', () => {
  before(async () => {
    session = await startBrowser();
    page = await openPage(await session.newContext(), `${session.baseUrl}?view=ao`);
  });
  after(async () => {
    fs.writeFileSync(path.join(artifactDir, 'parity.json'), `${JSON.stringify(report, null, 2)}\n`);
    console.log(JSON.stringify(report, null, 2));
    if (page) assert.deepEqual(page.errors, []);
    await session?.close();
  });

  // The final image too: the canvas is not multisampled any more (FXAA antialiases), so both draw the same way.
  for (const view of ['ao', 'ao-raw', 'final']) {
    test(`${view} view of the built-in scene`, { timeout: 120000 }, async () => {
      await page.evaluate((mode) => window.obscura.setView(mode), view);
      const browser = await snapshot(page);
      assert.equal(browser.width, 320);
      fs.writeFileSync(path.join(artifactDir, `browser_${view}.rgba`), browser.pixels);
      for (const backend of ['osmesa', 'egl']) {
        const native = nativeAo(view, backend);
        const difference = compareImages(browser, native);
        const large = largeFraction(browser, native);
        const round = (x) => Number(x.toFixed(3));
        report.views[`${view} vs ${backend}`] = {
          mean: { r: round(difference.r.mean), g: round(difference.g.mean), b: round(difference.b.mean) },
          max: { r: difference.r.max, g: difference.g.max, b: difference.b.max },
          pixelsDiffering: round(difference.r.differing),
          [`pixelsOver${LARGE_DIFFERENCE}`]: round(large),
        };
        if (view !== 'ao-raw') {
          for (const channel of ['r', 'g', 'b']) {
            assert.ok(difference[channel].mean <= MEAN_BOUND,
                      `${backend} ${channel}: mean ${difference[channel].mean} > ${MEAN_BOUND}`);
          }
          assert.ok(large <= FEW_PIXELS, `${backend}: ${large} of the pixels differ by more than ${LARGE_DIFFERENCE}`);
        }
      }
    });
  }
});
