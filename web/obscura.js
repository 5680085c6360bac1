// Obscura's JavaScript API: image-space effects (Scalable Ambient Obscurance, tone mapping, FXAA) on a WebGL 1
// canvas, driven by the same C++ core as the native renderer. Documented in web/README.md; the demo page (app.js)
// uses nothing else.
//
//   import { createObscura } from './obscura.js';
//   const obscura = await createObscura(document.querySelector('canvas'));
//   obscura.set('ao.radius', 1.5);        // 'radius' (the name before effects had prefixes) works too
//   obscura.set('tonemap.operator', 'agx');
//   obscura.setView('ao');
//
// Everything that describes effects and parameters (names, kinds, ranges, presets, views, passes, keys) comes from
// the core's effect table, so a page never repeats it.
import createObscuraCore from './obscura-core.js';
import { decodeCompressedGltf } from './gltf-decoders.js';

// A refused call: an unknown parameter, a value out of range, a file that is not valid glTF. `message` is one line
// meant for the user.
export class ObscuraError extends Error {
  constructor(message) {
    super(message);
    this.name = 'ObscuraError';
  }
}

// Starts the core on `canvas` and resolves to an Obscura instance once the first frames are scheduled.
// Options:
//   pointerControls (default true): orbit / pan / zoom with mouse, touch and wheel on the canvas.
//   dynamicResolution (default false): resolution.dynamic's default here: on, the render scale follows the frame time
//     (resolution.target-ms), the demo page's choice; off, frames are drawn at resolution.scale.
//   quickStart (default false): resolution.quick-start's default here: on, the first frame is a cheap one (the lit
//     scene without AO, antialiasing and the lens and camera effects) and the full frame follows by itself within a
//     few frames, its programs warmed meanwhile (startup().quickStart says what was warmed and when); the demo page's
//     choice. snapshot() always reads the full frame.
//   prepare (default true): begin compiling the first frame's programs as part of start-up (prepare()); false for a
//     caller that changes the state first and then calls prepare() itself.
//   checkGlErrors (default false): glGetError after every pass; a GL error stops drawing and is logged as a console
//     error naming the pass (for tests and debugging: each check waits for the GPU).
//   wasmUrl: where obscura-core.wasm is served (default: beside this file, found through import.meta.url; bundlers
//     that follow `new URL(..., import.meta.url)` copy the file and rewrite the URL).
export async function createObscura(canvas, { pointerControls = true, checkGlErrors = false, dynamicResolution = false,
                                             quickStart = false, prepare = true, wasmUrl } = {}) {
  const start = performance.now();
  const core = await createObscuraCore(coreOptions(canvas, wasmUrl));
  const wasmMs = performance.now() - start;
  const obscura = new Obscura(core, canvas);
  if (!core._obscura_create(checkGlErrors ? 1 : 0, dynamicResolution ? 1 : 0, quickStart ? 1 : 0, prepare ? 1 : 0)) {
    throw new ObscuraError(core.UTF8ToString(core._obscura_error()));
  }
  obscura.description = obscura.json('obscura_describe');
  if (pointerControls) obscura.attachPointerControls();
  obscura.wasmMs = wasmMs;
  obscura.createMs = performance.now() - start;
  obscura.firstFrame = obscura.waitForFirstFrame();
  return obscura;
}

// The module's options: its canvas, and where its .wasm is (the literal `new URL('./obscura-core.wasm',
// import.meta.url)` is what bundlers recognise as an asset to copy).
function coreOptions(canvas, wasmUrl) {
  const wasm = String(wasmUrl ?? new URL('./obscura-core.wasm', import.meta.url));
  return { canvas, locateFile: (file, directory) => (file.endsWith('.wasm') ? wasm : directory + file) };
}

// AO on the page's own geometry (docs/api.md, "In the browser"): Obscura joins the WebGL 1 context the page made on
// `canvas` (canvas.getContext('webgl') first; the module is handed that very context), draws nothing on its own
// schedule and has no scene. Per frame the page calls beginGBuffer(), draws its meshes with a fragment shader built
// on gbufferGlsl, then ambientOcclusion(camera) and composite(), or samples the returned texture itself.
// Options: checkGlErrors (default false) and wasmUrl, as createObscura's.
export async function createAmbientOcclusion(canvas, { checkGlErrors = false, wasmUrl } = {}) {
  const core = await createObscuraCore(coreOptions(canvas, wasmUrl));
  if (!core._obscura_geometry_create(checkGlErrors ? 1 : 0)) {
    throw new ObscuraError(core.UTF8ToString(core._obscura_geometry_error()));
  }
  return new ObscuraAmbientOcclusion(core, canvas);
}

export class ObscuraAmbientOcclusion {
  constructor(core, canvas) {
    this.core = core;
    this.canvas = canvas;
    // The page's own context: the one the module draws with too.
    this.gl = canvas.getContext('webgl');
    this.description = JSON.parse(core.UTF8ToString(core._obscura_describe()));
  }

  // The library's version ('0.1.0').
  get version() { return this.core.UTF8ToString(this.core._obscura_geometry_version()); }
  // The GLSL ES 1.00 chunk obscura_gbuffer.glsl: after the page's `precision highp float;`, its fragment shader
  // writes gl_FragColor = obscuraGBuffer(normalize(viewNormal), -viewPosition.z, near, far).
  get gbufferGlsl() { return this.core.UTF8ToString(this.core._obscura_geometry_glsl()); }
  // Every parameter of the frame, as Obscura's parameters (the AO's are those named 'ao' and 'ao.*').
  get parameters() { return this.description.parameters; }
  get(name) { return this.result('obscura_geometry_get', ['string'], [name]); }
  set(name, value) {
    this.check(this.core.ccall('obscura_geometry_set', 'number', ['string', 'string'], [name, String(value)]));
  }

  // Binds Obscura's G-buffer framebuffer (RGBA8 and a depth buffer) of width x height, cleared to the background,
  // with its viewport set: the page draws its meshes next, depth test on.
  beginGBuffer(width = this.gl.drawingBufferWidth, height = this.gl.drawingBufferHeight) {
    this.check(this.core._obscura_geometry_begin(width, height));
  }
  // Runs the AO on the G-buffer drawn since beginGBuffer() for the camera it was drawn with ({eye, target, up: [x, y,
  // z], fovy (degrees), near, far}) and returns the AO as a WebGLTexture (RGB = visibility, A = 1; NEAREST; the
  // G-buffer's size), owned by Obscura and valid until the next call. Leaves the canvas's framebuffer (null) bound.
  ambientOcclusion({ eye, target, up = [0, 1, 0], fovy = 50, near = 0.1, far = 100 }) {
    this.check(this.core._obscura_geometry_ambient_occlusion(eye[0], eye[1], eye[2], target[0], target[1], target[2],
                                                            up[0], up[1], up[2], fovy, near, far));
    const gl = this.gl;
    const previous = gl.getParameter(gl.TEXTURE_BINDING_2D);
    this.check(this.core._obscura_geometry_bind_ao());
    const texture = gl.getParameter(gl.TEXTURE_BINDING_2D);
    gl.bindTexture(gl.TEXTURE_2D, previous);
    return texture;
  }
  // Multiplies the last AO into the framebuffer the page has bound (its own, or null: the canvas), of that size.
  composite(width = this.gl.drawingBufferWidth, height = this.gl.drawingBufferHeight) {
    this.check(this.core._obscura_geometry_composite(width, height));
  }
  // {width, height, frames, cpuMs, passesRun, pooledTargets}
  stats() { return JSON.parse(this.core.UTF8ToString(this.core._obscura_geometry_stats())); }

  check(ok) {
    if (!ok) throw new ObscuraError(this.core.UTF8ToString(this.core._obscura_geometry_error()));
  }
  result(name, types, values) {
    const pointer = this.core.ccall(name, 'number', types, values);
    this.check(pointer);
    return this.core.UTF8ToString(pointer);
  }
}

// Fires 'change' after every call that changes what is shown (parameters, view, camera, scene, timeline), and
// 'timeupdate' on every animation frame while the timeline plays.
export class Obscura extends EventTarget {
  constructor(core, canvas) {
    super();
    this.core = core;
    this.canvas = canvas;
  }

  // --- What the core offers (read once at start) ---------------------------------------------------------------
  // [{name, effect, alias?, kind: 'switch'|'number'|'integer'|'choice'|'color'|'text', range, help, default,
  //   primary, slow, min?, max?, choices?}]: every parameter of the frame, "preset" (effect '') first, then each
  // effect's ("ao", "ao.radius", ...), in frame order. alias: an older name set() and get() also take ('radius'). A
  // number's choices are words it accepts besides numbers ('auto' for the AO's bias, intensity and contrast). A
  // colour reads as linear 'r,g,b'; set() also takes sRGB '#rrggbb' (fog.color). primary: shown up front. slow: a
  // change takes a noticeable time (lighting.sun-elevation makes the sky again), so a slider applies it on release.
  get parameters() { return this.description.parameters; }
  // [{name, title, switch, passes: [...], targets: [{name, encoding, views: [...]}], parameters: [names]}]: the
  // effect table, in the order the frame runs it.
  get effects() { return this.description.effects; }
  // [{name, samples, turns, blurRadius, blurStride, halfResolution}]: the AO's quality presets
  get presets() { return this.description.presets; }
  // ['final', 'split', then every target's debug view: 'normals', 'depth', 'mask', 'ao-raw', 'ao-blur-h', 'ao',
  //  'scene-color', 'shading-count', 'display-color']
  get views() { return this.description.views; }
  // ['ao', 'ao.blur', ..., 'tonemap', 'fxaa', ...]: every switch the 'split' view can compare, off left | on right
  get compareSwitches() { return this.description.compareSwitches; }
  // [{key, label, description}]: the keys handleKey() understands (the same as obscura-view's); key is
  // KeyboardEvent.key (' ' for space, 'ArrowLeft'), label how a person reads it ('space', 'left arrow')
  get keyBindings() { return this.description.keys; }
  // Every pass of the table, in frame order ('gbuffer', 'hierarchy', 'sao', ..., 'lighting', 'tonemap', 'fxaa',
  // 'view', 'present'): the keys of stats().passMs
  get passes() { return this.description.passes; }
  // {version, renderer, vendor, shadingLanguage, maxRenderSize, depth24, elementIndexUint, timerQuery}
  get context() { return this.description.context; }

  // --- Parameters and view -----------------------------------------------------------------------------------------
  // The current value of a parameter, as text ('1.5', 'on', 'medium'; '' for a preset the values no longer match).
  get(name) { return this.text('obscura_get', ['string'], [name]); }
  // The value in use: get(name), except that bias, intensity and contrast on 'auto' read as the values fitted to
  // the ray-traced reference for the current preset and radius.
  effective(name) { return this.text('obscura_get_effective', ['string'], [name]); }
  // Sets a parameter from a string or number; throws ObscuraError with the core's message if refused.
  set(name, value) { this.call('obscura_set', ['string', 'string'], [name, String(value)]); }
  // Autofocus depth of field on the point (x, y) of the canvas, CSS pixels from its top left: dof.focus becomes
  // 'auto' and dof.focus-x, dof.focus-y the point as fractions of the canvas, so the lens focuses on the depth drawn
  // there (in the URL, as the parameters are). Depth of field itself stays as it is.
  focusAt(x, y) {
    const fraction = (v, size) => String(Math.min(Math.max(size > 0 ? v / size : 0.5, 0), 1));
    this.set('dof.focus', 'auto');
    this.set('dof.focus-x', fraction(x, this.canvas.clientWidth));
    this.set('dof.focus-y', fraction(y, this.canvas.clientHeight));
  }
  get view() { return this.text('obscura_view', [], []); }
  // Forces how the depth hierarchy is stored: 'separate', 'atlas', 'mipchain' (needs EXT_shader_texture_lod and
  // OES_fbo_render_mipmap) or 'auto' (the best the context offers; the default). Returns the storage now in use.
  // The AO is the same whichever is used; they differ in speed.
  setHierarchyStorage(name) {
    const used = this.text('obscura_set_hierarchy_storage', ['string'], [name]);
    this.changed();
    return used;
  }
  // Allows (true, the default) or refuses vertex array objects for the scene's draws (OES_vertex_array_object: one
  // call binds a piece's vertex streams). Returns whether the scene now draws with them; the image is the same.
  setVertexArrays(allow) {
    const used = this.text('obscura_set_vertex_arrays', ['number'], [allow ? 1 : 0]) === 'on';
    this.changed();
    return used;
  }
  // Allows (true, the default) or refuses static batches: the still, rigid, opaque instances that share a material
  // drawn as one piece placed in world space (fewer WebGL calls a frame). Returns how many batches the scene now
  // draws; the image is the same.
  setStaticBatches(allow) {
    const batches = Number(this.text('obscura_set_static_batches', ['number'], [allow ? 1 : 0]));
    this.changed();
    return batches;
  }
  // Forces where the prefiltered environment's roughness levels live: 'halffloat' (half floats the hardware filters:
  // OES_texture_half_float_linear), 'mipchain' (RGB9E5 filtered by hand, read with EXT_shader_texture_lod), 'atlas'
  // (RGB9E5 without the extension) or 'auto' (the default: the first the context can take). Returns the layout now in
  // use; all give the same image within a level of 255.
  setEnvironmentLayout(name) {
    const used = this.text('obscura_set_environment_layout', ['string'], [name]);
    this.changed();
    return used;
  }
  setView(mode) { this.call('obscura_set_view', ['string'], [mode]); }
  // The switch the 'split' view compares (one of compareSwitches; 'ao' at first; in the state as compare=).
  get compare() { return this.text('obscura_compare', [], []); }
  setCompare(name) { this.call('obscura_set_compare', ['string'], [name]); }

  // The whole state (view, parameters that differ from their defaults, camera) as query-string text, and back.
  // setState applies only what the text names and throws (changing nothing) on anything unknown or invalid. The
  // radius's default is the scene's (scene().defaultRadius); a radius setState gives is kept when scenes change.
  state() { return this.text('obscura_state', [], []); }
  setState(query) { this.call('obscura_set_state', ['string'], [query]); }
  // Begins compiling the programs of the next frame of the final view, as the state is now, and returns at once: the
  // browser compiles them while the page goes on, and the frame finds them ready (docs/resolution.md, "Start-up").
  // createObscura does it unless told not to; a restored context does it again; programs begun for a frame that is
  // then not drawn (the state changed) are dropped after the next one. startup().programsPrepared counts them.
  prepare() { this.call('obscura_prepare', [], []); }

  // --- Camera (pixel deltas in the same units as viewportHeight; CSS pixels of the canvas by default) -------------
  orbit(dx, dy, viewportHeight = this.canvas.clientHeight) { this.move('obscura_orbit', dx, dy, viewportHeight); }
  pan(dx, dy, viewportHeight = this.canvas.clientHeight) { this.move('obscura_pan', dx, dy, viewportHeight); }
  // factor > 1 moves away from the target.
  zoom(factor) { this.move('obscura_zoom', factor); }
  resetCamera() { this.move('obscura_reset_camera'); }

  // The cameras: the free one (orbit, pan, zoom move it) and the scene's own (glTF cameras on nodes, which move with
  // its animation). camera() is {choice, orthographic, cameras, eye, target, up, fovy, ymag}: choice 'free' or the
  // scene camera looked through (its name, or its index where the name does not find it); orthographic, the projection
  // of the view shown; cameras, the scene's [{name, orthographic}]; the rest the free camera's (fovy in degrees, ymag
  // the orthographic half height in scene units).
  camera() { return this.json('obscura_camera'); }
  // Looks through 'free' or one of the scene's cameras (a name or an index into camera().cameras); the state keeps it
  // as camera=NAME. Throws ObscuraError for a camera the scene does not have. A scene loaded starts on 'free'; a move
  // starts the free camera from the view shown.
  setCamera(choice) { this.call('obscura_set_camera', ['string'], [String(choice)]); }
  // Makes the free camera orthographic (true) or perspective, from the view shown, keeping the view's size at its
  // target; the state keeps it as projection=orthographic&ymag=H.
  setOrthographic(on) { this.call('obscura_set_orthographic', ['number'], [on ? 1 : 0]); }

  // Applies a key binding (event.key of a keydown); false if the key is not bound.
  handleKey(key) {
    const done = this.core.ccall('obscura_handle_key', 'number', ['string'], [key]);
    if (!done) {
      const message = this.core.UTF8ToString(this.core._obscura_error());
      if (message) throw new ObscuraError(message);
      return false;
    }
    this.changed();
    return true;
  }

  // --- Scenes ------------------------------------------------------------------------------------------------------
  // Loads a .glb or .gltf from bytes (ArrayBuffer or Uint8Array). A .gltf's external buffers and images come in
  // sideFiles, keyed by the URI the file uses: {'scene.bin': bytes, ...}. Resolves to scene(); on a bad file it
  // rejects with ObscuraError and the previous scene stays on screen. The AO radius becomes the new scene's
  // defaultRadius, unless setState() gave one (then it is kept); set('ao.radius', r) after loading overrides it.
  // Draco (KHR_draco_mesh_compression) and meshopt (EXT_meshopt_compression) geometry is decoded first, by the npm
  // decoders in the site's decoders/ folder (gltf-decoders.js); a missing decoder rejects with ObscuraError.
  async loadScene(bytes, name, sideFiles = {}) {
    // Let the page paint its progress indicator before the (synchronous) parse and upload.
    await new Promise((resolve) => requestAnimationFrame(() => setTimeout(resolve, 0)));
    bytes = bytes instanceof Uint8Array ? bytes : new Uint8Array(bytes);
    let decoded = null;
    try {
      decoded = await decodeCompressedGltf(bytes, sideFiles);
    } catch (e) {
      throw new ObscuraError(`${name}: ${e.message}`);
    }
    if (decoded) ({ bytes, sideFiles } = decoded);
    for (const [uri, data] of Object.entries(sideFiles)) {
      this.withBytes(data, (pointer, size) => this.core.ccall('obscura_add_side_file', null,
                                                             ['string', 'number', 'number'], [uri, pointer, size]));
    }
    const ok = this.withBytes(bytes, (pointer, size) =>
      this.core.ccall('obscura_load_scene', 'number', ['string', 'number', 'number'], [name, pointer, size]));
    if (!ok) throw new ObscuraError(this.core.UTF8ToString(this.core._obscura_error()));
    this.changed();
    return this.scene();
  }

  // Reads File objects (from a file picker or a drop) and loads the one .glb or .gltf among them, the others being
  // its side files. onProgress(fraction) follows the reading.
  // An .hdr among them (alone) becomes the environment instead (loadEnvironment), a .cube (alone) the colour grade's
  // LUT (loadLut); resolves to scene() either way.
  async loadFiles(files, { onProgress = () => {} } = {}) {
    files = Array.from(files);
    const luts = files.filter((f) => /\.cube$/i.test(f.name));
    if (luts.length === 1 && files.length === 1) {
      await this.loadLut(await readFile(luts[0], (bytes) => onProgress(bytes / (luts[0].size || 1))), luts[0].name);
      return this.scene();
    }
    const environments = files.filter((f) => /\.hdr$/i.test(f.name));
    if (environments.length === 1 && files.length === 1) {
      const file = environments[0];
      await this.loadEnvironment(await readFile(file, (bytes) => onProgress(bytes / (file.size || 1))), file.name);
      return this.scene();
    }
    const scenes = files.filter((f) => /\.(glb|gltf)$/i.test(f.name));
    if (scenes.length !== 1) {
      throw new ObscuraError(scenes.length === 0
        ? `no .glb or .gltf among ${files.map((f) => f.name).join(', ') || 'the files'}`
        : `choose one scene at a time (got ${scenes.map((f) => f.name).join(', ')})`);
    }
    const total = files.reduce((sum, f) => sum + f.size, 0) || 1;
    const loaded = new Map();
    const contents = await Promise.all(files.map((file) => readFile(file, (bytes) => {
      loaded.set(file, bytes);
      onProgress([...loaded.values()].reduce((a, b) => a + b, 0) / total);
    })));
    const sideFiles = {};
    files.forEach((file, i) => { if (file !== scenes[0]) sideFiles[file.name] = contents[i]; });
    return this.loadScene(contents[files.indexOf(scenes[0])], scenes[0].name, sideFiles);
  }

  // An equirectangular environment (.hdr, or a PNG of RGBE bytes) for the ambient light and the background: kept in
  // the module's file system and set as lighting.environment (its path there). Rejects with ObscuraError on a file
  // the core cannot decode; the environment in use stays then. set('lighting.environment', 'sky') goes back.
  async loadEnvironment(bytes, name) {
    bytes = bytes instanceof Uint8Array ? bytes : new Uint8Array(bytes);
    const path = this.withBytes(bytes, (pointer, size) => this.core.ccall(
      'obscura_add_environment', 'string', ['string', 'number', 'number'], [name, pointer, size]));
    if (!path) throw new ObscuraError(this.core.UTF8ToString(this.core._obscura_error()));
    this.set('lighting.environment', path);
    this.changed();
    return path;
  }

  // A 3D LUT for colour grading (an Adobe / Resolve .cube file, as bytes or text): kept in the module's file system,
  // set as grading.lut (its path there) and grading switched on. Throws ObscuraError on a malformed file, naming its
  // line; the grade in use stays then. set('grading.lut', 'none') takes it off.
  async loadLut(cube, name = 'grade.cube') {
    const bytes = typeof cube === 'string' ? new TextEncoder().encode(cube)
      : cube instanceof Uint8Array ? cube : new Uint8Array(cube);
    const path = this.withBytes(bytes, (pointer, size) => this.core.ccall(
      'obscura_add_lut', 'string', ['string', 'number', 'number'], [name, pointer, size]));
    if (!path) throw new ObscuraError(this.core.UTF8ToString(this.core._obscura_error()));
    this.set('grading.lut', path);
    this.set('grading', 'on');
    this.changed();
    return path;
  }

  loadBuiltinScene() {
    this.call('obscura_load_builtin_scene', [], []);
    return this.scene();
  }

  // {name, triangles, warnings: [what the loader repaired or ignored], defaultRadius, radiusGiven}. defaultRadius:
  // the AO radius the scene gets when nobody sets one, in its units: 5 % of the diameter of its bounding sphere, to
  // two significant figures (the built-in scene: 1, metres). radiusGiven: a state text (setState, the page's URL)
  // gave the radius, which loading a scene then keeps.
  scene() { return this.json('obscura_scene'); }
  // scene().defaultRadius alone (cheap: the page reads it on every change).
  get defaultRadius() { return Number(this.text('obscura_default_radius', [], [])); }

  // --- Timeline (the scene's animations) -----------------------------------------------------------------------
  // A scene starts paused at 0 s on its first animation. While it plays, frames are drawn on every animation frame
  // and 'timeupdate' fires after each (no 'change': the time moves by itself); 'change' fires when playing stops.
  // The time stays on the timeline: wrapped into [0, duration) while looping (the default), else clamped to
  // [0, duration], where playing stops. Where nothing plays (no animations, or the animation 'none') the time stays 0.

  // {animations, animation, time, duration, playing, speed, loop, frameInterval}: all of the below at once.
  timeline() { return this.json('obscura_timeline'); }
  // The scene's animation names in its order ('' for an unnamed one: choose it by index); [] for a still scene.
  get animations() { return this.timeline().animations; }
  // The animations playing: a name, an index (as text) where the animation has no name of its own, 'all' or 'none'.
  get animation() { return this.timeline().animation; }
  // Chooses by name, index (number or text), 'all' (every animation together) or 'none' (the rest pose); back to
  // 0 s. Throws ObscuraError listing the choices.
  setAnimation(choice) { this.call('obscura_set_animation', ['string'], [String(choice)]); }
  // Seconds on the timeline, and its length (the chosen animations' longest; 0 when nothing plays).
  get time() { return this.core._obscura_time(); }
  get duration() { return this.timeline().duration; }
  setTime(seconds) { this.call('obscura_set_time', ['number'], [Number(seconds)]); }
  get playing() { return this.core._obscura_playing() !== 0; }
  // Plays from the current time (from 0 at the end of a timeline that does not loop); does nothing where nothing
  // plays.
  play() { this.move('obscura_play'); }
  pause() { this.move('obscura_pause'); }
  // Pauses and moves by `frames` frame intervals (frameInterval: 1/60 s); negative steps back.
  stepFrames(frames = 1) { this.move('obscura_step_frames', Math.trunc(frames)); }
  // Playback speed, a factor on the clock (0.01 .. 100; default 1).
  get speed() { return this.timeline().speed; }
  setSpeed(factor) { this.call('obscura_set_speed', ['number'], [Number(factor)]); }
  // Whether the timeline wraps at its end (default true).
  get loop() { return this.timeline().loop; }
  setLoop(loop) { this.move('obscura_set_loop', loop ? 1 : 0); }

  // --- Measurements ------------------------------------------------------------------------------------------------
  // Frames are drawn when something changed; continuous mode draws on every animation frame, so the timings stay
  // live (at the cost of keeping the GPU busy).
  setContinuous(continuous) { this.core._obscura_set_continuous(continuous ? 1 : 0); }

  // {width, height (drawing-buffer pixels), continuous, pending (a change waits for its frame), frameMs (between
  //  frames drawn back to back, smoothed; 0 until there were such frames), cpuMs (time in the renderer, smoothed),
  //  lastCpuMs (time in the renderer of the last drawn frame), hostMs and lastHostMs (the same for the render call
  //  alone: the renderer's host time, without the page's canvas work), frames (drawn so far), timerQueries
  //  (EXT_disjoint_timer_query in use), passMs ({gbuffer: ms, ...} of a recent measured frame (one drawn frame in
  //  four: README, "Timer queries"), read a few animation frames after it, drawn or not; null per pass not run; null
  //  without timer queries or before the first result),
  //  passesRun (the passes the last frame ran, in order), passesDoneBy ({tonemap: 'lighting'}: passes whose work
  //  another pass did in the last frame, so they did not run and have no time of their own), history ({frames:
  //  consecutive frames the history survived, drops: how often it was dropped (resize, scene change, a new render
  //  scale), frameIndex}: starts afresh after a context loss), pooledTargets (render targets the frame keeps),
  //  triangles (what the last geometry pass drew, at the levels of detail gbuffer.lod chose), drawCalls (its draw
  //  calls: a static batch's members at one level in one),
  //  contextLost, contextRestores, glObjects: {textures, buffers, ...} (live GL objects), error (why frames stopped,
  //  or ''), render ({width, height: the size the effects ran at, scale: the render scale, pixelRatio: the canvas's
  //  device pixels per CSS pixel (devicePixelRatio up to resolution.max-pixel-ratio), devicePixelRatio, dynamic
  //  (resolution.dynamic), measuredBy ('gpu': timer queries, 'cpu': the interval between frames drawn back to
  //  back), meanMs (dynamic resolution's mean frame time at this scale; 0 while it measures), targetMs, changes (of
  //  the scale so far)}), cheapFrame (the last frame was quick start's cheap one: the full frame follows), startup
  //  (the core's start-up figures: see startup())}
  stats() { return this.json('obscura_stats'); }

  // Start-up, in ms: {wasmMs (fetching, compiling and instantiating obscura-core.wasm), createMs (all of
  // createObscura: the wasm, then the core's own start, coreMs, of which coreParts: the WebGL context, the programs
  // compiled, the sky made and prefiltered, the scene uploaded, ...), programsPrepared (a count, not ms: the first
  // frame's programs begun at the core's start, which the browser compiles while the page goes on), firstFrameMs
  // (from createObscura's end to the animation frame after the first frame was drawn: the first frame's whole cost,
  // as stats().frameMs measures a steady one; null until then), firstFrameCpuMs (its time in the renderer),
  // firstFrameParts (what the first frame did besides drawing: programs compiled on first use or finished, ...),
  // fullFrameMs (likewise to the animation frame after the first full frame: firstFrameMs's without quick start),
  // quickStart ({cheapFrames: frames drawn cheap before the full one, firstFullFrame: its index (frames before it:
  // cheapFrames), fullAtMs: when the renderer drew it, warmed: [{pass, frame, atMs, cpuMs}]: each pass of the full
  // frame drawn once at a small size by a cheap frame so that its program and the driver's code for it are ready, in
  // which frame, when (ms since the renderer was made) and its time on the CPU})}. `firstFrame` is a promise of the
  // same once the first frame is on screen.
  startup() {
    const s = this.stats().startup;
    return { wasmMs: this.wasmMs, createMs: this.createMs, coreMs: s.createMs, coreParts: s.createParts,
             firstFrameMs: s.firstFrameMs, firstFrameCpuMs: s.firstFrameCpuMs, firstFrameParts: s.firstFrameParts,
             fullFrameMs: s.fullFrameMs, quickStart: s.quickStart, programsPrepared: s.programsPrepared };
  }

  // Resolves to startup() once a frame has been drawn and the browser has run the animation frame after it.
  waitForFirstFrame() {
    return new Promise((resolve) => {
      const poll = () => {
        const startup = this.startup();
        if (startup.firstFrameMs !== null) resolve(startup);
        else requestAnimationFrame(poll);
      };
      requestAnimationFrame(poll);
    });
  }

  // Draws a frame now into the canvas, outside the animation-frame schedule (an embedder drawing on its own clock,
  // a benchmark that bounds each frame with gl.finish). Throws ObscuraError if no frame could be drawn.
  draw() {
    if (!this.core._obscura_draw()) throw new ObscuraError(this.core.UTF8ToString(this.core._obscura_error()));
  }

  // Draws a frame now and returns it: {width, height, pixels: Uint8Array RGBA, rows top to bottom}.
  snapshot() {
    const pointer = this.core._obscura_snapshot();
    if (!pointer) throw new ObscuraError(this.core.UTF8ToString(this.core._obscura_error()));
    const { width, height, pointer: data } = JSON.parse(this.core.UTF8ToString(pointer));
    return { width, height, pixels: this.core.HEAPU8.slice(data, data + width * height * 4) };
  }

  // --- Pointer controls ----------------------------------------------------------------------------------------------
  // Left drag: orbit. Right or middle drag, or shift + left drag: pan. Wheel: zoom. Touch: one finger orbits, two
  // fingers pinch to zoom and move together to pan. A click (a left press released within 4 pixels of where it went
  // down) with depth of field on focuses there (focusAt).
  attachPointerControls() {
    const canvas = this.canvas;
    const pointers = new Map();  // pointerId -> {x, y, pan}
    canvas.style.touchAction = 'none';
    canvas.addEventListener('contextmenu', (e) => e.preventDefault());
    canvas.addEventListener('pointerdown', (e) => {
      canvas.setPointerCapture(e.pointerId);
      pointers.set(e.pointerId, { x: e.clientX, y: e.clientY, pan: e.button === 1 || e.button === 2 || e.shiftKey,
                                  downX: e.clientX, downY: e.clientY, click: pointers.size === 0 && e.button === 0 });
      e.preventDefault();
    });
    const release = (e) => pointers.delete(e.pointerId);
    canvas.addEventListener('pointerup', (e) => {
      const pointer = pointers.get(e.pointerId);
      release(e);
      if (!pointer || !pointer.click || pointer.pan || this.get('dof') !== 'on') return;
      if (Math.hypot(e.clientX - pointer.downX, e.clientY - pointer.downY) > 4) return;
      const rect = canvas.getBoundingClientRect();
      this.focusAt(e.clientX - rect.left, e.clientY - rect.top);
    });
    canvas.addEventListener('pointercancel', release);
    canvas.addEventListener('pointermove', (e) => {
      const pointer = pointers.get(e.pointerId);
      if (!pointer) return;
      if (pointers.size === 1) {
        const dx = e.clientX - pointer.x, dy = e.clientY - pointer.y;
        if (pointer.pan) this.pan(dx, dy);
        else this.orbit(dx, dy);
      } else if (pointers.size === 2) {
        const [a, b] = [...pointers.values()];
        const before = Math.hypot(a.x - b.x, a.y - b.y);
        const other = a === pointer ? b : a;
        const after = Math.hypot(e.clientX - other.x, e.clientY - other.y);
        if (before > 0 && after > 0) this.zoom(before / after);
        this.pan((e.clientX - pointer.x) / 2, (e.clientY - pointer.y) / 2);
      }
      pointer.x = e.clientX;
      pointer.y = e.clientY;
    });
    canvas.addEventListener('wheel', (e) => {
      const pixels = e.deltaMode === 1 ? e.deltaY * 33 : e.deltaMode === 2 ? e.deltaY * canvas.clientHeight : e.deltaY;
      this.zoom(Math.exp(pixels * 0.0015));
      e.preventDefault();
    }, { passive: false });
  }

  // --- Plumbing ----------------------------------------------------------------------------------------------------
  call(name, types, values) {
    if (!this.core.ccall(name, 'number', types, values)) {
      throw new ObscuraError(this.core.UTF8ToString(this.core._obscura_error()));
    }
    this.changed();
  }

  text(name, types, values) {
    const pointer = this.core.ccall(name, 'number', types, values);
    if (!pointer) throw new ObscuraError(this.core.UTF8ToString(this.core._obscura_error()));
    return this.core.UTF8ToString(pointer);
  }

  json(name) { return JSON.parse(this.text(name, [], [])); }

  move(name, ...args) {
    this.core['_' + name](...args);
    this.changed();
  }

  // Copies bytes into the module's memory for the duration of `use(pointer, size)`.
  withBytes(bytes, use) {
    const view = bytes instanceof Uint8Array ? bytes : new Uint8Array(bytes);
    const pointer = this.core._malloc(Math.max(view.length, 1));
    try {
      this.core.HEAPU8.set(view, pointer);
      return use(pointer, view.length);
    } finally {
      this.core._free(pointer);
    }
  }

  changed() {
    this.dispatchEvent(new Event('change'));
    this.followPlayback();
  }

  // While the timeline plays (whoever started it: play(), a key, setState), 'timeupdate' after every animation
  // frame; when it stops by itself (the end of a timeline without loop), 'change'.
  followPlayback() {
    if (this.following || !this.playing) return;
    this.following = true;
    const follow = () => {
      const playing = this.playing;
      this.dispatchEvent(new Event('timeupdate'));
      if (playing) {
        requestAnimationFrame(follow);
      } else {
        this.following = false;
        this.dispatchEvent(new Event('change'));
      }
    };
    requestAnimationFrame(follow);
  }
}

function readFile(file, onProgress) {
  return new Promise((resolve, reject) => {
    const reader = new FileReader();
    reader.onprogress = (e) => onProgress(e.loaded);
    reader.onload = () => {
      onProgress(file.size);
      resolve(new Uint8Array(reader.result));
    };
    reader.onerror = () => reject(new ObscuraError(`${file.name}: cannot be read (${reader.error})`));
    reader.readAsArrayBuffer(file);
  });
}
