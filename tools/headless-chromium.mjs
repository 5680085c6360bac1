// How every headless Chromium of the project is launched (the browser tests, the browser benchmark and its
// scripts): Debian's /usr/bin/chromium (nothing is downloaded), WebGL through ANGLE on SwiftShader, nothing from the
// network. Playwright's chromium.launch(chromiumLaunchOptions) takes it; this module imports no package, so both npm
// folders (tests/browser, tools/browser-bench) can share it.
export const chromiumFlags = ['--no-sandbox', '--disable-gpu', '--enable-unsafe-swiftshader', '--use-angle=swiftshader',
                              '--disable-background-networking', '--disable-component-update', '--disable-sync',
                              '--no-first-run', '--disable-quic'];

export const chromiumLaunchOptions = { executablePath: '/usr/bin/chromium', headless: true, args: chromiumFlags };

// Command-line options of the form --name VALUE, for the small scripts: `handlers` maps each option to a function
// that takes its value, or, for a flag (--quick), a function of no parameter, which takes none. An argument not
// starting with -- goes to `positional` where the script takes such arguments. Throws on an unknown option, a missing
// value or an unexpected positional argument, naming `script` for its usage.
export function parseOptions(argv, handlers, script, positional = null) {
  for (let i = 0; i < argv.length; ++i) {
    if (positional && !argv[i].startsWith('--')) {
      positional(argv[i]);
      continue;
    }
    const handler = Object.hasOwn(handlers, argv[i]) ? handlers[argv[i]] : null;
    if (!handler) throw new Error(`unknown option ${argv[i]} (see the header of ${script})`);
    if (handler.length === 0) {
      handler();
      continue;
    }
    if (i + 1 >= argv.length) throw new Error(`${argv[i]} needs a value`);
    handler(argv[++i]);
  }
}

// The positional arguments of a script that takes no options (at most `most` of them), through parseOptions: a
// mistyped --option fails instead of being read as an argument.
export function parsePositional(argv, script, most) {
  const positional = [];
  parseOptions(argv, {}, script, (a) => positional.push(a));
  if (positional.length > most) throw new Error(`${script}: at most ${most} arguments (see its header)`);
  return positional;
}

// The scripts' figures: the median of the readings; a size ("640x360") as [width, height], and a --sizes list
// ("640x360,1280x720") as such pairs.
export function median(values) {
  const sorted = [...values].sort((a, b) => a - b);
  const mid = sorted.length >> 1;
  return sorted.length % 2 ? sorted[mid] : 0.5 * (sorted[mid - 1] + sorted[mid]);
}
export function parseSize(text) {
  return text.split('x').map(Number);
}
export function parseSizes(text) {
  return text.split(',').map(parseSize);
}

// The demo page's address with its dynamic resolution and quick start off. The page turns them on: it starts at its
// smallest scale, so a frame measured there would draw a quarter of the pixels its peers draw, and its first frames
// are quick start's cheap ones (without AO and FXAA): every benchmark and accuracy script opens the page through this
// (its state keeps the settings; a state may still set resolution.scale).
export function fixedScaleUrl(url) {
  const address = new URL(url);
  address.searchParams.set('resolution.dynamic', 'off');
  address.searchParams.set('resolution.quick-start', 'off');
  return address.toString();
}

// Throws unless the page's frame is rendered at the canvas's size (render scale 1): run after the state is applied.
export async function expectFullScale(page, what) {
  const render = await page.evaluate(() => window.obscura.stats().render);
  if (render.dynamic || render.scale !== 1) {
    throw new Error(`${what}: Obscura renders at scale ${render.scale}${render.dynamic ? ' (dynamic)' : ''}, ` +
                    `${render.width}x${render.height}; the comparison needs the canvas's full size`);
  }
}

// The demo page served at `url` in a fresh context of `width` x `height` CSS pixels (device pixel ratio 1), once it
// says it is ready, with the controls panel hidden so that the canvas is all there is, and its dynamic resolution
// off (fixedScaleUrl). Returns the page and the list its uncaught errors are pushed to.
export async function openDemoPage(browser, url, width, height) {
  const page = await (await browser.newContext({ viewport: { width, height }, deviceScaleFactor: 1 })).newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(fixedScaleUrl(url));
  await page.waitForFunction(() => document.body.dataset.ready === 'true', null, { timeout: 120000 });
  await page.addStyleTag({ content: '#panel { display: none !important; }' });
  return { page, errors };
}

// An init script (browserContext.addInitScript(countWebGlCalls)) that counts every call of a WebGL 1 context's
// methods by name into window.glCalls, which the page's code may reset; getParameter and getExtension by their
// argument too ("getParameter(0x8fbb)"); and the calls of the extension objects whose methods the renderer calls
// per frame (OES_vertex_array_object's bindVertexArrayOES, ...). tests/browser/calls.test.mjs and
// tools/browser-bench/gl-calls.mjs use it.
export function countWebGlCalls() {
  window.glCalls = {};
  const count = (proto, queried) => {
    for (const name of Object.getOwnPropertyNames(proto)) {
      const method = Object.getOwnPropertyDescriptor(proto, name).value;
      if (typeof method !== 'function' || name === 'constructor') continue;
      const byArgument = queried.includes(name);
      proto[name] = function (...args) {
        const key = byArgument ? `${name}(0x${Number(args[0]).toString(16)})` : name;
        window.glCalls[key] = (window.glCalls[key] ?? 0) + 1;
        const result = method.apply(this, args);
        // The extension objects have no interface object of their own to patch up front: their prototype is
        // patched when the page first asks for them. Not the timer queries' extension: the page's stats, not the
        // renderer's, and left out of the figures before.
        if (name === 'getExtension' && args[0] === 'OES_vertex_array_object' && result &&
            !Object.getPrototypeOf(result).counted) {
          count(Object.getPrototypeOf(result), []);
          Object.getPrototypeOf(result).counted = true;
        }
        return result;
      };
    }
  };
  count(WebGLRenderingContext.prototype, ['getParameter', 'getExtension']);
}

// Runs in the page (page.evaluate(applyBenchmarkState, state)): every parameter at its default (the presets follow
// their parameters), dynamic resolution off where the build has it, then `state` (query text, or 'every': every
// effect with a switch on), at 1 s on the clock and playing, the final image. The host-time scripts use it.
export function applyBenchmarkState(state) {
  const o = window.obscura;
  const query = new URLSearchParams();
  for (const p of o.parameters) if (p.name !== 'preset' && !p.name.endsWith('.preset')) query.set(p.name, p.default);
  if (o.parameters.some((p) => p.name === 'resolution.dynamic')) query.set('resolution.dynamic', 'off');
  const asked = state === 'every' ? o.effects.filter((e) => e.switch).map((e) => `${e.name}=on`).join('&') : state;
  for (const [key, value] of new URLSearchParams(asked)) query.set(key, value);
  query.set('time', '1');
  query.set('play', 'on');
  query.set('view', 'final');
  o.setState(query.toString());
}
