// Writes the fuzzer's seeds for compressed and quantized geometry (run from the repository root after
// `npm ci` in web/, which brings the meshoptimizer encoder):
//   node tests/fuzz/seeds/make-compressed-seeds.mjs
// - meshopt-quantized.glb: a 9 x 9 grid whose positions are unnormalized u16 (KHR_mesh_quantization) under a node
//   scale, normals octahedral-filtered bytes, both EXT_meshopt_compression ATTRIBUTES, indices TRIANGLES, the data
//   only compressed (a fallback buffer without data), and a LINE_STRIP primitive beside it.
// - draco-engine.glb: Debian's Draco 2CylinderEngine (.gltf + .bin) as one .glb.
import fs from 'node:fs';
import { MeshoptEncoder } from '../../../web/node_modules/meshoptimizer/meshopt_encoder.module.js';

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
