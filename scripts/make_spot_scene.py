#!/usr/bin/python3
"""Writes scenes/spotlights.gltf: a small stage lit by glTF's KHR_lights_punctual, the way an
exporter (Blender's, three.js') writes it: three coloured spot lights with soft cones (inner and
outer angles), one of them with a range, and a dim directional moonlight, over a floor, a back
wall, a sphere, a box and a column in glTF 2.0 metallic-roughness materials (one of them metal).
The lights shine down their nodes' -z, turned by the nodes' rotations (quaternions).

Standard library only; deterministic:  /usr/bin/python3 scripts/make_spot_scene.py
"""

import base64
import json
import math
import os
import struct

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "spotlights.gltf")


def box(center, half):
    """A box's 24 vertices, normals and 36 indices, wound outward."""
    cx, cy, cz = center
    hx, hy, hz = half
    faces = [((1, 0, 0), (0, 0, -1), (0, 1, 0)), ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
             ((0, 1, 0), (1, 0, 0), (0, 0, -1)), ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
             ((0, 0, 1), (1, 0, 0), (0, 1, 0)), ((0, 0, -1), (-1, 0, 0), (0, 1, 0))]
    pos, nrm, idx = [], [], []
    for n, u, v in faces:
        base = len(pos)
        for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            p = [n[k] + su * u[k] + sv * v[k] for k in range(3)]
            pos.append((cx + p[0] * hx, cy + p[1] * hy, cz + p[2] * hz))
            nrm.append(n)
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return pos, nrm, idx


def sphere(center, radius, segments, rings):
    pos, nrm, idx = [], [], []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for s in range(segments + 1):
            phi = 2 * math.pi * s / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            nrm.append(n)
            pos.append(tuple(center[k] + radius * n[k] for k in range(3)))
    for r in range(rings):
        for s in range(segments):
            a = r * (segments + 1) + s
            b = a + segments + 1
            idx += [a, b, a + 1, a + 1, b, b + 1]
    return pos, nrm, idx


def cylinder(center, radius, height, segments):
    pos, nrm, idx = [], [], []
    cx, cy, cz = center
    for s in range(segments + 1):
        phi = 2 * math.pi * s / segments
        n = (math.cos(phi), 0.0, -math.sin(phi))
        for y in (0.0, height):
            pos.append((cx + radius * n[0], cy + y, cz + radius * n[2]))
            nrm.append(n)
    for s in range(segments):
        a = 2 * s
        idx += [a, a + 2, a + 1, a + 1, a + 2, a + 3]
    top = len(pos)  # the cap
    pos.append((cx, cy + height, cz))
    nrm.append((0.0, 1.0, 0.0))
    for s in range(segments + 1):
        phi = 2 * math.pi * s / segments
        pos.append((cx + radius * math.cos(phi), cy + height, cz - radius * math.sin(phi)))
        nrm.append((0.0, 1.0, 0.0))
    for s in range(segments):
        idx += [top, top + 1 + s, top + 2 + s]
    return pos, nrm, idx


def look_rotation(d):
    """The quaternion (x, y, z, w) that turns -z into the unit direction d: about the axis
    cross(-z, d) by the angle acos(dot(-z, d))."""
    axis = (d[1], -d[0], 0.0)
    length = math.sqrt(axis[0] ** 2 + axis[1] ** 2)
    if length < 1e-9:
        return [0.0, 0.0, 0.0, 1.0] if d[2] < 0 else [0.0, 1.0, 0.0, 0.0]
    angle = math.acos(max(-1.0, min(1.0, -d[2])))
    s = math.sin(angle / 2) / length
    return [round(axis[0] * s, 7), round(axis[1] * s, 7), 0.0, round(math.cos(angle / 2), 7)]


def aim(frm, to):
    d = [to[k] - frm[k] for k in range(3)]
    n = math.sqrt(sum(a * a for a in d))
    return look_rotation([a / n for a in d])


def main():
    meshes = [
        ("floor", box((0, -0.05, 0), (6, 0.05, 5)), 0),
        ("wall", box((0, 2.5, -3.0), (6, 2.5, 0.1)), 0),
        ("sphere", sphere((-1.6, 0.8, -0.6), 0.8, 48, 24), 1),
        ("box", box((0.4, 0.6, 0.3), (0.6, 0.6, 0.6)), 2),
        ("column", cylinder((2.3, 0.0, -1.2), 0.35, 2.6, 40), 3),
    ]
    blob = bytearray()
    views, accessors, gl_meshes = [], [], []
    for name, (pos, nrm, idx), material in meshes:
        first = len(accessors)
        for data, kind in ((pos, "VEC3"), (nrm, "VEC3")):
            offset = len(blob)
            for v in data:
                blob += struct.pack("<3f", *v)
            views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(blob) - offset, "target": 34962})
            acc = {"bufferView": len(views) - 1, "componentType": 5126, "count": len(data), "type": kind}
            if data is pos:
                acc["min"] = [min(p[k] for p in pos) for k in range(3)]
                acc["max"] = [max(p[k] for p in pos) for k in range(3)]
            accessors.append(acc)
        offset = len(blob)
        for i in idx:
            blob += struct.pack("<I", i)
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(blob) - offset, "target": 34963})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5125, "count": len(idx), "type": "SCALAR"})
        gl_meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": first, "NORMAL": first + 1},
                                                        "indices": first + 2, "material": material}]})
    materials = [
        {"name": "plaster", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.78, 0.75, 1], "metallicFactor": 0,
                                                      "roughnessFactor": 0.9}},
        {"name": "gold", "pbrMetallicRoughness": {"baseColorFactor": [1.0, 0.78, 0.34, 1], "metallicFactor": 1,
                                                   "roughnessFactor": 0.3}},
        {"name": "red plastic", "pbrMetallicRoughness": {"baseColorFactor": [0.75, 0.08, 0.06, 1], "metallicFactor": 0,
                                                          "roughnessFactor": 0.4}},
        {"name": "marble", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.9, 0.88, 1], "metallicFactor": 0,
                                                     "roughnessFactor": 0.15}},
    ]
    lights = [
        {"name": "warm spot", "type": "spot", "color": [1.0, 0.75, 0.45], "intensity": 120,
         "spot": {"innerConeAngle": 0.25, "outerConeAngle": 0.45}},
        {"name": "cool spot", "type": "spot", "color": [0.45, 0.65, 1.0], "intensity": 90,
         "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.35}},
        {"name": "magenta spot", "type": "spot", "color": [1.0, 0.35, 0.8], "intensity": 80, "range": 9,
         "spot": {"innerConeAngle": 0.0, "outerConeAngle": 0.3}},
        {"name": "moonlight", "type": "directional", "color": [0.6, 0.7, 1.0], "intensity": 0.25},
    ]
    spots = [((-3.0, 4.2, 2.0), (-1.6, 0.8, -0.6)), ((2.5, 4.5, 2.5), (0.4, 0.6, 0.3)),
             ((3.5, 4.0, 0.5), (2.3, 1.3, -1.6))]
    nodes = [{"mesh": m} for m in range(len(meshes))]
    for k, (frm, to) in enumerate(spots):
        nodes.append({"name": lights[k]["name"], "translation": list(frm), "rotation": aim(frm, to),
                      "extensions": {"KHR_lights_punctual": {"light": k}}})
    nodes.append({"name": "moon", "rotation": aim((0, 0, 0), (0.3, -1.0, -0.5)),
                  "extensions": {"KHR_lights_punctual": {"light": 3}}})
    nodes.append({"name": "camera", "translation": [0.6, 2.3, 7.4], "rotation": aim((0.6, 2.3, 7.4), (0.2, 0.9, -0.6)),
                  "camera": 0})
    gltf = {
        "asset": {"version": "2.0", "generator": "gpurt scripts/make_spot_scene.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": lights}},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.62, "znear": 0.1, "aspectRatio": 1.5}}],
        "meshes": gl_meshes,
        "materials": materials,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
    }
    with open(OUT, "w") as f:
        json.dump(gltf, f, separators=(",", ":"))
        f.write("\n")


if __name__ == "__main__":
    main()
