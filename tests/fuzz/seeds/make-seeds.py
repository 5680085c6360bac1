#!/usr/bin/env python3
"""Writes the fuzzer's seeds for what moves (issue 13): small valid files with skins, morph targets and animations,
each feature in the forms the loader reads (so that mutations start from every code path). Run from this folder;
the outputs are committed, this script is how they were made.

  skin-animated.gltf     two-joint skin (u8 joints, normalised u16 weights), CUBICSPLINE rotation, STEP translation,
                         LINEAR scale, inverse bind matrices; data URI buffer (the JSON is what mutates)
  morph-sparse.glb       two morph targets (one sparse, one with NORMAL), mesh and node weights, a LINEAR weights
                         animation of normalised u8 outputs; binary chunk (the bytes are what mutates)
  hierarchy-animated.glb a node under two parents, a matrix node, rotations of normalised shorts, a channel on a
                         node outside the scene, an unknown path and a target without a node (skipped with warnings)
"""
import base64
import json
import struct


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


if __name__ == "__main__":
    for name, make in (("skin-animated.gltf", skin_animated), ("morph-sparse.glb", morph_sparse),
                       ("hierarchy-animated.glb", hierarchy_animated)):
        with open(name, "wb") as f:
            f.write(make())
