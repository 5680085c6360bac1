// Writes the fuzzer's seeds for compressed and quantized geometry (run from the repository root after
// `npm ci` in web/, which brings the meshoptimizer encoder):
//   node tests/fuzz/seeds/make-compressed-seeds.mjs
// - meshopt-quantized.glb: a 9 x 9 grid whose positions are unnormalized u16 (KHR_mesh_quantization) under a node
//   scale, normals octahedral-filtered bytes, both EXT_meshopt_compression ATTRIBUTES, indices TRIANGLES, the data
//   only compressed (a fallback buffer without data), and a LINE_STRIP primitive beside it.
// - draco-engine.glb: Debian's Draco 2CylinderEngine (.gltf + .bin) as one .glb.
// - draco-grid.glb: the 9 x 9 grid (float positions, normals, texture coordinates) Draco-compressed twice, with the
//   edgebreaker and with the sequential connectivity coder, in two primitives. The engine takes about 130 ms a run in
//   the sanitized fuzzer and this one under 1 ms, so the worker that schedules by execution time mutates Draco's
//   streams here (tools/fuzz-gltf.sh).
import fs from 'node:fs';
import { createRequire } from 'node:module';
import { MeshoptEncoder } from '../../../web/node_modules/meshoptimizer/meshopt_encoder.module.js';

const draco3d = createRequire(import.meta.url)('../../../web/node_modules/draco3d/draco3d.js');

const out = new URL('./', import.meta.url);

function glb(json, bin) {
  const text = Buffer.from(JSON.stringify(json));
  const jsonChunk = Buffer.concat([text, Buffer.alloc((4 - (text.length % 4)) % 4, 0x20)]);
  const binChunk = Buffer.concat([bin, Buffer.alloc((4 - (bin.length % 4)) % 4)]);
  const header = Buffer.alloc(12);
  header.write('glTF', 0);
  header.writeUInt32LE(2, 4);
  header.writeUInt32LE(12 + 8 + jsonChunk.length + 8 + binChunk.length, 8);
  const chunk = (type, data) => {
    const h = Buffer.alloc(8);
    h.writeUInt32LE(data.length, 0);
    h.writeUInt32LE(type, 4);
    return Buffer.concat([h, data]);
  };
  return Buffer.concat([header, chunk(0x4E4F534A, jsonChunk), chunk(0x004E4942, binChunk)]);
}

await MeshoptEncoder.ready;
const n = 9;
const positions = new Uint16Array(n * n * 4);  // x, y, z, padding
const normals = new Float32Array(n * n * 4);
for (let y = 0; y < n; y++) {
  for (let x = 0; x < n; x++) {
    const i = y * n + x;
    positions.set([x * 1000, y * 1000, Math.round(500 + 300 * Math.sin(x) * Math.cos(y)), 0], i * 4);
    const length = Math.hypot(0.3 * Math.cos(x), 0.2, 1);
    normals.set([-0.3 * Math.cos(x) / length, 0.2 / length, 1 / length, 0], i * 4);
  }
}
const indices = [];
for (let y = 0; y + 1 < n; y++) {
  for (let x = 0; x + 1 < n; x++) {
    const a = y * n + x;
    indices.push(a, a + 1, a + n + 1, a, a + n + 1, a + n);
  }
}
const streams = [
  MeshoptEncoder.encodeGltfBuffer(new Uint8Array(positions.buffer), n * n, 8, 'ATTRIBUTES'),
  MeshoptEncoder.encodeGltfBuffer(MeshoptEncoder.encodeFilterOct(normals, n * n, 4, 8), n * n, 4, 'ATTRIBUTES'),
  MeshoptEncoder.encodeGltfBuffer(new Uint8Array(new Uint32Array(indices).buffer), indices.length, 4, 'TRIANGLES'),
];
const strip = new Float32Array([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 1]);
let bin = Buffer.alloc(0);
const place = (data) => {
  bin = Buffer.concat([bin, Buffer.alloc((4 - (bin.length % 4)) % 4)]);
  const offset = bin.length;
  bin = Buffer.concat([bin, Buffer.from(data.buffer ?? data, data.byteOffset ?? 0, data.byteLength ?? data.length)]);
  return offset;
};
const compressed = (data, count, stride, mode, filter) => ({
  buffer: 1, byteLength: count * stride, ...(mode === 'ATTRIBUTES' ? { byteStride: stride } : {}),
  extensions: { EXT_meshopt_compression: { buffer: 0, byteOffset: place(data), byteLength: data.length, byteStride: stride,
                                           count, mode, ...(filter ? { filter } : {}) } },
});
const bufferViews = [
  compressed(streams[0], n * n, 8, 'ATTRIBUTES'),
  compressed(streams[1], n * n, 4, 'ATTRIBUTES', 'OCTAHEDRAL'),
  compressed(streams[2], indices.length, 4, 'TRIANGLES'),
];
bufferViews.push({ buffer: 0, byteOffset: place(strip), byteLength: strip.byteLength });
const meshopt = {
  asset: { version: '2.0' },
  extensionsUsed: ['EXT_meshopt_compression', 'KHR_mesh_quantization'],
  extensionsRequired: ['EXT_meshopt_compression', 'KHR_mesh_quantization'],
  buffers: [{ byteLength: 0 }, { byteLength: 4096, extensions: { EXT_meshopt_compression: { fallback: true } } }],
  bufferViews,
  accessors: [
    { bufferView: 0, componentType: 5123, count: n * n, type: 'VEC3', min: [0, 0, 200], max: [8000, 8000, 800] },
    { bufferView: 1, componentType: 5120, normalized: true, count: n * n, type: 'VEC3' },
    { bufferView: 2, componentType: 5125, count: indices.length, type: 'SCALAR' },
    { bufferView: 3, componentType: 5126, count: 4, type: 'VEC3', min: [0, 0, 0], max: [1, 1, 1] },
  ],
  meshes: [{ primitives: [{ attributes: { POSITION: 0, NORMAL: 1 }, indices: 2 }, { attributes: { POSITION: 3 }, mode: 3 }] }],
  nodes: [{ mesh: 0, scale: [0.001, 0.001, 0.001] }],
  scenes: [{ nodes: [0] }],
  scene: 0,
};
meshopt.buffers[0].byteLength = (bin.length + 3) & ~3;
fs.writeFileSync(new URL('meshopt-quantized.glb', out), glb(meshopt, bin));

const models = '/usr/share/assimp/models/glTF2/draco/';
const engine = JSON.parse(fs.readFileSync(`${models}2CylinderEngine.gltf`, 'utf8'));
const engineBin = fs.readFileSync(`${models}2CylinderEngine.bin`);
delete engine.buffers[0].uri;
engine.buffers[0].byteLength = (engineBin.length + 3) & ~3;
fs.writeFileSync(new URL('draco-engine.glb', out), glb(engine, engineBin));

// The grid's vertices as floats, Draco-compressed: POSITION, NORMAL and TEXCOORD_0, u16 indices.
const dracoModule = await draco3d.createEncoderModule({});
const gridPositions = new Float32Array(n * n * 3);
const gridNormals = new Float32Array(n * n * 3);
const gridUvs = new Float32Array(n * n * 2);
for (let i = 0; i < n * n; i++) {
  gridPositions.set([positions[i * 4] / 1000, positions[i * 4 + 1] / 1000, positions[i * 4 + 2] / 1000], i * 3);
  gridNormals.set([normals[i * 4], normals[i * 4 + 1], normals[i * 4 + 2]], i * 3);
  gridUvs.set([(i % n) / (n - 1), Math.floor(i / n) / (n - 1)], i * 2);
}
const dracoStream = (method) => {
  const encoder = new dracoModule.Encoder();
  const builder = new dracoModule.MeshBuilder();
  const mesh = new dracoModule.Mesh();
  builder.AddFacesToMesh(mesh, indices.length / 3, new Uint32Array(indices));
  const ids = {
    POSITION: builder.AddFloatAttributeToMesh(mesh, dracoModule.POSITION, n * n, 3, gridPositions),
    NORMAL: builder.AddFloatAttributeToMesh(mesh, dracoModule.NORMAL, n * n, 3, gridNormals),
    TEXCOORD_0: builder.AddFloatAttributeToMesh(mesh, dracoModule.TEX_COORD, n * n, 2, gridUvs),
  };
  encoder.SetAttributeQuantization(dracoModule.POSITION, 14);
  encoder.SetAttributeQuantization(dracoModule.NORMAL, 10);
  encoder.SetAttributeQuantization(dracoModule.TEX_COORD, 12);
  encoder.SetEncodingMethod(method);
  const encoded = new dracoModule.DracoInt8Array();
  const length = encoder.EncodeMeshToDracoBuffer(mesh, encoded);
  const bytes = Buffer.alloc(length);
  for (let i = 0; i < length; i++) bytes[i] = encoded.GetValue(i) & 0xff;
  [encoded, mesh, builder, encoder].forEach((object) => dracoModule.destroy(object));
  return { bytes, ids };
};
const dracoStreams = [dracoStream(dracoModule.MESH_EDGEBREAKER_ENCODING),
                      dracoStream(dracoModule.MESH_SEQUENTIAL_ENCODING)];
let dracoBin = Buffer.alloc(0);
const dracoViews = dracoStreams.map(({ bytes }) => {
  dracoBin = Buffer.concat([dracoBin, Buffer.alloc((4 - (dracoBin.length % 4)) % 4)]);
  const view = { buffer: 0, byteOffset: dracoBin.length, byteLength: bytes.length };
  dracoBin = Buffer.concat([dracoBin, bytes]);
  return view;
});
const gridAccessors = () => [
  { componentType: 5126, count: n * n, type: 'VEC3', min: [0, 0, 0.2], max: [8, 8, 0.8] },
  { componentType: 5126, count: n * n, type: 'VEC3' },
  { componentType: 5126, count: n * n, type: 'VEC2' },
  { componentType: 5123, count: indices.length, type: 'SCALAR' },
];
const dracoGrid = {
  asset: { version: '2.0' },
  extensionsUsed: ['KHR_draco_mesh_compression'],
  extensionsRequired: ['KHR_draco_mesh_compression'],
  buffers: [{ byteLength: (dracoBin.length + 3) & ~3 }],
  bufferViews: dracoViews,
  accessors: [...gridAccessors(), ...gridAccessors()],
  meshes: [{
    primitives: dracoStreams.map(({ ids }, p) => ({
      attributes: { POSITION: 4 * p, NORMAL: 4 * p + 1, TEXCOORD_0: 4 * p + 2 },
      indices: 4 * p + 3,
      extensions: { KHR_draco_mesh_compression: { bufferView: p, attributes: ids } },
    })),
  }],
  nodes: [{ mesh: 0 }],
  scenes: [{ nodes: [0] }],
  scene: 0,
};
fs.writeFileSync(new URL('draco-grid.glb', out), glb(dracoGrid, dracoBin));
