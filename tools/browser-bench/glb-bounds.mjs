// The bounding sphere the benchmark gives every renderer: the sphere around the model's axis-aligned bounds in world
// space (centre of the box, radius = half its diagonal), the box taken over every vertex position of every mesh
// instance after its node's world transform. That is how Obscura frames a scene (Scene::worldBounds(),
// Bounds::radius() in src/scene) and what three.js's Box3.setFromObject(object, true) computes; the benchmark checks
// all three agree. Plain JavaScript, no dependencies, so that Node and the pages run the same code.

// Column-major 4x4 matrices, as glTF stores them.
function multiply(a, b) {
  const out = new Array(16).fill(0);
  for (let column = 0; column < 4; ++column) {
    for (let row = 0; row < 4; ++row) {
      let sum = 0;
      for (let k = 0; k < 4; ++k) sum += a[k * 4 + row] * b[column * 4 + k];
      out[column * 4 + row] = sum;
    }
  }
  return out;
}

// A node's local matrix: `matrix`, or translation * rotation * scale (glTF 2.0, 5.25).
function localMatrix(node) {
  if (node.matrix) return node.matrix.slice();
  const [tx, ty, tz] = node.translation ?? [0, 0, 0];
  const [x, y, z, w] = node.rotation ?? [0, 0, 0, 1];
  const [sx, sy, sz] = node.scale ?? [1, 1, 1];
  return [
    (1 - 2 * (y * y + z * z)) * sx, 2 * (x * y + z * w) * sx, 2 * (x * z - y * w) * sx, 0,
    2 * (x * y - z * w) * sy, (1 - 2 * (x * x + z * z)) * sy, 2 * (y * z + x * w) * sy, 0,
    2 * (x * z + y * w) * sz, 2 * (y * z - x * w) * sz, (1 - 2 * (x * x + y * y)) * sz, 0,
    tx, ty, tz, 1,
  ];
}

// Parses a binary glTF (.glb) held in an ArrayBuffer/Uint8Array and returns
// {min: [x, y, z], max, center, radius, diameter, vertices}. Throws on what it does not read (float POSITION only,
// no sparse accessors, no external buffers): enough for the benchmark's model, and loud otherwise.
export function glbBoundingSphere(bytes) {
  const data = bytes instanceof Uint8Array ? bytes : new Uint8Array(bytes);
  const view = new DataView(data.buffer, data.byteOffset, data.byteLength);
  if (view.getUint32(0, true) !== 0x46546c67) throw new Error('not a binary glTF (no "glTF" magic)');
  let offset = 12, json = null, bin = null;
  while (offset < data.byteLength) {
    const length = view.getUint32(offset, true), type = view.getUint32(offset + 4, true);
    const chunk = data.subarray(offset + 8, offset + 8 + length);
    if (type === 0x4e4f534a) json = JSON.parse(new TextDecoder().decode(chunk));
    else if (type === 0x004e4942) bin = chunk;
    offset += 8 + length;
  }
  if (!json || !bin) throw new Error('glb without a JSON or a BIN chunk');

  const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
  let vertices = 0;
  const addMesh = (meshIndex, world) => {
    for (const primitive of json.meshes[meshIndex].primitives) {
      const accessor = json.accessors[primitive.attributes.POSITION];
      if (accessor.componentType !== 5126 || accessor.type !== 'VEC3' || accessor.sparse) {
        throw new Error('only float VEC3 POSITION accessors without sparse storage are read here');
      }
      const bufferView = json.bufferViews[accessor.bufferView];
      if (bufferView.buffer !== 0) throw new Error('only the BIN chunk is read here');
      const stride = bufferView.byteStride ?? 12;
      const start = bin.byteOffset + (bufferView.byteOffset ?? 0) + (accessor.byteOffset ?? 0);
      const positions = new DataView(bin.buffer);
      for (let i = 0; i < accessor.count; ++i) {
        const p = [0, 1, 2].map((c) => positions.getFloat32(start + i * stride + c * 4, true));
        for (let c = 0; c < 3; ++c) {
          const w = world[c] * p[0] + world[4 + c] * p[1] + world[8 + c] * p[2] + world[12 + c];
          min[c] = Math.min(min[c], w);
          max[c] = Math.max(max[c], w);
        }
      }
      vertices += accessor.count;
    }
  };
  const visit = (nodeIndex, parent) => {
    const node = json.nodes[nodeIndex];
    const world = multiply(parent, localMatrix(node));
    if (node.mesh !== undefined) addMesh(node.mesh, world);
    for (const child of node.children ?? []) visit(child, world);
  };
  const identity = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
  const scene = json.scenes[json.scene ?? 0];
  for (const root of scene.nodes) visit(root, identity);
  if (vertices === 0) throw new Error('the scene has no vertices');

  const center = [0, 1, 2].map((c) => (min[c] + max[c]) / 2);
  const radius = Math.hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]) / 2;
  return { min, max, center, radius, diameter: 2 * radius, vertices };
}
