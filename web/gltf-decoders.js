// Compressed glTF geometry in the browser: KHR_draco_mesh_compression and EXT_meshopt_compression decoded with the
// official npm decoders (draco3d, meshoptimizer; web/package.json, copied into the site's decoders/ folder by
// tools/build-web.sh) before the core loads the file. The core's WebAssembly build has no decoder of its own (the
// native build uses Debian's libdraco and libmeshoptimizer: src/scene/GltfCompression.h); it gets the file with the
// compressed views and primitives replaced by plain ones in one extra buffer, the side file DECODED_URI, and the
// two extensions taken out of extensionsUsed and extensionsRequired. Everything else (limits, accessor checks,
// KHR_mesh_quantization) is the core's, as for any file.
//
// A decoder is fetched the first time a file needs it. A missing or broken decoder, or data it cannot decode, is
// an Error with a one-line message that obscura.js passes on as ObscuraError.

const KHR_DRACO = 'KHR_draco_mesh_compression';
const EXT_MESHOPT = 'EXT_meshopt_compression';
const DECODED_URI = 'obscura-decoded.bin';
const decoderBase = new URL('./decoders/', import.meta.url);

let draco = null;
let meshopt = null;

function loadDraco() {
  draco ??= new Promise((resolve, reject) => {
    const missing = () => reject(new Error(`${KHR_DRACO}: the Draco decoder (decoders/draco_decoder_nodejs.js, ` +
                                           'npm draco3d) could not be loaded'));
    const script = document.createElement('script');
    script.src = new URL('draco_decoder_nodejs.js', decoderBase).href;
    script.onload = () => {
      if (typeof globalThis.DracoDecoderModule !== 'function') return missing();
      globalThis.DracoDecoderModule({ locateFile: (file) => new URL(file, decoderBase).href }).then(resolve, missing);
    };
    script.onerror = missing;
    document.head.appendChild(script);
  });
  draco.catch(() => { draco = null; });  // a later file tries again
  return draco;
}

function loadMeshopt() {
  meshopt ??= import(new URL('meshopt_decoder.module.js', decoderBase).href)
    .then(async ({ MeshoptDecoder }) => { await MeshoptDecoder.ready; return MeshoptDecoder; })
    .catch(() => {
      meshopt = null;
      throw new Error(`${EXT_MESHOPT}: the meshoptimizer decoder (decoders/meshopt_decoder.module.js, ` +
                      'npm meshoptimizer) could not be loaded');
    });
  return meshopt;
}

// The JSON and BIN chunk of a .glb, or the JSON of a .gltf; null when it is neither (the core will say why).
function parseContainer(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const text = (begin, end) => new TextDecoder().decode(bytes.subarray(begin, end));
  try {
    if (bytes.length >= 20 && text(0, 4) === 'glTF') {
      const jsonLength = view.getUint32(12, true);
      if (view.getUint32(16, true) !== 0x4E4F534A || 20 + jsonLength > bytes.length) return null;
      let bin = null;
      const binStart = 20 + jsonLength;
      if (binStart + 8 <= bytes.length && view.getUint32(binStart + 4, true) === 0x004E4942) {
        bin = bytes.subarray(binStart + 8, Math.min(bytes.length, binStart + 8 + view.getUint32(binStart, true)));
      }
      return { glb: true, json: JSON.parse(text(20, 20 + jsonLength)), bin };
    }
    return { glb: false, json: JSON.parse(text(0, bytes.length)), bin: null };
  } catch {
    return null;
  }
}

function base64Bytes(uri) {
  const binary = atob(uri.slice(uri.indexOf(',') + 1));
  const out = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) out[i] = binary.charCodeAt(i);
  return out;
}

function glbOf(json, bin) {
  const encoder = new TextEncoder();
  let text = encoder.encode(JSON.stringify(json));
  const jsonLength = (text.length + 3) & ~3;
  const binLength = bin ? (bin.length + 3) & ~3 : 0;
  const out = new Uint8Array(12 + 8 + jsonLength + (bin ? 8 + binLength : 0));
  const view = new DataView(out.buffer);
  out.set(encoder.encode('glTF'), 0);
  view.setUint32(4, 2, true);
  view.setUint32(8, out.length, true);
  view.setUint32(12, jsonLength, true);
  view.setUint32(16, 0x4E4F534A, true);
  out.fill(0x20, 20, 20 + jsonLength);
  out.set(text, 20);
  if (bin) {
    view.setUint32(20 + jsonLength, binLength, true);
    view.setUint32(24 + jsonLength, 0x004E4942, true);
    out.set(bin, 28 + jsonLength);
  }
  return out;
}

// Whether a file uses either extension (without decoding anything).
export function usesCompression(bytes) {
  const container = parseContainer(bytes);
  const json = container?.json;
  const used = [...(json?.extensionsUsed ?? []), ...(json?.extensionsRequired ?? [])];
  return used.includes(KHR_DRACO) || used.includes(EXT_MESHOPT);
}

// Resolves to {bytes, sideFiles} with the file's compressed geometry decoded, or null when it uses neither
// extension (or is not glTF: the core reports that).
export async function decodeCompressedGltf(bytes, sideFiles = {}) {
  if (!usesCompression(bytes)) return null;
  const { glb, json, bin } = parseContainer(bytes);
  const buffers = json.buffers ?? [];
  const bufferBytes = (index) => {
    const buffer = buffers[index];
    if (!buffer) throw new Error(`buffer ${index} does not exist`);
    if (buffer.uri === undefined) {
      if (glb && index === 0 && bin) return bin;
      throw new Error(`buffer ${index} has no data (an ${EXT_MESHOPT} fallback read without the extension?)`);
    }
    if (buffer.uri.startsWith('data:')) return base64Bytes(buffer.uri);
    const data = sideFiles[buffer.uri] ?? sideFiles[decodeURIComponent(buffer.uri)];
    if (!data) throw new Error(`buffer ${index} is in ${buffer.uri}, which was not given with the file`);
    return data instanceof Uint8Array ? data : new Uint8Array(data);
  };
  const range = (index, offset = 0, length = 0, what = '') => {
    const data = bufferBytes(index);
    if (offset < 0 || length < 0 || offset + length > data.length) {
      throw new Error(`${what} spans bytes ${offset}..${offset + length} but buffer ${index} holds ${data.length}`);
    }
    return data.subarray(offset, offset + length);
  };

  // The decoded data, in one new buffer.
  const chunks = [];
  let length = 0;
  const decodedBuffer = buffers.length;
  const append = (data) => {
    const padding = (4 - (length % 4)) % 4;
    if (padding) chunks.push(new Uint8Array(padding));
    length += padding;
    const offset = length;
    chunks.push(data);
    length += data.length;
    return offset;
  };
  json.bufferViews ??= [];
  const addView = (data) => {
    json.bufferViews.push({ buffer: decodedBuffer, byteOffset: append(data), byteLength: data.length });
    return json.bufferViews.length - 1;
  };

  for (const [v, view] of json.bufferViews.entries()) {
    const ext = view.extensions?.[EXT_MESHOPT];
    if (!ext) continue;
    const what = `bufferView ${v} ${EXT_MESHOPT}`;
    const decoder = await loadMeshopt();
    const source = range(ext.buffer, ext.byteOffset ?? 0, ext.byteLength, what);
    const target = new Uint8Array(ext.count * ext.byteStride);
    try {
      decoder.decodeGltfBuffer(target, ext.count, ext.byteStride, source, ext.mode, ext.filter ?? 'NONE');
    } catch (e) {
      throw new Error(`${what}: ${String(e.message ?? e).split('\n')[0]}`);
    }
    Object.assign(view, { buffer: decodedBuffer, byteOffset: append(target), byteLength: target.length });
    delete view.extensions[EXT_MESHOPT];
  }

  const decodedAccessors = new Set();
  for (const [m, mesh] of (json.meshes ?? []).entries()) {
    for (const [p, primitive] of (mesh.primitives ?? []).entries()) {
      const ext = primitive.extensions?.[KHR_DRACO];
      if (!ext) continue;
      const what = `mesh ${m} primitive ${p} ${KHR_DRACO}`;
      const M = await loadDraco();
      const view = json.bufferViews[ext.bufferView];
      if (!view) throw new Error(`${what} refers to bufferView ${ext.bufferView}, which does not exist`);
      const data = range(view.buffer, view.byteOffset ?? 0, view.byteLength, what);
      const decoder = new M.Decoder();
      const stream = new M.DecoderBuffer();
      stream.Init(new Int8Array(data.buffer, data.byteOffset, data.byteLength), data.byteLength);
      const type = decoder.GetEncodedGeometryType(stream);
      const geometry = type === M.TRIANGULAR_MESH ? new M.Mesh() : new M.PointCloud();
      try {
        const status = type === M.TRIANGULAR_MESH ? decoder.DecodeBufferToMesh(stream, geometry)
          : type === M.POINT_CLOUD ? decoder.DecodeBufferToPointCloud(stream, geometry) : null;
        if (!status || !status.ok() || geometry.ptr === 0) {
          throw new Error(`${what}: ${status ? status.error_msg() : 'not Draco data'}`);
        }
        const points = geometry.num_points();
        if (primitive.indices !== undefined && type === M.TRIANGULAR_MESH && !decodedAccessors.has(primitive.indices)) {
          const accessor = json.accessors?.[primitive.indices];
          if (!accessor) throw new Error(`${what}: indices accessor ${primitive.indices} does not exist`);
          const count = geometry.num_faces() * 3;
          const pointer = M._malloc(count * 4);
          decoder.GetTrianglesUInt32Array(geometry, count * 4, pointer);
          const indices = new Uint8Array(M.HEAPU8.buffer, pointer, count * 4).slice();
          M._free(pointer);
          Object.assign(accessor, { bufferView: addView(indices), byteOffset: 0, componentType: 5125, count });
          delete accessor.sparse;
          decodedAccessors.add(primitive.indices);
        }
        const types = { 5120: [M.DT_INT8, 1], 5121: [M.DT_UINT8, 1], 5122: [M.DT_INT16, 2], 5123: [M.DT_UINT16, 2],
                        5125: [M.DT_UINT32, 4], 5126: [M.DT_FLOAT32, 4] };
        for (const [semantic, id] of Object.entries(ext.attributes ?? {})) {
          const index = primitive.attributes?.[semantic];
          if (index === undefined) throw new Error(`${what} compresses ${semantic}, which the primitive does not list`);
          if (decodedAccessors.has(index)) continue;
          const accessor = json.accessors?.[index];
          const attribute = decoder.GetAttributeByUniqueId(geometry, id);
          if (!accessor || !attribute || attribute.ptr === 0) {
            throw new Error(`${what} ${semantic} names an attribute the compressed data lacks`);
          }
          const [dataType, size] = types[accessor.componentType] ?? [];
          const components = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4 }[accessor.type];
          if (!dataType || components !== attribute.num_components()) {
            throw new Error(`${what} ${semantic}: the accessor's type does not match the compressed attribute`);
          }
          const bytes = points * components * size;
          const pointer = M._malloc(bytes);
          const ok = decoder.GetAttributeDataArrayForAllPoints(geometry, attribute, dataType, bytes, pointer);
          const values = new Uint8Array(M.HEAPU8.buffer, pointer, bytes).slice();
          M._free(pointer);
          if (!ok) throw new Error(`${what} ${semantic} cannot be converted to its accessor's component type`);
          Object.assign(accessor, { bufferView: addView(values), byteOffset: 0, count: points });
          delete accessor.sparse;
          decodedAccessors.add(index);
        }
      } finally {
        M.destroy(geometry);
        M.destroy(stream);
        M.destroy(decoder);
      }
      delete primitive.extensions[KHR_DRACO];
    }
  }

  for (const list of ['extensionsUsed', 'extensionsRequired']) {
    if (!json[list]) continue;
    json[list] = json[list].filter((name) => name !== KHR_DRACO && name !== EXT_MESHOPT);
    if (json[list].length === 0) delete json[list];
  }
  const decoded = new Uint8Array(length);
  let at = 0;
  for (const chunk of chunks) {
    decoded.set(chunk, at);
    at += chunk.length;
  }
  json.buffers = [...buffers, { uri: DECODED_URI, byteLength: decoded.length }];
  const out = glb ? glbOf(json, bin) : new TextEncoder().encode(JSON.stringify(json));
  return { bytes: out, sideFiles: { ...sideFiles, [DECODED_URI]: decoded } };
}
