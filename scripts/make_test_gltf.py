#!/usr/bin/env python3
"""Writes tests/data/svo/textured_box.gltf, the glTF that tests/test_svo_gltf.cpp and the
raykit-voxelize ctest tests load. Python 3 standard library only; deterministic (running it again
gives the same bytes). Usage: python3 scripts/make_test_gltf.py [output.gltf]

Contents (the tests re-derive every expected value from this description, not from the loader):
- texture 0: an 8x8 RGB PNG, a 2x2 checker of 4x4-texel squares: texel (column i, row j) = COLOR_A
  when i // 4 + j // 4 is even, else COLOR_B (sRGB bytes). Each box face maps the texture once, so
  a face shows 2x2 squares and a voxel of 1/8 face covers one texel. Sampler: wrapS CLAMP_TO_EDGE,
  wrapT MIRRORED_REPEAT, NEAREST filters.
- material 0 "checker": baseColorTexture 0, baseColorFactor 1, metallic 0.
- material 1 "tinted_glass": baseColorFactor (0.1, 0.4, 0.8, 0.5), metallic 0.5, roughness 0.2,
  KHR_materials_ior 1.33, KHR_materials_volume attenuationColor (0.5, 0.25, 1), distance 2.
- mesh 0 "box_and_lid":
  primitive 0: the unit cube [-0.5, 0.5]^3, 24 vertices (4 per face; positions and normals
    interleaved, byteStride 24), float TEXCOORD_0, 36 u16 indices, material 0. Face with outward
    normal n, in-plane axes a, b (a x b = n): vertex = 0.5 n + (s - 0.5) a + (t - 0.5) b for
    (s, t) in (0,0), (1,0), (1,1), (0,1); uv = (s, 1 - t); triangles (0,1,2), (0,2,3) of the face.
  primitive 1: the square y = 1.25, |x|, |z| <= 0.5 as a TRIANGLE_STRIP of u8 indices 0..3, normals
    +y, TEXCOORD_0 normalized u16, material 1.
- mesh 1 "fan_and_friends":
  primitive 0: TRIANGLE_FAN of 5 vertices in the plane z = 0.5 x with normal (-0.5, 0, 1)/|.|,
    u32 indices, TEXCOORD_0 normalized u8, no material.
  primitive 1: POINTS (the fan's vertices); primitive 2: LINES (the fan's indices): skipped.
  primitive 3: one non-indexed triangle in the plane z = 0 without normals or texcoords, material 1.
- node 0 "box": translation (1, 0.5, -2), mesh 0, child node 1.
- node 1 "fan": translation (0, 0, 2), rotation 90 degrees about +y, scale (2, 1, 0.5), mesh 1.
- node 2 "not_in_default_scene": mesh 0 at x = 100; only in scene 1. Default scene: 0 = [node 0].
"""
import base64
import json
import math
import os
import struct
import sys
import zlib

COLOR_A = (200, 40, 30)
COLOR_B = (240, 220, 110)

# Face table: outward normal n, in-plane axes a, b with a x b = n.
FACES = [
    ((1, 0, 0), (0, 0, -1), (0, 1, 0)),
    ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
    ((0, 1, 0), (1, 0, 0), (0, 0, -1)),
    ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
    ((0, 0, 1), (1, 0, 0), (0, 1, 0)),
    ((0, 0, -1), (-1, 0, 0), (0, 1, 0)),
]


def png_rgb(width, height, pixel):
    """A PNG (8-bit RGB, no interlace, filter 0 on every row) of pixel(i, j) -> (r, g, b)."""
    raw = b"".join(b"\x00" + b"".join(bytes(pixel(i, j)) for i in range(width)) for j in range(height))

    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


class Builder:
    def __init__(self):
        self.data = bytearray()
        self.views = []
        self.accessors = []

    def view(self, payload, stride=None, target=None):
        while len(self.data) % 4:
            self.data.append(0)
        v = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload)}
        if stride:
            v["byteStride"] = stride
        if target:
            v["target"] = target
        self.data += payload
        self.views.append(v)
        return len(self.views) - 1

    def accessor(self, view, ctype, count, atype, offset=0, normalized=False, vmin=None, vmax=None):
        a = {"bufferView": view, "componentType": ctype, "count": count, "type": atype}
        if offset:
            a["byteOffset"] = offset
        if normalized:
            a["normalized"] = True
        if vmin is not None:
            a["min"], a["max"] = vmin, vmax
        self.accessors.append(a)
        return len(self.accessors) - 1


def bounds(points):
    return [min(p[k] for p in points) for k in range(3)], [max(p[k] for p in points) for k in range(3)]


def f32(values):
    return struct.pack("<%df" % len(values), *values)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "tests", "data", "svo", "textured_box.gltf")
    FLOAT, U8, U16, U32 = 5126, 5121, 5123, 5125
    ARRAY, ELEMENT = 34962, 34963
    b = Builder()

    # mesh 0 primitive 0: the box.
    pos, nrm, uv, idx = [], [], [], []
    for n, a, bb in FACES:
        base = len(pos)
        for s, t in ((0, 0), (1, 0), (1, 1), (0, 1)):
            pos.append(tuple(0.5 * n[k] + (s - 0.5) * a[k] + (t - 0.5) * bb[k] for k in range(3)))
            nrm.append(n)
            uv.append((float(s), 1.0 - t))
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    inter = b"".join(f32(list(p) + list(q)) for p, q in zip(pos, nrm))
    v_box = b.view(inter, stride=24, target=ARRAY)
    lo, hi = bounds(pos)
    a_box_pos = b.accessor(v_box, FLOAT, 24, "VEC3", 0, vmin=lo, vmax=hi)
    a_box_nrm = b.accessor(v_box, FLOAT, 24, "VEC3", 12)
    a_box_uv = b.accessor(b.view(b"".join(f32(t) for t in uv), target=ARRAY), FLOAT, 24, "VEC2")
    a_box_idx = b.accessor(b.view(struct.pack("<36H", *idx), target=ELEMENT), U16, 36, "SCALAR")

    # mesh 0 primitive 1: the lid square, a strip.
    lid = [(-0.5, 1.25, 0.5), (0.5, 1.25, 0.5), (-0.5, 1.25, -0.5), (0.5, 1.25, -0.5)]
    lo, hi = bounds(lid)
    a_lid_pos = b.accessor(b.view(b"".join(f32(p) for p in lid), target=ARRAY), FLOAT, 4, "VEC3", vmin=lo, vmax=hi)
    a_lid_nrm = b.accessor(b.view(f32([0, 1, 0] * 4), target=ARRAY), FLOAT, 4, "VEC3")
    a_lid_uv = b.accessor(b.view(struct.pack("<8H", 0, 0, 65535, 0, 0, 65535, 65535, 32768), target=ARRAY),
                          U16, 4, "VEC2", normalized=True)
    a_lid_idx = b.accessor(b.view(bytes([0, 1, 2, 3]), target=ELEMENT), U8, 4, "SCALAR")

    # mesh 1 primitive 0: the fan (plane z = 0.5 x).
    fan = [(0.0, 0.0, 0.0), (0.4, -0.4, 0.2), (0.4, 0.4, 0.2), (-0.4, 0.4, -0.2), (-0.4, -0.4, -0.2)]
    ln = math.sqrt(0.5 * 0.5 + 1.0)
    fan_n = (-0.5 / ln, 0.0, 1.0 / ln)
    lo, hi = bounds(fan)
    a_fan_pos = b.accessor(b.view(b"".join(f32(p) for p in fan), target=ARRAY), FLOAT, 5, "VEC3", vmin=lo, vmax=hi)
    a_fan_nrm = b.accessor(b.view(f32(list(fan_n) * 5), target=ARRAY), FLOAT, 5, "VEC3")
    a_fan_uv = b.accessor(b.view(bytes([0, 0, 255, 0, 255, 255, 0, 255, 51, 102]), target=ARRAY), U8, 5, "VEC2",
                          normalized=True)
    a_fan_idx = b.accessor(b.view(struct.pack("<5I", 0, 1, 2, 3, 4), target=ELEMENT), U32, 5, "SCALAR")

    # mesh 1 primitive 3: one triangle, no indices, no normals.
    tri = [(-0.3, 0.6, 0.0), (0.3, 0.6, 0.0), (0.0, 0.9, 0.0)]
    lo, hi = bounds(tri)
    a_tri_pos = b.accessor(b.view(b"".join(f32(p) for p in tri), target=ARRAY), FLOAT, 3, "VEC3", vmin=lo, vmax=hi)

    png = png_rgb(8, 8, lambda i, j: COLOR_A if (i // 4 + j // 4) % 2 == 0 else COLOR_B)
    s45 = math.sqrt(0.5)
    gltf = {
        "asset": {"version": "2.0", "generator": "raykit scripts/make_test_gltf.py"},
        "extensionsUsed": ["KHR_materials_ior", "KHR_materials_volume"],
        "scene": 0,
        "scenes": [{"name": "default", "nodes": [0]}, {"name": "other", "nodes": [2]}],
        "nodes": [
            {"name": "box", "translation": [1.0, 0.5, -2.0], "mesh": 0, "children": [1]},
            {"name": "fan", "translation": [0.0, 0.0, 2.0], "rotation": [0.0, s45, 0.0, s45],
             "scale": [2.0, 1.0, 0.5], "mesh": 1},
            {"name": "not_in_default_scene", "translation": [100.0, 0.0, 0.0], "mesh": 0},
        ],
        "meshes": [
            {"name": "box_and_lid", "primitives": [
                {"attributes": {"POSITION": a_box_pos, "NORMAL": a_box_nrm, "TEXCOORD_0": a_box_uv},
                 "indices": a_box_idx, "material": 0},
                {"attributes": {"POSITION": a_lid_pos, "NORMAL": a_lid_nrm, "TEXCOORD_0": a_lid_uv},
                 "indices": a_lid_idx, "material": 1, "mode": 5},
            ]},
            {"name": "fan_and_friends", "primitives": [
                {"attributes": {"POSITION": a_fan_pos, "NORMAL": a_fan_nrm, "TEXCOORD_0": a_fan_uv},
                 "indices": a_fan_idx, "mode": 6},
                {"attributes": {"POSITION": a_fan_pos}, "mode": 0},
                {"attributes": {"POSITION": a_fan_pos}, "indices": a_fan_idx, "mode": 1},
                {"attributes": {"POSITION": a_tri_pos}, "material": 1},
            ]},
        ],
        "materials": [
            {"name": "checker", "pbrMetallicRoughness": {
                "baseColorTexture": {"index": 0}, "baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0}},
            {"name": "tinted_glass", "pbrMetallicRoughness": {
                "baseColorFactor": [0.1, 0.4, 0.8, 0.5], "metallicFactor": 0.5, "roughnessFactor": 0.2},
             "extensions": {
                 "KHR_materials_ior": {"ior": 1.33},
                 "KHR_materials_volume": {"attenuationColor": [0.5, 0.25, 1.0], "attenuationDistance": 2.0}}},
        ],
        "textures": [{"sampler": 0, "source": 0}],
        "samplers": [{"magFilter": 9728, "minFilter": 9728, "wrapS": 33071, "wrapT": 33648}],
        "images": [{"name": "checker8", "uri": "data:image/png;base64," + base64.b64encode(png).decode("ascii")}],
        "buffers": [{"byteLength": len(b.data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(b.data)).decode("ascii")}],
        "bufferViews": b.views,
        "accessors": b.accessors,
    }
    text = json.dumps(gltf, indent=1) + "\n"
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    with open(out, "w", encoding="ascii", newline="\n") as f:
        f.write(text)
    print("wrote %s (%d bytes, buffer %d bytes, PNG %d bytes)" % (out, len(text), len(b.data), len(png)))


if __name__ == "__main__":
    main()
