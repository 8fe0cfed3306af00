#!/usr/bin/env python3
"""Writes tests/assets/cycles/pbr_spheres.glb: a small binary glTF of our own (no outside source;
same licence as gpurt) that exercises every map of the glTF metallic-roughness material, for the
comparison with Blender's Cycles (tools/cycles-reference.py, tests/cli/CyclesReferenceTest.cpp).

Four UV spheres (radius 0.45, one mesh's accessors shared by four meshes with their own material)
in a 2 x 2 grid above a floor quad, each material with procedurally drawn 32 x 32 PNG textures
(written here with zlib, standard library only):
  top left      dielectric: baseColor texture (warm/cool checker), metallicRoughness texture
                (roughness 0.25 / 0.7 in bands, metallic 0), occlusion texture (R)
  top right     metal: gold baseColor factor, metallicRoughness texture (metallic 1, roughness
                running 0.2 -> 0.6 along u)
  bottom left   dielectric with a normal map (a grid of bumps, scale 1), roughness 0.4, blue
  bottom right  half metallic (0.5), roughness 0.55, grey, emissive texture (stripes) x factor
  floor         dielectric, a grey checker baseColor texture, roughness 0.8
The spheres carry TANGENT (dP/du, w so that cross(N, T) w points towards v = 0, the image's
top): Blender's importer ignores TANGENT and makes MikkTSpace tangents of the same frame, so
both renderers read the normal map alike.

With --dielectrics it writes tests/assets/cycles/dielectric_spheres.glb instead: the same spheres
and floor, the spheres dark untextured dielectrics (no TANGENT) of roughness 0.2 (dark red, top
left), 0.6 (green, top right), 0.4 (blue, bottom left) and 0.8 (grey, bottom right), so that their specular lobe, not their diffuse colour, makes
most of their light: there a change of a dielectric's roughness shows in the region means.

    scripts/make-pbr-spheres.py [--dielectrics] [OUT.glb]
"""
import json
import math
import struct
import sys
import zlib

TEX = 32


def png(rgb_rows):
    """An 8-bit RGB PNG of rows of (r, g, b) tuples, top row first."""
    height, width = len(rgb_rows), len(rgb_rows[0])
    raw = b"".join(b"\0" + bytes(c for px in row for c in px) for row in rgb_rows)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def texture(fn):
    """fn(u, v) -> (r, g, b) in 0..1 at texel centres, v = 0 the top row."""
    return png([[tuple(max(0, min(255, int(c * 255.0 + 0.5))) for c in fn((i + 0.5) / TEX, (j + 0.5) / TEX))
                 for i in range(TEX)] for j in range(TEX)])


def checker(a, b, n):
    return lambda u, v: a if (int(u * n) + int(v * n)) % 2 == 0 else b


def bumps(u, v):
    # Height h = 0.5 sin(2 pi 4 u) sin(2 pi 4 v) in texels of the unit square; the tangent-space
    # normal is (-dh/du, dh/dv', 1) normalised, v' = -v (green points towards the top row).
    k = 2.0 * math.pi * 4.0
    a = 0.08
    dhdu = a * k * math.cos(k * u) * math.sin(k * v)
    dhdv = a * k * math.sin(k * u) * math.cos(k * v)
    n = (-dhdu, dhdv, 1.0)
    length = math.sqrt(sum(c * c for c in n))
    return tuple(c / length * 0.5 + 0.5 for c in n)


def sphere(segments=24, rings=12):
    positions, normals, tangents, uvs, indices = [], [], [], [], []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for s in range(segments + 1):
            phi = 2.0 * math.pi * s / segments
            n = (math.sin(theta) * math.sin(phi), math.cos(theta), math.sin(theta) * math.cos(phi))
            positions.append(tuple(0.45 * c for c in n))
            normals.append(n)
            # dP/du (u = phi / 2 pi) is along (cos phi, 0, -sin phi); the top row (v = 0) is the
            # north pole, so the bitangent towards it is +theta's opposite: cross(N, T) there.
            t = (math.cos(phi), 0.0, -math.sin(phi))
            b = (n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0])
            north = (-math.cos(theta) * math.sin(phi), math.sin(theta), -math.cos(theta) * math.cos(phi))
            w = 1.0 if sum(b[i] * north[i] for i in range(3)) >= 0.0 else -1.0
            tangents.append(t + (w,))
            uvs.append((s / segments, r / rings))
    for r in range(rings):
        for s in range(segments):
            a, b = r * (segments + 1) + s, (r + 1) * (segments + 1) + s
            if r > 0:
                indices += [a, b, a + 1]
            if r < rings - 1:
                indices += [a + 1, b, b + 1]
    return positions, normals, tangents, uvs, indices


def main():
    args = sys.argv[1:]
    dielectrics = "--dielectrics" in args
    args = [a for a in args if a != "--dielectrics"]
    default = "tests/assets/cycles/dielectric_spheres.glb" if dielectrics else "tests/assets/cycles/pbr_spheres.glb"
    out = args[0] if args else default
    blob = bytearray()
    views, accessors = [], []

    def add_view(data, target=None):
        while len(blob) % 4:
            blob.append(0)
        view = {"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)}
        if target:
            view["target"] = target
        blob.extend(data)
        views.append(view)
        return len(views) - 1

    def add_accessor(values, kind, component=5126, target=34962):
        width = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}[kind]
        flat = [c for v in values for c in (v if width > 1 else (v,))]
        fmt = "<%d%s" % (len(flat), "f" if component == 5126 else "H")
        accessor = {"bufferView": add_view(struct.pack(fmt, *flat), target), "componentType": component,
                    "count": len(values), "type": kind}
        if kind == "VEC3" and component == 5126:
            accessor["min"] = [min(v[i] for v in values) for i in range(3)]
            accessor["max"] = [max(v[i] for v in values) for i in range(3)]
        accessors.append(accessor)
        return len(accessors) - 1

    positions, normals, tangents, uvs, indices = sphere()
    sphere_attributes = {"POSITION": add_accessor(positions, "VEC3"), "NORMAL": add_accessor(normals, "VEC3"),
                         "TANGENT": add_accessor(tangents, "VEC4"), "TEXCOORD_0": add_accessor(uvs, "VEC2")}
    sphere_indices = add_accessor(indices, "SCALAR", 5123, 34963)
    if dielectrics:
        del sphere_attributes["TANGENT"]  # no normal map: the accessor stays, unused
    floor_size, floor_y = 1.6, -1.0
    floor_positions = [(-floor_size, floor_y, floor_size), (floor_size, floor_y, floor_size),
                       (floor_size, floor_y, -floor_size), (-floor_size, floor_y, -floor_size)]
    floor_attributes = {"POSITION": add_accessor(floor_positions, "VEC3"),
                        "NORMAL": add_accessor([(0.0, 1.0, 0.0)] * 4, "VEC3"),
                        "TEXCOORD_0": add_accessor([(0.0, 1.0), (1.0, 1.0), (1.0, 0.0), (0.0, 0.0)], "VEC2")}
    floor_indices = add_accessor([0, 1, 2, 0, 2, 3], "SCALAR", 5123, 34963)

    images = [
        texture(checker((0.9, 0.45, 0.2), (0.25, 0.55, 0.8), 4)),                          # 0 base colour
        texture(lambda u, v: (1.0, 0.25 if int(v * 6) % 2 == 0 else 0.7, 0.0)),             # 1 bands of roughness
        texture(lambda u, v: (0.35 + 0.65 * abs(math.sin(math.pi * 3 * v)), 1.0, 1.0)),    # 2 occlusion (R)
        texture(lambda u, v: (0.0, 0.2 + 0.4 * u, 1.0)),                                    # 3 metal, roughness ramp
        texture(bumps),                                                                     # 4 normal map
        texture(lambda u, v: (1.0, 0.8, 0.4) if int(u * 8) % 2 == 0 else (0.0, 0.0, 0.0)),  # 5 emissive stripes
        texture(checker((0.75, 0.75, 0.75), (0.3, 0.3, 0.3), 4)),                          # 6 floor
    ]
    image_entries = [{"bufferView": add_view(data), "mimeType": "image/png"} for data in images]
    textures = [{"source": k, "sampler": 0} for k in range(len(images))]

    materials = [
        {"name": "dielectric_textured", "pbrMetallicRoughness": {
            "baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 1}},
         "occlusionTexture": {"index": 2}},
        {"name": "gold_rough_ramp", "pbrMetallicRoughness": {
            "baseColorFactor": [1.0, 0.78, 0.34, 1.0], "metallicRoughnessTexture": {"index": 3}}},
        {"name": "bumpy_blue", "pbrMetallicRoughness": {
            "baseColorFactor": [0.2, 0.35, 0.8, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.4},
         "normalTexture": {"index": 4, "scale": 1.0}},
        {"name": "half_metal_emissive", "pbrMetallicRoughness": {
            "baseColorFactor": [0.6, 0.6, 0.6, 1.0], "metallicFactor": 0.5, "roughnessFactor": 0.55},
         "emissiveTexture": {"index": 5}, "emissiveFactor": [2.0, 2.0, 2.0]},
        {"name": "floor", "pbrMetallicRoughness": {
            "baseColorTexture": {"index": 6}, "metallicFactor": 0.0, "roughnessFactor": 0.8}},
    ]
    if dielectrics:
        # (tint, roughness) top left, top right, bottom left (the bumpy blue's place and roughness),
        # bottom right
        spheres = [((0.06, 0.015, 0.01), 0.2), ((0.015, 0.05, 0.02), 0.6), ((0.01, 0.02, 0.06), 0.4),
                   ((0.03, 0.03, 0.03), 0.8)]
        materials[:4] = [{"name": "dark_dielectric_%d" % k, "pbrMetallicRoughness": {
            "baseColorFactor": list(tint) + [1.0], "metallicFactor": 0.0, "roughnessFactor": roughness}}
            for k, (tint, roughness) in enumerate(spheres)]
    meshes = [{"name": "sphere_%d" % k, "primitives": [{"attributes": sphere_attributes, "indices": sphere_indices,
                                                         "material": k}]} for k in range(4)]
    meshes.append({"name": "floor", "primitives": [{"attributes": floor_attributes, "indices": floor_indices,
                                                    "material": 4}]})
    centres = [(-0.5, 0.5, 0.0), (0.5, 0.5, 0.0), (-0.5, -0.5, 0.0), (0.5, -0.5, 0.0)]
    nodes = [{"name": "sphere_%d" % k, "mesh": k, "translation": list(c)} for k, c in enumerate(centres)]
    nodes.append({"name": "floor", "mesh": 4})
    while len(blob) % 4:
        blob.append(0)
    document = {
        "asset": {"version": "2.0", "generator": "gpurt scripts/make-pbr-spheres.py"},
        "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes, "meshes": meshes,
        "materials": materials, "textures": textures, "images": image_entries,
        "samplers": [{"magFilter": 9729, "minFilter": 9729, "wrapS": 10497, "wrapT": 10497}],
        "accessors": accessors, "bufferViews": views, "buffers": [{"byteLength": len(blob)}],
    }
    text = json.dumps(document, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    glb = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(text) + 8 + len(blob))
    glb += struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(blob), 0x004E4942) + bytes(blob)
    with open(out, "wb") as f:
        f.write(glb)
    print("%s: %d bytes" % (out, len(glb)))


if __name__ == "__main__":
    main()
