#!/usr/bin/env python3
"""Writes the fuzzer's seeds: small files with every input form the loader reads, each feature in the forms it takes
(so that mutations start from every code path; README.md lists the forms and where each is). Run from this folder;
the outputs are committed, this script is how they were made. make-compressed-seeds.mjs writes the Draco and meshopt
ones.

  skin-animated.gltf     two-joint skin (u8 joints, normalised u16 weights), CUBICSPLINE rotation, STEP translation,
                         LINEAR scale, inverse bind matrices; data URI buffer (the JSON is what mutates)
  morph-sparse.glb       two morph targets (one sparse, one with NORMAL), mesh and node weights, a LINEAR weights
                         animation of normalised u8 outputs; binary chunk (the bytes are what mutates)
  hierarchy-animated.glb a node under two parents, a matrix node, rotations of normalised shorts, a channel on a
                         node outside the scene, an unknown path and a target without a node (skipped with warnings)
  skin-40-joints.glb     a 40-joint chain (beyond the 16-joint uniform palette of a GLES 2 minimum context), u16
                         joints, four float weights per vertex, a LINEAR rotation on every joint
  materials-textured.glb every texture slot (base colour with KHR_texture_transform, metallic-roughness, normal with
                         TANGENT, occlusion on TEXCOORD_1, emissive with KHR_materials_emissive_strength), PNG images
                         in buffer views and a data uri, samplers, COLOR_0, alphaMode MASK and BLEND, double-sided,
                         KHR_materials_unlit, clearcoat, specular, ior, transmission and volume, quantized positions
                         (KHR_mesh_quantization), a non-indexed primitive, a triangle strip
  lights-cameras.gltf    KHR_lights_punctual point, spot and directional lights, perspective and orthographic
                         cameras, on nodes of a hierarchy
  external-buffer.glb    its buffer is the file "buffer.bin", which the fuzzer offers as the second half of the input
                         (this file's second half is that buffer)
  refused-keys-not-increasing.gltf   animation key times that go back: refused
  refused-joint-outside-skin.glb     a weighted joint index beyond the skin's joints: refused
"""
import base64
import json
import struct
import zlib


class Builder:
    def __init__(self):
        self.bin = bytearray()
        self.doc = {"asset": {"version": "2.0"}, "bufferViews": [], "accessors": [], "meshes": [], "nodes": []}

    def view(self, data):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)})
        self.bin += data
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, fmt, values, component_type, type_, count, normalized=False, view=True):
        accessor = {"componentType": component_type, "count": count, "type": type_}
        if view:
            accessor["bufferView"] = self.view(struct.pack("<%d%s" % (len(values), fmt), *values))
        if normalized:
            accessor["normalized"] = True
        self.doc["accessors"].append(accessor)
        return len(self.doc["accessors"]) - 1

    def floats(self, values, type_, width):
        return self.accessor("f", values, 5126, type_, len(values) // width)

    def gltf(self):
        doc = dict(self.doc)
        doc["buffers"] = [{"byteLength": len(self.bin),
                           "uri": "data:application/octet-stream;base64," + base64.b64encode(self.bin).decode()}]
        return json.dumps(doc, indent=1).encode()

    def glb(self):
        doc = dict(self.doc)
        while len(self.bin) % 4:
            self.bin.append(0)
        doc["buffers"] = [{"byteLength": len(self.bin)}]
        text = json.dumps(doc, separators=(",", ":")).encode()
        while len(text) % 4:
            text += b" "
        body = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(self.bin), 0x004E4942)
        body += bytes(self.bin)
        return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


QUAD = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 2, 0, 1, 2, 0]
QUAD_INDICES = [0, 1, 2, 0, 2, 3, 3, 2, 5, 3, 5, 4]


def quad(b, normals=True):
    attributes = {"POSITION": b.floats(QUAD, "VEC3", 3)}
    if normals:
        attributes["NORMAL"] = b.floats([0, 0, 1] * 6, "VEC3", 3)
    return attributes, b.accessor("H", QUAD_INDICES, 5123, "SCALAR", len(QUAD_INDICES))


def skin_animated():
    b = Builder()
    attributes, indices = quad(b, normals=False)
    attributes["JOINTS_0"] = b.accessor("B", [0, 1, 0, 0] * 6, 5121, "VEC4", 6)
    attributes["WEIGHTS_0"] = b.accessor("H", [65535, 0, 0, 0] * 2 + [32768, 32767, 0, 0] * 2 + [0, 65535, 0, 0] * 2,
                                         5123, "VEC4", 6, normalized=True)
    b.doc["meshes"].append({"primitives": [{"attributes": attributes, "indices": indices}]})
    b.doc["nodes"] = [{"mesh": 0, "skin": 0, "name": "body"},
                      {"name": "hip", "children": [2]},
                      {"name": "knee", "translation": [0, 1, 0]}]
    inverse_bind = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] + [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1]
    b.doc["skins"] = [{"joints": [1, 2], "skeleton": 1, "inverseBindMatrices": b.floats(inverse_bind, "MAT4", 16)}]
    times = b.floats([0, 1, 2], "SCALAR", 1)
    s = 0.70710677
    rotation = [0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0.5, 0] + [0, 0, 0, 0, 0, 0, s, s, 0, 0, 0, 0] + \
               [0, 0, -0.5, 0, 0, 0, 0, 1, 0, 0, 0, 0]
    b.doc["animations"] = [{"name": "bend", "samplers": [
        {"input": times, "output": b.floats(rotation, "VEC4", 4), "interpolation": "CUBICSPLINE"},
        {"input": times, "output": b.floats([0, 0, 0, 0, 0.5, 0, 0, 0, 0], "VEC3", 3), "interpolation": "STEP"},
        {"input": times, "output": b.floats([1, 1, 1, 1.5, 1, 1, 1, 1, 1], "VEC3", 3)}],
        "channels": [{"sampler": 0, "target": {"node": 2, "path": "rotation"}},
                     {"sampler": 1, "target": {"node": 1, "path": "translation"}},
                     {"sampler": 2, "target": {"node": 2, "path": "scale"}}]}]
    b.doc["scenes"] = [{"nodes": [0, 1]}]
    b.doc["scene"] = 0
    return b.gltf()


def morph_sparse():
    b = Builder()
    attributes, indices = quad(b)
    lift = [0.0] * 18
    lift[14] = 1.0  # vertex 4 up in z
    sparse = b.accessor("f", [], 5126, "VEC3", 6, view=False)
    b.doc["accessors"][sparse]["sparse"] = {
        "count": 2,
        "indices": {"bufferView": b.view(struct.pack("<2B", 1, 5)), "componentType": 5121},
        "values": {"bufferView": b.view(struct.pack("<6f", 0.5, 0, 0, 0.5, 0, 0))}}
    targets = [{"POSITION": b.floats(lift, "VEC3", 3), "NORMAL": b.floats([0, -0.5, 0] * 6, "VEC3", 3)},
               {"POSITION": sparse}]
    b.doc["meshes"].append({"primitives": [{"attributes": attributes, "indices": indices, "targets": targets}],
                            "weights": [0.25, 0]})
    b.doc["nodes"] = [{"mesh": 0, "name": "mesh weights"},
                      {"mesh": 0, "name": "own weights", "weights": [0, 1], "translation": [2, 0, 0]}]
    b.doc["animations"] = [{"name": "breathe", "samplers": [
        {"input": b.floats([0, 0.5, 1], "SCALAR", 1),
         "output": b.accessor("B", [0, 0, 255, 128, 0, 255], 5121, "SCALAR", 6, normalized=True)}],
        "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}}]}]
    b.doc["scenes"] = [{"nodes": [0, 1]}]
    return b.glb()


def hierarchy_animated():
    b = Builder()
    attributes, indices = quad(b)
    b.doc["meshes"].append({"primitives": [{"attributes": attributes, "indices": indices}]})
    b.doc["nodes"] = [{"mesh": 0, "name": "shared", "rotation": [0, 0, 0, 1]},
                      {"name": "left", "translation": [-2, 0, 0], "children": [0, 3]},
                      {"name": "right", "translation": [2, 0, 0], "children": [0]},
                      {"name": "fixed", "mesh": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 3, 0, 1]},
                      {"name": "outside", "mesh": 0}]
    half = 23170  # sin and cos of 45 degrees as normalised shorts
    b.doc["animations"] = [
        {"name": "spin", "samplers": [
            {"input": b.floats([0, 1, 2], "SCALAR", 1),
             "output": b.accessor("h", [0, 0, 0, 32767, 0, 0, 32767, 0, 0, 0, -half, half], 5122, "VEC4", 3,
                                  normalized=True)},
            {"input": b.floats([0, 2], "SCALAR", 1), "output": b.floats([0, 0, 0, 0, 1, 0], "VEC3", 3)}],
         "channels": [{"sampler": 0, "target": {"node": 0, "path": "rotation"}},
                      {"sampler": 1, "target": {"node": 1, "path": "translation"}},
                      {"sampler": 1, "target": {"node": 2, "path": "translation"}},
                      {"sampler": 1, "target": {"node": 4, "path": "translation"}},
                      {"sampler": 1, "target": {"node": 2, "path": "pointer"}},
                      {"sampler": 1, "target": {"path": "pointer", "extensions": {
                          "KHR_animation_pointer": {"pointer": "/nodes/1/translation"}}}}]},
        {"name": "bob", "samplers": [
            {"input": b.floats([0.5], "SCALAR", 1), "output": b.floats([1, 1, 1], "VEC3", 3),
             "interpolation": "STEP"}],
         "channels": [{"sampler": 0, "target": {"node": 2, "path": "scale"}}]}]
    b.doc["extensionsUsed"] = ["KHR_animation_pointer"]
    b.doc["scenes"] = [{"nodes": [1, 2]}]
    b.doc["scene"] = 0
    return b.glb()


def skin_40_joints():
    b = Builder()
    joints = 40
    # A strip of 2 * (joints + 1) vertices up the y axis; the vertices of row r follow joints r - 1 .. r + 2.
    positions, normals, joint_ids, weights, indices = [], [], [], [], []
    for row in range(joints + 1):
        for x in (0.0, 0.2):
            positions += [x, row * 0.1, 0.0]
            normals += [0.0, 0.0, 1.0]
            joint_ids += [min(max(row + k - 1, 0), joints - 1) for k in range(4)]
            weights += [0.1, 0.4, 0.4, 0.1]
        if row:
            a = 2 * (row - 1)
            indices += [a, a + 1, a + 3, a, a + 3, a + 2]
    attributes = {"POSITION": b.floats(positions, "VEC3", 3), "NORMAL": b.floats(normals, "VEC3", 3),
                  "JOINTS_0": b.accessor("H", joint_ids, 5123, "VEC4", len(joint_ids) // 4),
                  "WEIGHTS_0": b.floats(weights, "VEC4", 4)}
    b.doc["meshes"].append({"primitives": [{"attributes": attributes,
                                            "indices": b.accessor("H", indices, 5123, "SCALAR", len(indices))}]})
    b.doc["nodes"] = [{"mesh": 0, "skin": 0, "name": "tail"}]
    for j in range(joints):
        node = {"name": "joint %d" % j, "translation": [0, 0.1 if j else 0, 0]}
        if j + 1 < joints:
            node["children"] = [j + 2]
        b.doc["nodes"].append(node)
    inverse_bind = []
    for j in range(joints):
        inverse_bind += [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -0.1 * j, 0, 1]
    b.doc["skins"] = [{"joints": list(range(1, joints + 1)), "inverseBindMatrices":
                       b.floats(inverse_bind, "MAT4", 16)}]
    times = b.floats([0, 1], "SCALAR", 1)
    bend = b.floats([0, 0, 0, 1, 0, 0, 0.0499792, 0.9987503], "VEC4", 4)
    b.doc["animations"] = [{"name": "curl", "samplers": [{"input": times, "output": bend}],
                            "channels": [{"sampler": 0, "target": {"node": j + 1, "path": "rotation"}}
                                         for j in range(joints)]}]
    b.doc["scenes"] = [{"nodes": [0, 1]}]
    return b.glb()


def png(width, height, rgba):
    """A PNG of 8-bit RGBA rows (no filter), as the loader's stb_image reads it."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    rows = b"".join(b"\0" + bytes(rgba[y * width * 4:(y + 1) * width * 4]) for y in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def materials_textured():
    b = Builder()
    attributes, indices = quad(b)
    uv = [0, 0, 1, 0, 1, 1, 0, 1, 0, 2, 1, 2]
    attributes["TEXCOORD_0"] = b.floats(uv, "VEC2", 2)
    attributes["TEXCOORD_1"] = b.accessor("B", [0, 0, 255, 0, 255, 255, 0, 255, 0, 128, 255, 128], 5121, "VEC2", 6,
                                          normalized=True)
    attributes["TANGENT"] = b.floats([1, 0, 0, 1] * 6, "VEC4", 4)
    attributes["COLOR_0"] = b.accessor("H", [65535, 32768, 0, 65535] * 6, 5123, "VEC4", 6, normalized=True)
    checker = png(2, 2, [255, 255, 255, 255, 0, 0, 0, 128, 0, 0, 0, 128, 255, 255, 255, 255])
    flat = png(1, 1, [128, 128, 255, 255])
    b.doc["images"] = [{"bufferView": b.view(checker), "mimeType": "image/png"},
                       {"bufferView": b.view(flat), "mimeType": "image/png"},
                       {"uri": "data:image/png;base64," + base64.b64encode(checker).decode()}]
    b.doc["samplers"] = [{"magFilter": 9728, "minFilter": 9986, "wrapS": 33071, "wrapT": 33648}, {}]
    b.doc["textures"] = [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 1}, {"source": 2}]
    transform = {"KHR_texture_transform": {"offset": [0.5, 0], "rotation": 0.3, "scale": [2, 2]}}
    b.doc["materials"] = [
        {"name": "every slot", "doubleSided": True,
         "pbrMetallicRoughness": {"baseColorFactor": [1, 0.8, 0.6, 1], "metallicFactor": 0.5, "roughnessFactor": 0.7,
                                  "baseColorTexture": {"index": 0, "extensions": transform},
                                  "metallicRoughnessTexture": {"index": 2}},
         "normalTexture": {"index": 1, "scale": 0.8},
         "occlusionTexture": {"index": 2, "texCoord": 1, "strength": 0.5},
         "emissiveTexture": {"index": 0}, "emissiveFactor": [1, 0.5, 0],
         "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}},
        {"name": "cut out", "alphaMode": "MASK", "alphaCutoff": 0.4,
         "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 0}}},
        {"name": "glass", "alphaMode": "BLEND", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 1, 0.3]},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.9},
                        "KHR_materials_volume": {"thicknessFactor": 0.1, "attenuationColor": [0.9, 1, 1]},
                        "KHR_materials_ior": {"ior": 1.5}}},
        {"name": "lacquer", "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1,
                                                                       "clearcoatRoughnessFactor": 0.1},
                                           "KHR_materials_specular": {"specularFactor": 0.5,
                                                                      "specularColorFactor": [1, 0.9, 0.8]}}},
        {"name": "unlit", "pbrMetallicRoughness": {"baseColorTexture": {"index": 2}},
         "extensions": {"KHR_materials_unlit": {}}}]
    quantized = b.accessor("h", [0, 0, 0, 32767, 0, 0, 32767, 32767, 0, 0, 32767, 0], 5122, "VEC3", 4,
                           normalized=True)
    strip = b.floats([0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0], "VEC3", 3)
    b.doc["meshes"] = [
        {"primitives": [{"attributes": attributes, "indices": indices, "material": m} for m in range(5)]},
        {"primitives": [{"attributes": {"POSITION": quantized},
                         "indices": b.accessor("B", [0, 1, 2, 0, 2, 3], 5121, "SCALAR", 6), "material": 1},
                        {"attributes": {"POSITION": strip}, "mode": 5, "material": 2},
                        {"attributes": {"POSITION": strip}, "material": 4}]}]
    b.doc["nodes"] = [{"mesh": 0}, {"mesh": 1, "translation": [2, 0, 0], "scale": [-1, 1, 1]}]
    b.doc["extensionsUsed"] = ["KHR_texture_transform", "KHR_materials_emissive_strength", "KHR_materials_transmission",
                               "KHR_materials_volume", "KHR_materials_ior", "KHR_materials_clearcoat",
                               "KHR_materials_specular", "KHR_materials_unlit", "KHR_mesh_quantization"]
    b.doc["extensionsRequired"] = ["KHR_mesh_quantization", "KHR_texture_transform"]
    b.doc["scenes"] = [{"nodes": [0, 1]}]
    return b.glb()


def lights_cameras():
    b = Builder()
    attributes, indices = quad(b)
    b.doc["meshes"].append({"primitives": [{"attributes": attributes, "indices": indices}]})
    b.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"type": "point", "color": [1, 0.9, 0.8], "intensity": 20, "range": 10},
        {"type": "spot", "intensity": 50, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.6}},
        {"type": "directional", "color": [1, 1, 0.9], "intensity": 3}]}}
    b.doc["cameras"] = [
        {"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05, "zfar": 100, "aspectRatio": 1.5}},
        {"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.1}},
        {"type": "orthographic", "orthographic": {"xmag": 2, "ymag": 1.5, "znear": 0.01, "zfar": 50}}]
    b.doc["nodes"] = [{"mesh": 0, "children": [1, 2, 3, 4, 5, 6]},
                      {"translation": [0, 2, 2], "extensions": {"KHR_lights_punctual": {"light": 0}}},
                      {"translation": [1, 3, 1], "rotation": [-0.3826834, 0, 0, 0.9238795],
                       "extensions": {"KHR_lights_punctual": {"light": 1}}},
                      {"rotation": [-0.5, 0.5, 0.5, 0.5], "extensions": {"KHR_lights_punctual": {"light": 2}}},
                      {"camera": 0, "translation": [0, 1, 5]},
                      {"camera": 1, "translation": [3, 1, 3], "rotation": [0, 0.3826834, 0, 0.9238795]},
                      {"camera": 2, "translation": [0, 1, 4], "scale": [2, 2, 2]}]
    b.doc["extensionsUsed"] = ["KHR_lights_punctual"]
    b.doc["scenes"] = [{"nodes": [0]}]
    b.doc["scene"] = 0
    return b.gltf()


def external_buffer():
    """A .glb whose buffer 0 names the file "buffer.bin"; the fuzzer offers the input's second half under that name,
    so the file is laid out with exactly its buffer as its second half (the JSON chunk padded to the buffer's length
    less the 28 bytes of headers)."""
    b = Builder()
    attributes, indices = quad(b)
    b.doc["meshes"].append({"primitives": [{"attributes": attributes, "indices": indices}]})
    b.doc["nodes"] = [{"mesh": 0}]
    while len(b.bin) % 4:
        b.bin.append(0)
    doc = dict(b.doc)
    data = bytes(b.bin)
    while True:  # the buffer padded until the JSON naming its length fits in front of it
        doc["buffers"] = [{"uri": "buffer.bin", "byteLength": len(data)}]
        text = json.dumps(doc, separators=(",", ":")).encode()
        if len(text) + 28 <= len(data):
            break
        data += bytes(4)
    text += b" " * (len(data) - 28 - len(text))
    body = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(data), 0x004E4942) + data
    out = struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body
    assert out[len(out) // 2:] == data
    return out


def keys_not_increasing():
    b = Builder()
    attributes, indices = quad(b)
    b.doc["meshes"].append({"primitives": [{"attributes": attributes, "indices": indices}]})
    b.doc["nodes"] = [{"mesh": 0}]
    b.doc["animations"] = [{"samplers": [{"input": b.floats([0, 1, 0.5], "SCALAR", 1),
                                          "output": b.floats([0, 0, 0, 1, 0, 0, 2, 0, 0], "VEC3", 3)}],
                            "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}]}]
    return b.gltf()


def joint_outside_skin():
    b = Builder()
    attributes, indices = quad(b)
    attributes["JOINTS_0"] = b.accessor("B", [0, 0, 0, 0] * 5 + [2, 0, 0, 0], 5121, "VEC4", 6)
    attributes["WEIGHTS_0"] = b.floats([1, 0, 0, 0] * 6, "VEC4", 4)
    b.doc["meshes"].append({"primitives": [{"attributes": attributes, "indices": indices}]})
    b.doc["nodes"] = [{"mesh": 0, "skin": 0}, {"name": "only joint"}]
    b.doc["skins"] = [{"joints": [1]}]
    b.doc["scenes"] = [{"nodes": [0, 1]}]
    return b.glb()


if __name__ == "__main__":
    for name, make in (("skin-animated.gltf", skin_animated), ("morph-sparse.glb", morph_sparse),
                       ("hierarchy-animated.glb", hierarchy_animated), ("skin-40-joints.glb", skin_40_joints),
                       ("materials-textured.glb", materials_textured), ("lights-cameras.gltf", lights_cameras),
                       ("external-buffer.glb", external_buffer),
                       ("refused-keys-not-increasing.gltf", keys_not_increasing),
                       ("refused-joint-outside-skin.glb", joint_outside_skin)):
        with open(name, "wb") as f:
            f.write(make())
