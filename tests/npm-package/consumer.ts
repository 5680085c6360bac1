// A TypeScript consumer of the npm package: every part of the API, typed (package.test.mjs runs tsc --noEmit --strict
// on it against the installed package's obscura.d.ts).
import {
  createAmbientOcclusion, createObscura, Obscura, ObscuraAmbientOcclusion, ObscuraError,
  type Camera, type ParameterInfo, type SceneInfo, type Snapshot, type Stats, type Timeline,
} from 'obscura-webgl';

export async function scene(canvas: HTMLCanvasElement): Promise<Obscura> {
  const obscura: Obscura = await createObscura(canvas, { pointerControls: false, checkGlErrors: true,
                                                          wasmUrl: new URL('obscura-core.wasm', location.href) });
  const radius: ParameterInfo | undefined = obscura.parameters.find((p) => p.name === 'ao.radius');
  if (radius?.kind === 'number' && radius.min !== undefined) obscura.set('ao.radius', radius.min * 2);
  obscura.set('tonemap.operator', 'agx');
  const views: string[] = obscura.views;
  obscura.setView(views.includes('split') ? 'split' : 'final');
  obscura.setCompare(obscura.compareSwitches[0] ?? 'ao');
  const effects: string[] = obscura.effects.map((e) => `${e.title}: ${e.passes.join(' ')} ${e.targets[0]?.encoding}`);
  const presets: number[] = obscura.presets.map((p) => p.samples);
  const keys: string[] = obscura.keyBindings.map((k) => k.label);
  const maxSize: number = obscura.context.maxRenderSize;
  const state: string = obscura.state();
  obscura.setState(state);
  obscura.orbit(10, 5);
  obscura.pan(1, 2, 100);
  obscura.zoom(1.1);
  obscura.resetCamera();
  const handled: boolean = obscura.handleKey(' ');
  const storage: string = obscura.setHierarchyStorage('auto');
  const loaded: SceneInfo = await obscura.loadScene(new Uint8Array(0), 'empty.glb', { 'a.bin': new ArrayBuffer(4) });
  const builtin: SceneInfo = obscura.loadBuiltinScene();
  const warnings: string[] = obscura.scene().warnings;
  const radiusNow: number = obscura.defaultRadius + loaded.defaultRadius + builtin.triangles;
  const timeline: Timeline = obscura.timeline();
  obscura.setAnimation(timeline.animations.length > 0 ? 0 : 'none');
  obscura.setTime(obscura.time + obscura.duration);
  if (!obscura.playing) obscura.play();
  obscura.pause();
  obscura.stepFrames(-1);
  obscura.setSpeed(obscura.speed * 2);
  obscura.setLoop(!obscura.loop);
  obscura.setContinuous(false);
  const stats: Stats = obscura.stats();
  const gbufferMs: number | null | undefined = stats.passMs?.gbuffer;
  obscura.draw();
  const shot: Snapshot = obscura.snapshot();
  const bytes: Uint8Array = shot.pixels;
  obscura.addEventListener('change', () => obscura.get('ao.radius'));
  obscura.addEventListener('timeupdate', (event: Event) => event.type);
  console.log(effects, presets, keys, maxSize, handled, storage, warnings, radiusNow, gbufferMs, bytes.length,
              obscura.effective('ao.bias'), obscura.view, obscura.compare, stats.history.drops, obscura.animation,
              obscura.animations);
  return obscura;
}

export async function ownGeometry(canvas: HTMLCanvasElement): Promise<WebGLTexture> {
  const gl = canvas.getContext('webgl');
  if (!gl) throw new Error('no WebGL 1');
  const ao: ObscuraAmbientOcclusion = await createAmbientOcclusion(canvas, { checkGlErrors: false });
  const source: string = 'precision highp float;\n' + ao.gbufferGlsl;
  ao.set('ao.radius', 0.5);
  const version: string = ao.version + ao.get('ao.radius') + ao.parameters.length + source.length;
  ao.beginGBuffer();
  ao.beginGBuffer(gl.drawingBufferWidth, gl.drawingBufferHeight);
  const camera: Camera = { eye: [0, 1, 3], target: [0, 0, 0], fovy: 50, near: 0.1, far: 50 };
  const texture: WebGLTexture = ao.ambientOcclusion(camera);
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  ao.composite();
  const passes: string[] = ao.stats().passesRun;
  console.log(version, passes, ao.gl === gl);
  return texture;
}

export function describe(error: unknown): string {
  return error instanceof ObscuraError ? `refused: ${error.message}` : String(error);
}
