// What each effect costs in the browser: the GPU milliseconds of its passes (from EXT_disjoint_timer_query, which
// SwiftShader offers) in the demo page's frame of the built-in scene, playing its animation so that motion blur and
// the temporal effects have motion to work on, at each size asked. Every effect of the table is measured with its
// switch on (the others at their defaults), and the AO's temporal accumulation beside the single-frame AO; then the
// lighting pass on the metallic-roughness sample (assets/scenes/pbr-samples.glb) loaded into the page; then the
// transparent layer, transmission and clear coat on the glass sample (assets/scenes/glass-samples.glb), and on variants
// of it edited here that put each over most of the frame (every opaque material blended, transmissive, clear-coated
// or without the material layers: the clear coat's cost is the lighting's difference). The camera's finish adds
// percentile metering, six streaks, hatching, and the tone mapping with the exposure and the lens light it reads
// against the tone mapping with bloom alone (what those stages add to the pass they join). The display colour's
// stages (grading, with its balance and with a .cube LUT loaded through loadLut, the vignette, the grain, the dithering)
// run inside the lighting's pass: each is timed as the lighting pass with it on against the lighting without dithering
// (--effects grading,vignette,grain,dither runs those alone). Writes a CSV;
// docs/benchmarks.md ("Every effect at two sizes") and docs/transparency.md show the figures.
//
// Usage: node tools/browser-bench/effect-costs.mjs [--sizes 640x360,1280x720] [--samples N] [--settle MS] [--csv FILE]
//                                                  [--effects NAME,...]  (only these effects' cases; default: all)
//   (defaults: both sizes, 7 timer readings per case, 2500 ms for each case's shaders to compile and its first
//   timer results to come back, bench-results/browser-effects.csv; --effects: only the cases of these effects)
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startServer } from '../serve-web.mjs';
import { chromiumLaunchOptions, median, openDemoPage, parseOptions, parseSizes } from '../headless-chromium.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
const options = { sizes: '640x360,1280x720', samples: 7, settle: 2500,
                  csv: path.join(root, 'bench-results', 'browser-effects.csv'), effects: '' };
parseOptions(process.argv.slice(2), {
  '--sizes': (v) => { options.sizes = v; },
  '--samples': (v) => { options.samples = Number(v); },
  '--settle': (v) => { options.settle = Number(v); },
  '--csv': (v) => { options.csv = path.resolve(v); },
  '--effects': (v) => { options.effects = v.split(','); },
}, path.basename(import.meta.url));
const sizes = parseSizes(options.sizes);
if (!sizes.every(([w, h]) => w > 0 && h > 0) || !(options.samples > 0 && options.settle >= 0))
  throw new Error('--sizes WxH,... and --samples N must be positive, --settle MS not negative');

// The cases: each effect with its switch on (its own passes timed), and the AO's variants that the issues set
// targets for (the temporal accumulation at 4 taps against the single frame's default), where the table has them.
function casesOf(description) {
  const names = new Set(description.parameters.map((p) => p.name));
  // An effect whose passes do not run in the final frame (the motion vectors, which only the motion effects read;
  // the tone curve, which the lighting applies) is timed again showing its target's view.
  // The display colour's stages have no pass of their own to time (below: what they add to the lighting's).
  const displayStages = ['grading', 'vignette', 'grain', 'dither'];
  const cases = description.effects.filter((e) => !displayStages.includes(e.name)).map((e) => ({
    label: e.name, effect: e.name, passes: e.passes, state: e.switch ? `${e.name}=on` : '',
    fallbackView: e.targets.flatMap((t) => t.views)[0] }));
  const ao = description.effects.find((e) => e.name === 'ao');
  if (ao && names.has('ao.temporal')) {
    cases.push({ label: 'ao 4 taps', effect: 'ao', passes: ao.passes, state: 'ao=on&ao.samples=4' });
    cases.push({ label: 'ao temporal 4 taps', effect: 'ao', passes: ao.passes,
                 state: 'ao=on&ao.temporal=on&ao.samples=4' });
  }
  // The camera's finish (issue 29): percentile metering, a six-streak star, hatching; and the tone-mapping pass with
  // what it joins (the exposure texel, the lens light's upsample) against the same pass with bloom alone, which keeps
  // it from being absorbed by the lighting too.
  const byName = (name) => description.effects.find((e) => e.name === name);
  const tonemap = byName('tonemap');
  if (byName('auto-exposure'))
    cases.push({ label: 'auto-exposure percentile', effect: 'auto-exposure', passes: byName('auto-exposure').passes,
                 state: 'auto-exposure=on&auto-exposure.metering=percentile' });
  if (byName('glare'))
    cases.push({ label: 'glare 6 streaks', effect: 'glare', passes: byName('glare').passes,
                 state: 'glare=on&glare.streaks=6' });
  if (names.has('edges.style'))
    cases.push({ label: 'edges hatching', effect: 'edges', passes: byName('edges').passes,
                 state: 'edges=on&edges.style=hatching' });
  if (tonemap && byName('bloom')) {
    cases.push({ label: 'tonemap, bloom on', effect: 'tonemap', passes: tonemap.passes, state: 'bloom=on' });
    if (byName('auto-exposure'))
      cases.push({ label: 'tonemap, auto exposure', effect: 'tonemap', passes: tonemap.passes,
                   state: 'bloom=on&auto-exposure=on' });
    if (byName('lens-flare'))
      cases.push({ label: 'tonemap, lens light', effect: 'tonemap', passes: tonemap.passes,
                   state: 'bloom=on&lens-flare=on' });
  }
  // Issue 29's display stages, fused into the lighting: its pass without dithering, with it (the default), and with
  // each stage on; grading's LUT is the one loaded into the page (lutPath), 33 points a side.
  if (byName('dither')) {
    const balance = 'grading=on&grading.temperature=5000&grading.saturation=1.2&grading.contrast=1.1';
    const lut = `grading=on&grading.lut=${lutPath}`;
    for (const [label, effect, state] of [
      ['lighting, dither off', 'dither', 'dither=off'], ['lighting, dither (default)', 'dither', ''],
      ['lighting, grading balance', 'grading', balance], ['lighting, grading LUT', 'grading', lut],
      ['lighting, grading both', 'grading', `${balance}&grading.lut=${lutPath}`],
      ['lighting, vignette', 'vignette', 'vignette=on'], ['lighting, grain', 'grain', 'grain=on'],
      ['lighting, all four', 'grading', `${balance}&grading.lut=${lutPath}&vignette=on&grain=on`]])
      cases.push({ label, effect, passes: ['lighting'], state });
  }
  return options.effects ? cases.filter((c) => options.effects.includes(c.effect)) : cases;
}

// A warm grade as a 33-point .cube (what a grading tool writes), for the grading LUT's cases.
const lutPath = '/luts/bench-warm.cube';
function warmCube() {
  const n = 33;
  let text = 'LUT_3D_SIZE 33\n';
  for (let b = 0; b < n; ++b)
    for (let g = 0; g < n; ++g)
      for (let r = 0; r < n; ++r)
        text += `${Math.min(1, 1.05 * r / (n - 1) + 0.02).toFixed(5)} ${(g / (n - 1)).toFixed(5)} ` +
                `${(0.85 * b / (n - 1)).toFixed(5)}\n`;
  return text;
}

// A .glb's JSON chunk edited by `edit` (the binary chunk kept), as a buffer for the page's file input.
function editedGlb(file, edit) {
  const bytes = fs.readFileSync(file);
  const jsonLength = bytes.readUInt32LE(12);
  const json = JSON.parse(bytes.subarray(20, 20 + jsonLength).toString('utf8'));
  edit(json);
  let text = Buffer.from(JSON.stringify(json), 'utf8');
  if (text.length % 4) text = Buffer.concat([text, Buffer.alloc(4 - (text.length % 4), 0x20)]);
  const rest = bytes.subarray(20 + jsonLength);
  const header = Buffer.alloc(20);
  header.write('glTF', 0);
  header.writeUInt32LE(2, 4);
  header.writeUInt32LE(20 + text.length + rest.length, 8);
  header.writeUInt32LE(text.length, 12);
  header.writeUInt32LE(0x4e4f534a, 16);  // JSON
  return Buffer.concat([header, text, rest]);
}

const rows = [];
function writeCsv() {
  fs.mkdirSync(path.dirname(options.csv), { recursive: true });
  fs.writeFileSync(options.csv, 'effect,width,height,effect_ms,frame_ms,readings\n' +
    rows.map((r) => `${r.label},${r.width},${r.height},${r.effectMs.toFixed(2)},${r.frameMs.toFixed(2)},${r.readings}`)
      .join('\n') + '\n');
}

const server = await startServer(process.env.OBSCURA_WEB_SITE ?? path.join(root, 'build-web', 'site'));
const browser = await chromium.launch(chromiumLaunchOptions);
try {
  for (const [width, height] of sizes) {
    const demo = `http://127.0.0.1:${server.address().port}/`;
    const { page, errors } = await openDemoPage(browser, demo, width, height);
    const description = await page.evaluate(() => {
      const o = window.obscura;
      return { effects: o.effects, parameters: o.parameters, timerQuery: o.context.timerQuery,
               renderer: o.context.renderer };
    });
    if (!description.timerQuery) throw new Error('this browser offers no EXT_disjoint_timer_query: no per-pass times');
    if (description.effects.some((e) => e.name === 'grading'))
      await page.evaluate((cube) => window.obscura.loadLut(cube, 'bench-warm.cube'), warmCube());
    console.log(`${width}x${height}, ${description.renderer}, the built-in scene playing`);
    const measure = (state, passes) => page.evaluate(async ({ state, passes, samples, settle }) => {
      const o = window.obscura;
      // From the defaults each time (a setState only changes what it names), playing from 1 s.
      const query = new URLSearchParams();
      for (const p of o.parameters) if (p.name !== 'preset' && !p.name.endsWith('.preset')) query.set(p.name, p.default);
      query.set('resolution.dynamic', 'off');  // the canvas's full size (fixedScaleUrl)
      for (const [key, value] of new URLSearchParams(state)) query.set(key, value);
      query.set('time', '1');
      query.set('play', 'on');
      if (!query.has('view')) query.set('view', 'final');
      o.setState(query.toString());
      o.setContinuous(true);
      await new Promise((r) => setTimeout(r, settle));
      const effect = [], frame = [];
      let last = null, framesWithout = 0;
      for (let tries = 0; effect.length < samples && tries < 20 * samples; ++tries) {
        await new Promise((r) => setTimeout(r, 150));
        const s = o.stats();
        if (s.frames === last) continue;
        last = s.frames;
        // Three frames in a row without the case's passes (a stage fused into another pass, a layer with nothing to
        // draw): no reading will come, and the case is reported without one rather than waited on.
        framesWithout = passes.some((p) => s.passesRun.includes(p)) ? 0 : framesWithout + 1;
        if (framesWithout >= 3) break;
        if (!s.passMs) continue;
        const timed = passes.filter((p) => s.passMs[p] !== null && s.passMs[p] !== undefined);
        if (!timed.length) continue;
        effect.push(timed.reduce((sum, p) => sum + s.passMs[p], 0));
        if (s.frameMs > 0) frame.push(s.frameMs);
      }
      o.setContinuous(false);
      o.pause();
      return { effect, frame };
    }, { state, passes, samples: options.samples, settle: options.settle });
    const report = (label, result) => {
      const row = { label, width, height,
                    effectMs: result.effect.length ? median(result.effect) : NaN,
                    frameMs: result.frame.length ? median(result.frame) : NaN, readings: result.effect.length };
      rows.push(row);
      console.log(`${label.padEnd(28)} ${row.effectMs.toFixed(2).padStart(8)} ms   frame ` +
                  `${row.frameMs.toFixed(1).padStart(7)} ms   (${row.readings} readings)`);
      writeCsv();  // after every case, so a run cut short keeps what it measured
    };
    for (const c of casesOf(description)) {
      let result = await measure(c.state, c.passes);
      let label = c.label;
      if (!result.effect.length && c.fallbackView) {
        result = await measure(`${c.state}${c.state ? '&' : ''}view=${c.fallbackView}`, c.passes);
        label = `${c.label} (view ${c.fallbackView})`;
      }
      report(label, result);
    }
    // The metallic-roughness lighting (issue 15): the lighting pass on the PBR sample (assets/scenes/pbr-samples.glb:
    // forward, every texture slot, two punctual lights), loaded with the file picker as a visitor would, defaults.
    const lighting = description.effects.find((e) => e.name === 'lighting');
    await page.locator('#file-input').setInputFiles(path.join(root, 'assets', 'scenes', 'pbr-samples.glb'));
    await page.waitForFunction(
      () => document.querySelector('#scene-name').textContent.startsWith('pbr-samples.glb'), null, { timeout: 60000 });
    report('lighting, PBR sample', await measure('', lighting.passes));
    // Issue 31: the transparent layer, transmission and clear coat on the glass sample, and on variants whose
    // materials put each over most of the frame (obscura-bench section 8d makes the same ones): every opaque material
    // blended, transmissive, clear-coated, or without the material layers.
    const glassFile = path.join(root, 'assets', 'scenes', 'glass-samples.glb');
    const load = async (name, buffer) => {
      await page.locator('#file-input').setInputFiles({ name, mimeType: 'model/gltf-binary', buffer });
      await page.waitForFunction((n) => document.querySelector('#scene-name').textContent.startsWith(n), name,
                                 { timeout: 60000 });
    };
    const layers = ['KHR_materials_clearcoat', 'KHR_materials_ior', 'KHR_materials_specular'];
    const opaque = (m) => m.alphaMode !== 'BLEND' && !m.extensions?.KHR_materials_transmission &&
                          !m.extensions?.KHR_materials_unlit;
    const variant = (edit) => editedGlb(glassFile, (json) => {
      for (const m of json.materials) if (opaque(m)) edit(m);
    });
    const withExtension = (m, name, value) => { m.extensions = { ...(m.extensions ?? {}), [name]: value }; };
    const transparencyPasses = ['transparency'], levelsPasses = ['transmission-levels'];
    await load('glass-samples.glb', fs.readFileSync(glassFile));
    report('glass: transparency', await measure('', transparencyPasses));
    report('glass: transmission-levels', await measure('', levelsPasses));
    report('glass: lighting', await measure('', lighting.passes));
    await load('glass-all-blended.glb', variant((m) => {
      m.alphaMode = 'BLEND';
      m.pbrMetallicRoughness = { ...(m.pbrMetallicRoughness ?? {}) };
      const f = m.pbrMetallicRoughness.baseColorFactor ?? [1, 1, 1, 1];
      m.pbrMetallicRoughness.baseColorFactor = [f[0], f[1], f[2], 0.5];
    }));
    report('all blended: transparency', await measure('', transparencyPasses));
    await load('glass-all-transmissive.glb', variant((m) => {
      withExtension(m, 'KHR_materials_transmission', { transmissionFactor: 1 });
      m.pbrMetallicRoughness = { ...(m.pbrMetallicRoughness ?? {}), roughnessFactor: 0.3 };
    }));
    report('all transmissive: transparency', await measure('', transparencyPasses));
    report('all transmissive: levels', await measure('', levelsPasses));
    await load('glass-no-layers.glb', variant((m) => { for (const e of layers) delete m.extensions?.[e]; }));
    report('no layers: lighting', await measure('', lighting.passes));
    await load('glass-all-coated.glb', variant((m) => {
      for (const e of layers) delete m.extensions?.[e];
      withExtension(m, 'KHR_materials_clearcoat', { clearcoatFactor: 1, clearcoatRoughnessFactor: 0.1 });
    }));
    report('all clear-coated: lighting', await measure('', lighting.passes));
    if (errors.length) throw new Error(`page errors: ${errors.join('; ')}`);
    await page.context().close();
  }
  console.log(`wrote ${path.relative(root, options.csv)}`);
} finally {
  await browser.close();
  server.stop();
}
