// The three.js side of the browser benchmark, set up the way a new user would: GLTFLoader, a WebGLRenderer with its
// default options, a hemisphere light plus a directional light, and the post-processing passes as their READMEs and
// three's examples show them. bench.mjs opens one page per renderer (three.html?...), calls benchSetup() and then
// times window.benchDraw() with the same loop it uses for Obscura (draw, gl.finish, a 1-pixel gl.readPixels).
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { EffectComposer } from 'three/addons/postprocessing/EffectComposer.js';
import { RenderPass } from 'three/addons/postprocessing/RenderPass.js';
import { SAOPass } from 'three/addons/postprocessing/SAOPass.js';
import { OutputPass } from 'three/addons/postprocessing/OutputPass.js';
import { RoomEnvironment } from 'three/addons/environments/RoomEnvironment.js';
import { N8AOPass, N8AOPostPass } from 'n8ao';
import * as Postprocessing from 'postprocessing';
import { installPassCounter } from './pass-counter.mjs';

// Obscura's lighting (src/effects/lighting/LightingEffect.h), in three.js terms. Obscura shades base * (hemisphere(n) *
// AO + light * max(n.l, 0)) with linear colours; three.js's Lambert term is base / pi times the irradiance, so the same
// colours at intensity pi give the same diffuse light (MeshStandardMaterial adds a faint specular on top: the
// engine's materials are metalness 0, roughness 1).
const LIGHTING = {
  directionToLight: [0.45, 0.8, 0.35],
  lightColor: [0.50, 0.48, 0.44],
  skyColor: [0.62, 0.66, 0.72],
  groundColor: [0.30, 0.28, 0.26],
  background: [0.62, 0.67, 0.73],  // display-encoded (sRGB) in Obscura
  intensity: Math.PI,
};

const linear = ([r, g, b]) => new THREE.Color().setRGB(r, g, b, THREE.LinearSRGBColorSpace);

// SAOPass parameters for a world-space AO radius r (see docs/benchmarks.md, "Choices"):
//   saoKernelRadius: SAOShader places its 7 taps on a spiral out to kernelRadius pixels of the pass's resolution,
//     the same for every pixel; r projected at the depth of the model's centre (the camera's target) gives it.
//   saoScale: each tap's weight is 1 / (1 + (scale |v| / far)^2); scale = far / r halves it at |v| = r.
//   saoIntensity, saoBias: with that scale a tap contributes max(0, r cos(theta) - bias) / (1 + (|v|/r)^2) (a
//     length: SAOShader divides n.v by scale |v| / far), so intensity = k / r and bias = b r make the AO independent
//     of the model's units: AO = k mean(max(0, cos(theta) - b) / (1 + (|v|/r)^2)).
//   The blur keeps SAOPass's defaults (radius 8, std dev 4, depth cutoff 0.01 of far - near).
export const SAO_SHAPE = { k: 1.0, b: 0.05 };
export function saoParameters(r, camera, heightPixels) {
  const distance = camera.eye.reduce((sum, e, i) => sum + (e - camera.target[i]) ** 2, 0) ** 0.5;
  const pixelsPerUnit = heightPixels / 2 / (Math.tan((camera.fovy * Math.PI) / 360) * distance);
  return {
    saoKernelRadius: r * pixelsPerUnit,
    saoScale: camera.far / r,
    saoIntensity: SAO_SHAPE.k / r,
    saoBias: SAO_SHAPE.b * r,
  };
}

function makeRenderer(options = {}) {
  // WebGLRenderer's defaults otherwise (antialias false, no tone mapping, sRGB output, WebGL 2).
  const renderer = new THREE.WebGLRenderer(options);
  renderer.setPixelRatio(window.devicePixelRatio);
  renderer.setSize(window.innerWidth, window.innerHeight);
  document.body.appendChild(renderer.domElement);
  return renderer;
}

// The image-based light of the modes that do Obscura's lighting work ('three-env-*', 'pmndrs-all'): the file's
// materials as loaded (MeshStandardMaterial) under scene.environment = a PMREM of three's RoomEnvironment (as three's
// examples set it up: PMREMGenerator.fromScene(new RoomEnvironment(), 0.04)) and the same directional sun; no
// hemisphere light (the environment is the ambient light, as Obscura's sky is).
const ENVIRONMENT_MODES = new Set(['three-env-plain', 'three-env-n8ao', 'pmndrs-all']);

// options: {mode, modelUrl, camera: {eye, target, up, fovy, near, far}, aoRadius, aoOnly, fog}. Resolves to a
// description of what was set up; afterwards window.benchDraw() draws one frame and window.benchGl is the renderer's
// context. aoOnly (peer-accuracy.mjs): the AO pass shows its ambient visibility alone, as each pass's own debug
// output offers it (SAOPass's OUTPUT.SAO, N8AO's "AO" display mode), sRGB-encoded into the canvas. fog ('pmndrs-all'):
// {density, color}, three's FogExp2 (1 - exp(-(density d)^2)) as Obscura's exp2 fog (bench.mjs sets both).
window.benchSetup = async ({ mode, modelUrl, camera: c, aoRadius, aoOnly = false, fog = null }) => {
  const gltf = await new GLTFLoader().loadAsync(modelUrl);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color().setRGB(...LIGHTING.background, THREE.SRGBColorSpace);
  scene.add(gltf.scene);
  const withEnvironment = ENVIRONMENT_MODES.has(mode);
  if (!withEnvironment) {
    const hemisphere = new THREE.HemisphereLight(linear(LIGHTING.skyColor), linear(LIGHTING.groundColor),
                                                 LIGHTING.intensity);
    scene.add(hemisphere);
  }
  const sun = new THREE.DirectionalLight(linear(LIGHTING.lightColor), LIGHTING.intensity);
  sun.position.set(...LIGHTING.directionToLight);  // shines towards its target at the origin
  scene.add(sun);
  if (mode === 'pmndrs-all') scene.fog = new THREE.FogExp2(linear(fog.color), fog.density);

  // Box3.setFromObject(..., precise = true): every vertex after its world transform, as Obscura and glb-bounds.mjs.
  scene.updateMatrixWorld(true);
  const box = new THREE.Box3().setFromObject(gltf.scene, true);
  const bounds = { min: box.min.toArray(), max: box.max.toArray(), center: box.getCenter(new THREE.Vector3()).toArray(),
                   radius: box.getSize(new THREE.Vector3()).length() / 2 };

  const width = window.innerWidth, height = window.innerHeight;
  // The camera is Obscura's own framing of the model (its state() after loadScene), set before any pass reads it:
  // SAOPass copies the inverse projection when the composer sizes it.
  const camera = new THREE.PerspectiveCamera(c.fovy, width / height, c.near, c.far);
  camera.position.set(...c.eye);
  camera.up.set(...c.up);
  camera.lookAt(...c.target);
  camera.updateProjectionMatrix();
  camera.updateMatrixWorld(true);

  const info = { mode, three: THREE.REVISION, bounds, setup: {} };
  let renderer, draw;
  // The environment is prefiltered once, when the renderer is made (not timed: it is the warm-up's).
  const environmentFor = (r) => {
    if (!withEnvironment) return;
    const pmrem = new THREE.PMREMGenerator(r);
    scene.environment = pmrem.fromScene(new RoomEnvironment(), 0.04).texture;
    pmrem.dispose();
  };
  if (mode === 'three-plain' || mode === 'three-plain-aa' || mode === 'three-env-plain') {
    renderer = makeRenderer(mode === 'three-plain-aa' ? { antialias: true } : {});
    environmentFor(renderer);
    draw = () => renderer.render(scene, camera);
    info.setup = { pipeline: 'renderer.render(scene, camera)' +
                             (withEnvironment ? ', scene.environment: PMREM of RoomEnvironment' : '') };
  } else if (mode === 'three-sao') {
    renderer = makeRenderer();
    // As three's webgl_postprocessing_sao example: RenderPass, SAOPass, OutputPass (sRGB conversion).
    const composer = new EffectComposer(renderer);
    composer.addPass(new RenderPass(scene, camera));
    const sao = new SAOPass(scene, camera);
    Object.assign(sao.params, saoParameters(aoRadius, c, renderer.domElement.height));
    if (aoOnly) sao.params.output = SAOPass.OUTPUT.SAO;
    composer.addPass(sao);
    composer.addPass(new OutputPass());
    draw = () => composer.render();
    info.setup = { pipeline: 'EffectComposer: RenderPass, SAOPass, OutputPass', saoParams: { ...sao.params },
                   saoResolution: sao.saoMaterial.uniforms.size.value.toArray() };
  } else if (mode === 'three-n8ao' || mode === 'three-env-n8ao') {
    renderer = makeRenderer();
    environmentFor(renderer);
    // As N8AO's README: N8AOPass replaces the RenderPass; it converts to sRGB itself (gammaCorrection, default on).
    const composer = new EffectComposer(renderer);
    const n8ao = new N8AOPass(scene, camera, renderer.domElement.width, renderer.domElement.height);
    n8ao.configuration.aoRadius = aoRadius;  // world units; everything else stays at N8AO's defaults
    if (aoOnly) n8ao.setDisplayMode('AO');
    composer.addPass(n8ao);
    draw = () => composer.render();
    info.setup = { pipeline: 'EffectComposer: N8AOPass' +
                             (withEnvironment ? ', scene.environment: PMREM of RoomEnvironment' : ''),
                   configuration: { ...n8ao.configuration } };
    // What N8AO decided at its first frames (depth mip atlas where float targets render, denoiser in use).
    window.benchAfterWarmup = () => JSON.parse(JSON.stringify({
      depthMipAtlas: n8ao.depthMipsSupported, effective: n8ao.effectiveConfiguration ?? null }));
  } else if (mode === 'three-n8ao-pp') {
    renderer = makeRenderer();
    // As N8AO's README for pmndrs/postprocessing: RenderPass, then N8AOPostPass (last pass: it gamma-corrects).
    const composer = new Postprocessing.EffectComposer(renderer);
    composer.addPass(new Postprocessing.RenderPass(scene, camera));
    const n8ao = new N8AOPostPass(scene, camera, renderer.domElement.width, renderer.domElement.height);
    n8ao.configuration.aoRadius = aoRadius;
    composer.addPass(n8ao);
    draw = () => composer.render();
    info.setup = { pipeline: 'postprocessing EffectComposer: RenderPass, N8AOPostPass',
                   configuration: { ...n8ao.configuration } };
  } else if (mode === 'pmndrs-all') {
    // Every effect Obscura runs in its every-effect frame, as pmndrs/postprocessing's documentation composes them:
    // RenderPass (with three's FogExp2), N8AOPostPass, then one EffectPass per convolution: depth of field, bloom
    // with the tone mapping, FXAA. The frame buffers are half-float (HDR for the bloom), the renderer's own tone
    // mapping off (the ToneMappingEffect's).
    renderer = makeRenderer({ powerPreference: 'high-performance', antialias: false, stencil: false, depth: false });
    environmentFor(renderer);
    const composer = new Postprocessing.EffectComposer(renderer, { frameBufferType: THREE.HalfFloatType });
    composer.addPass(new Postprocessing.RenderPass(scene, camera));
    const n8ao = new N8AOPostPass(scene, camera, renderer.domElement.width, renderer.domElement.height);
    n8ao.configuration.aoRadius = aoRadius;
    n8ao.configuration.gammaCorrection = false;  // not the last pass
    composer.addPass(n8ao);
    const distance = Math.hypot(...c.eye.map((e, i) => e - c.target[i]));
    const dof = new Postprocessing.DepthOfFieldEffect(camera, { worldFocusDistance: distance,
                                                                worldFocusRange: bounds.radius, bokehScale: 2 });
    composer.addPass(new Postprocessing.EffectPass(camera, dof));
    composer.addPass(new Postprocessing.EffectPass(camera, new Postprocessing.BloomEffect(),
                                                   new Postprocessing.ToneMappingEffect()));
    composer.addPass(new Postprocessing.EffectPass(camera, new Postprocessing.FXAAEffect()));
    draw = () => composer.render();
    info.setup = { pipeline: 'postprocessing EffectComposer (half float): RenderPass with FogExp2, N8AOPostPass, ' +
                             'EffectPass(DepthOfFieldEffect), EffectPass(BloomEffect, ToneMappingEffect), ' +
                             'EffectPass(FXAAEffect); scene.environment: PMREM of RoomEnvironment',
                   configuration: { ...n8ao.configuration } };
  } else {
    throw new Error(`unknown mode ${mode}`);
  }
  const gl = renderer.getContext();
  info.drawingBuffer = [gl.drawingBufferWidth, gl.drawingBufferHeight];
  info.contextAttributes = gl.getContextAttributes();
  info.webgl = gl.getParameter(gl.VERSION);
  info.glRenderer = gl.getParameter(gl.RENDERER);
  info.camera = { position: camera.position.toArray(), up: camera.up.toArray(), fov: camera.fov,
                  aspect: camera.aspect, near: camera.near, far: camera.far };
  // Colours are JSON-unfriendly objects: keep their hex.
  for (const value of Object.values(info.setup.configuration ?? {})) if (value?.isColor) value.toJSON = () => value.getHexString();
  window.benchDraw = draw;
  window.benchGl = gl;
  window.benchRenderer = renderer;
  installPassCounter(gl);
  return JSON.parse(JSON.stringify(info));
};

document.body.dataset.ready = 'true';
