// TypeScript declarations of Obscura's JavaScript API (obscura.js). The reference is web/README.md; AO on the page's
// own geometry: docs/api.md, "In the browser". Stable within a major version (CHANGELOG.md).

/** A call the core refused: an unknown parameter, a value out of range, a file that is not valid glTF. `message` is
 * one line meant for the user. */
export class ObscuraError extends Error {
  constructor(message: string);
  readonly name: 'ObscuraError';
}

export interface CreateOptions {
  /** Orbit / pan / zoom with mouse, touch and wheel on the canvas (default true). */
  pointerControls?: boolean;
  /** glGetError after every pass; a GL error stops drawing (for tests and debugging; default false). */
  checkGlErrors?: boolean;
  /** resolution.dynamic's default: the render scale follows the frame time (the demo page's choice; default false). */
  dynamicResolution?: boolean;
  /**
   * resolution.quick-start's default: the first frame is a cheap one (the lit scene without AO, antialiasing and the
   * lens and camera effects) and the full frame follows by itself within a few frames, its passes warmed meanwhile
   * (the demo page's choice; default false). snapshot() always reads the full frame.
   */
  quickStart?: boolean;
  /** Where obscura-core.wasm is served (default: beside obscura.js, through import.meta.url). */
  wasmUrl?: string | URL;
}

/** Starts Obscura on a canvas (its own WebGL 1 context, drawn on requestAnimationFrame when something changed). */
export function createObscura(canvas: HTMLCanvasElement, options?: CreateOptions): Promise<Obscura>;

/** Starts Obscura's AO on the page's own WebGL 1 context (the one the page made on `canvas` first). */
export function createAmbientOcclusion(
  canvas: HTMLCanvasElement, options?: Omit<CreateOptions, 'pointerControls' | 'dynamicResolution' | 'quickStart'>,
): Promise<ObscuraAmbientOcclusion>;

export type ParameterKind = 'switch' | 'number' | 'integer' | 'choice' | 'color' | 'text';

export interface ParameterInfo {
  /** Full name: 'ao.radius', 'tonemap.operator', 'fxaa'; 'preset' for the frame's quality preset. */
  name: string;
  /** The effect it belongs to ('' for 'preset'). */
  effect: string;
  /** An older name get/set/setState also take ('radius'). */
  alias?: string;
  kind: ParameterKind;
  /** For people: '0.0001 .. 1e+06 (scene units)'. */
  range: string;
  help: string;
  /** The default, as text. */
  default: string;
  /** Shown up front by the demo page. */
  primary: boolean;
  /** A change takes a noticeable time (lighting.sun-elevation makes the sky again): apply it when a drag ends. */
  slow: boolean;
  min?: number;
  max?: number;
  /** A switch's or a choice's values; for a number, words it takes besides numbers ('auto'). */
  choices?: string[];
}

export interface TargetInfo {
  name: string;
  encoding: string;
  views: string[];
}

export interface EffectInfo {
  name: string;
  title: string;
  switch: boolean;
  passes: string[];
  targets: TargetInfo[];
  parameters: string[];
}

export interface PresetInfo {
  name: string;
  samples: number;
  turns: number;
  blurRadius: number;
  blurStride: number;
  halfResolution: boolean;
}

export interface KeyBinding {
  /** KeyboardEvent.key: ' ' for space, 'ArrowLeft'. */
  key: string;
  /** How a person reads it: 'space', 'left arrow'. */
  label: string;
  description: string;
}

export interface ContextInfo {
  version: string;
  renderer: string;
  vendor: string;
  shadingLanguage: string;
  maxRenderSize: number;
  depth24: boolean;
  elementIndexUint: boolean;
  timerQuery: boolean;
  [more: string]: unknown;
}

export interface SceneInfo {
  name: string;
  triangles: number;
  /** What the loader repaired or ignored. */
  warnings: string[];
  /** The AO radius the scene gets when nobody sets one, in its units. */
  defaultRadius: number;
  /** A state text gave the radius, so loading a scene keeps it. */
  radiusGiven: boolean;
  [more: string]: unknown;
}

/** Obscura.camera(): the camera looked through, the scene's own cameras, and the free camera. */
export interface CameraState {
  /** 'free', or the scene camera looked through: its name, or its index where the name does not find it. */
  choice: string;
  /** The projection of the view shown. */
  orthographic: boolean;
  /** The scene's cameras (glTF cameras on nodes), in node order. */
  cameras: { name: string; orthographic: boolean }[];
  /** The free camera: eye, target and up in scene units, fovy in degrees, ymag the orthographic half height. */
  eye: [number, number, number];
  target: [number, number, number];
  up: [number, number, number];
  fovy: number;
  ymag: number;
}

export interface Timeline {
  animations: string[];
  animation: string;
  time: number;
  duration: number;
  playing: boolean;
  speed: number;
  loop: boolean;
  frameInterval: number;
}

export interface Stats {
  width: number;
  height: number;
  continuous: boolean;
  pending: boolean;
  frameMs: number;
  cpuMs: number;
  lastCpuMs: number;
  /** The render call's own time (planning and the passes' WebGL calls), smoothed and of the last drawn frame. */
  hostMs: number;
  lastHostMs: number;
  frames: number;
  /** The last frame was quick start's cheap one (resolution.quick-start): the full frame follows by itself. */
  cheapFrame: boolean;
  timerQueries: boolean;
  /** GPU milliseconds per pass of a recent measured frame (one drawn frame in four, every frame under dynamic
   *  resolution, and the first after a pause; null: the pass did not run), or null without timer queries. */
  passMs: Record<string, number | null> | null;
  passesRun: string[];
  /** Passes whose work another pass did: {tonemap: 'lighting'}. */
  passesDoneBy: Record<string, string>;
  history: { frames: number; drops: number; frameIndex: number };
  pooledTargets: number;
  /** Triangles the last geometry pass drew, at the levels of detail `gbuffer.lod` chose. */
  triangles: number | null;
  /** The last geometry pass's draw calls (a static batch's members at one level of detail in one). */
  drawCalls: number | null;
  contextLost: boolean;
  contextRestores: number;
  glObjects: Record<string, number>;
  /** Why frames stopped, or ''. */
  error: string;
  /** The size the effects ran at, the render scale and dynamic resolution's state (docs/resolution.md). */
  render: {
    width: number; height: number; scale: number; pixelRatio: number; devicePixelRatio: number; dynamic: boolean;
    measuredBy: 'gpu' | 'cpu'; meanMs: number; framesMeasured: number; refining: boolean; step: number;
    targetMs: number; changes: number;
  };
  [more: string]: unknown;
}

/** Where start-up went, in ms (Obscura.startup()). */
export interface Startup {
  wasmMs: number;
  createMs: number;
  coreMs: number;
  coreParts: Record<string, number>;
  firstFrameMs: number | null;
  firstFrameCpuMs: number | null;
  firstFrameParts: Record<string, number>;
  /** From createObscura's end to the animation frame after the first full frame (firstFrameMs without quick start). */
  fullFrameMs: number | null;
  /** What quick start did (resolution.quick-start); cheapFrames 0 and firstFullFrame 0 without it. */
  quickStart: {
    /** Frames drawn cheap before the full one. */
    cheapFrames: number;
    /** The index of the first full frame (null before it). */
    firstFullFrame: number | null;
    /** When the renderer drew it, ms since the renderer was made (null before it). */
    fullAtMs: number | null;
    /** Each pass of the full frame drawn once at a small size by a cheap frame: which frame, when, its CPU time. */
    warmed: { pass: string; frame: number; atMs: number; cpuMs: number }[];
  } | null;
}

export interface Snapshot {
  width: number;
  height: number;
  /** RGBA8, rows top to bottom. */
  pixels: Uint8Array;
}

export type SideFiles = Record<string, ArrayBuffer | Uint8Array>;

/** Fires 'change' after every call that changes what is shown, and 'timeupdate' on every animation frame while the
 * timeline plays. */
export class Obscura extends EventTarget {
  private constructor();
  readonly canvas: HTMLCanvasElement;

  // What the core offers.
  readonly parameters: ParameterInfo[];
  readonly effects: EffectInfo[];
  readonly presets: PresetInfo[];
  /** 'final', 'split', then every target's debug view ('normals', 'depth', 'ao', ...). */
  readonly views: string[];
  readonly compareSwitches: string[];
  readonly keyBindings: KeyBinding[];
  readonly passes: string[];
  readonly context: ContextInfo;

  // Parameters, view and state.
  get(name: string): string;
  effective(name: string): string;
  set(name: string, value: string | number): void;
  readonly view: string;
  setView(view: string): void;
  readonly compare: string;
  setCompare(name: string): void;
  /** 'separate' | 'atlas' | 'mipchain' | 'auto'; returns the storage now in use. */
  setHierarchyStorage(name: string): string;
  /**
   * 'halffloat' | 'mipchain' | 'atlas' | 'auto': where the prefiltered environment's levels live (half floats the
   * hardware filters, or RGB9E5 filtered by hand); returns the layout now in use.
   */
  setEnvironmentLayout(name: string): string;
  /**
   * Allows (the default) or refuses vertex array objects for the scene's draws (OES_vertex_array_object); returns
   * whether the scene now draws with them. The image is the same either way.
   */
  setVertexArrays(allow: boolean): boolean;
  /**
   * Allows (the default) or refuses static batches: the still, rigid, opaque instances that share a material drawn
   * as one piece. Returns how many batches the scene now draws. The image is the same either way.
   */
  setStaticBatches(allow: boolean): number;
  /** The view, the parameters that differ from their defaults, the timeline and the camera, as query-string text. */
  state(): string;
  setState(query: string): void;
  handleKey(key: string): boolean;

  // Camera.
  orbit(dx: number, dy: number, viewportHeight?: number): void;
  pan(dx: number, dy: number, viewportHeight?: number): void;
  zoom(factor: number): void;
  resetCamera(): void;
  /**
   * The cameras: the free one (orbit, pan, zoom) and the scene's own (glTF cameras on nodes, moved by its animation).
   * choice: 'free' or the scene camera looked through (its name, or its index); orthographic: the view shown's
   * projection; the rest the free camera's.
   */
  camera(): CameraState;
  /** Looks through 'free' or a scene camera (a name, or an index into camera().cameras); the state keeps camera=. */
  setCamera(choice: string | number): void;
  /** The free camera orthographic or perspective, from the view shown (state: projection=orthographic&ymag=). */
  setOrthographic(on: boolean): void;
  /** Depth of field's autofocus on (x, y), CSS pixels from the canvas's top left (dof.focus=auto, dof.focus-x/-y). */
  focusAt(x: number, y: number): void;

  // Scenes.
  loadScene(bytes: ArrayBuffer | Uint8Array, name: string, sideFiles?: SideFiles): Promise<SceneInfo>;
  loadFiles(files: FileList | File[], options?: { onProgress?: (fraction: number) => void }): Promise<SceneInfo>;
  /** An equirectangular .hdr (or a PNG of RGBE bytes) as lighting.environment; resolves to its path in the module. */
  loadEnvironment(bytes: ArrayBuffer | Uint8Array, name: string): Promise<string>;
  /**
   * A 3D LUT for colour grading (Adobe / Resolve .cube, as bytes or text) as grading.lut, with grading switched on;
   * resolves to its path in the module. Rejects with ObscuraError naming the line of a malformed file; the grade in use
   * stays then.
   */
  loadLut(cube: ArrayBuffer | Uint8Array | string, name?: string): Promise<string>;
  loadBuiltinScene(): SceneInfo;
  scene(): SceneInfo;
  readonly defaultRadius: number;

  // Timeline.
  timeline(): Timeline;
  readonly animations: string[];
  readonly animation: string;
  setAnimation(choice: string | number): void;
  readonly time: number;
  readonly duration: number;
  setTime(seconds: number): void;
  readonly playing: boolean;
  play(): void;
  pause(): void;
  stepFrames(frames?: number): void;
  readonly speed: number;
  setSpeed(factor: number): void;
  readonly loop: boolean;
  setLoop(loop: boolean): void;

  // Measurements.
  setContinuous(continuous: boolean): void;
  stats(): Stats;
  /** Where start-up went (the page prints it in its stats). */
  startup(): Startup;
  /** startup() once the first frame is on screen. */
  readonly firstFrame: Promise<Startup>;
  draw(): void;
  snapshot(): Snapshot;
  attachPointerControls(): void;

  addEventListener(type: 'change' | 'timeupdate', listener: (event: Event) => void,
                   options?: boolean | AddEventListenerOptions): void;
  addEventListener(type: string, listener: EventListenerOrEventListenerObject | null,
                   options?: boolean | AddEventListenerOptions): void;
}

/** The camera the page drew its G-buffer with: eye, target and up in its world units, vertical field of view in
 * degrees, and the near and far planes its projection used (the same as it gives obscuraGBuffer). */
export interface Camera {
  eye: [number, number, number] | number[];
  target: [number, number, number] | number[];
  up?: [number, number, number] | number[];
  fovy?: number;
  near?: number;
  far?: number;
}

export interface AmbientOcclusionStats {
  width: number;
  height: number;
  frames: number;
  cpuMs: number;
  passesRun: string[];
  pooledTargets: number;
}

/** Obscura's AO on the page's own WebGL 1 context and geometry. */
export class ObscuraAmbientOcclusion {
  private constructor();
  readonly canvas: HTMLCanvasElement;
  /** The page's context, which Obscura draws with too. */
  readonly gl: WebGLRenderingContext;
  readonly version: string;
  /** The GLSL ES 1.00 chunk obscura_gbuffer.glsl (obscuraGBuffer(viewNormal, viewDepth, near, far)). */
  readonly gbufferGlsl: string;
  readonly parameters: ParameterInfo[];
  get(name: string): string;
  set(name: string, value: string | number): void;
  /** Binds Obscura's G-buffer framebuffer (cleared, viewport set); the page draws its meshes next. */
  beginGBuffer(width?: number, height?: number): void;
  /** The AO of the G-buffer drawn since beginGBuffer: RGB visibility, A 1; owned by Obscura. */
  ambientOcclusion(camera: Camera): WebGLTexture;
  /** Multiplies the last AO into the framebuffer the page has bound. */
  composite(width?: number, height?: number): void;
  stats(): AmbientOcclusionStats;
}
