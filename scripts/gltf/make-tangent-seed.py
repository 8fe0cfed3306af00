#!/usr/bin/env python3
"""Writes the fuzz_gltf seed tests/fuzz/corpus/gltf/tangent.gltf: a normal-mapped quad (a 2 x 2
PNG normal map in a data URI) drawn by two primitives, one with TANGENT as VEC4 FLOAT (w +1 and
-1, one corner's tangent of zero length), one with TANGENT as normalized BYTE
(KHR_mesh_quantization), both with NORMAL and TEXCOORD_0; a mirroring node draws the mesh again.
Small (one line, under 2 KB) so that libFuzzer's mutations reach every part of it.
  scripts/gltf/make-tangent-seed.py [OUT]"""
import base64
import json
import struct
import sys
import zlib


def png(width, height, rgb):
    raw = b"".join(b"\x00" + bytes(rgb) * width for _ in range(height))

    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


views, accessors, data = [], [], bytearray()


def add(values, fmt, component_type, type_, count, normalized=False):
    while len(data) % 4:
        data.append(0)
    offset = len(data)
    data.extend(struct.pack("<" + fmt * len(values), *values))
    views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(data) - offset})
    accessor = {"bufferView": len(views) - 1, "componentType": component_type, "count": count, "type": type_}
    if normalized:
        accessor["normalized"] = True
    accessors.append(accessor)
    return len(accessors) - 1


position = add([-1, 1, 0, -1, -1, 0, 1, -1, 0, 1, 1, 0], "f", 5126, "VEC3", 4)
normal = add([0, 0, 1] * 4, "f", 5126, "VEC3", 4)
texcoord = add([0, 0, 0, 1, 1, 1, 1, 0], "f", 5126, "VEC2", 4)
tangent = add([0, 1, 0, 1, 0, 1, 0, -1, 0, 0, 0, 1, 1, 0, 0, 1], "f", 5126, "VEC4", 4)
quantized = add([0, 127, 0, -127] * 4, "b", 5120, "VEC4", 4, normalized=True)
indices = add([0, 1, 2, 0, 2, 3], "H", 5123, "SCALAR", 6)


def primitive(t):
    return {"attributes": {"POSITION": position, "NORMAL": normal, "TEXCOORD_0": texcoord, "TANGENT": t},
            "indices": indices, "material": 0}


gltf = {
    "asset": {"version": "2.0"},
    "extensionsUsed": ["KHR_mesh_quantization"],
    "buffers": [{"byteLength": len(data),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(data)).decode()}],
    "bufferViews": views,
    "accessors": accessors,
    "images": [{"uri": "data:image/png;base64," + base64.b64encode(png(2, 2, (200, 90, 230))).decode()}],
    "textures": [{"source": 0}],
    "materials": [{"normalTexture": {"index": 0, "scale": 0.8}}],
    "meshes": [{"primitives": [primitive(tangent), primitive(quantized)]}],
    "nodes": [{"mesh": 0}, {"mesh": 0, "scale": [-1, 1, 1], "translation": [3, 0, 0]}],
    "scenes": [{"nodes": [0, 1]}],
}
out = sys.argv[1] if len(sys.argv) > 1 else "tests/fuzz/corpus/gltf/tangent.gltf"
with open(out, "w") as f:
    f.write(json.dumps(gltf, separators=(", ", ": ")))
