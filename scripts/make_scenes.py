#!/usr/bin/python3
"""Writes gpurt's demo scenes (scenes/*.obj, *.mtl, *.json): the seed's three test scenes rebuilt
from geometry generated here, so that every shipped asset can be regenerated and redistributed.

  A  boxes.json    "3 boxes": 36 triangles, one box a mirror, no floor
  B  room.json     "cubes distributed in a room": 2,064 triangles (a closed room and 171 cubes)
  C  highlow.json  "high and low polygon objects": a 60,000-triangle torus beside a tetrahedron, a
                   mirror cube and an octahedron on a floor (60,026 triangles)
  D  cornell.json  the classic Cornell box with an area light (MTL Ke), a glass sphere (illum 7,
                   Ni 1.5, exact vertex normals) and a mirror block
  E  cornell_blocks.json  the classic Cornell box with two white blocks
  F  metal_rough_spheres.json  glTF's metallic-roughness model in the spirit of Khronos'
                   MetalRoughSpheres: 5 x 5 spheres, metallic 0..1 down, roughness 0..1 across,
                   under the sky of sky.json
  G  rough_glass.json  KHR_materials_transmission's rough dielectric (JSON transmission, ior):
                   five glass spheres, roughness 0..0.5, one tinted, on a slab under the sky
  H  layers.json   KHR_materials_clearcoat, _specular and _sheen (JSON clearcoat,
                   clearcoat_roughness, specular_factor, specular_color, sheen_color,
                   sheen_roughness): a rough red plastic bare, under a smooth and a rough coat, a
                   coated black, a tinted reflection, a velvet
  I  volume.json   KHR_materials_volume (JSON attenuation_color, attenuation_distance): three
                   spheres of one amber glass, small to large (the larger, the deeper its colour),
                   an upright torus of blue-green glass and a rough green glass cube
  J  iridescence.json  KHR_materials_iridescence (JSON iridescence, iridescence_ior,
                   iridescence_thickness): four dark spheres under films of 250 to 550 nm and two
                   anodised titanium ones
  K  anisotropy.json  KHR_materials_anisotropy (JSON anisotropy, anisotropy_rotation): metal
                   spheres polished, then brushed around the up axis at strengths 0.5 and 0.9,
                   brushed along the meridians, in a spiral (gold), and a smoother copper at full
                   strength
  L  thin_walls.json  KHR_materials_transmission's thin walls (JSON thin_walled) beside solids:
                   clear glass solid and thin (a bubble), a thin tinted one, rough glass thin
                   (frosted) and solid
  M  dispersion.json  KHR_materials_dispersion (JSON dispersion): five clear glass spheres of index
                   1.6, dispersion 0, 1, 3, 6 and 12 (Abbe numbers none, 20, 6.7, 3.3, 1.7)

Standard library only; deterministic (its own random generator, fixed number formatting), so
running it again rewrites the files byte for byte:  /usr/bin/python3 scripts/make_scenes.py
(`scripts/make_scenes.py globe FOLDER` writes the textured sphere of the test assets there instead.)
"""

import math
import os
import sys

SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes")


def fmt(x):
    """A number with 6 significant digits, never '-0'."""
    text = "%.6g" % x
    return "0" if text in ("-0", "0") else text


class Lcg:
    """Numerical Recipes' 32-bit linear congruential generator: the same numbers on every Python."""

    def __init__(self, seed):
        self.state = seed & 0xFFFFFFFF

    def uniform(self, lo, hi):
        self.state = (1664525 * self.state + 1013904223) & 0xFFFFFFFF
        return lo + (hi - lo) * (self.state / 4294967296.0)

    def below(self, n):
        return min(n - 1, int(self.uniform(0, n)))


class ObjWriter:
    """Collects indexed vertices and faces (grouped by material, in the order they were added)."""

    def __init__(self, comment, mtllib=None):
        self.lines = ["# " + line for line in comment] if isinstance(comment, list) else ["# " + comment]
        self.lines.append("# written by scripts/make_scenes.py; do not edit by hand")
        if mtllib:
            self.lines.append("mtllib " + mtllib)
        self.vertex_count = 0
        self.triangles = 0
        self.material = None

    def vertex(self, p):
        self.lines.append("v %s %s %s" % (fmt(p[0]), fmt(p[1]), fmt(p[2])))
        self.vertex_count += 1
        return self.vertex_count  # OBJ indices start at 1

    def normal(self, n):
        self.lines.append("vn %s %s %s" % (fmt(n[0]), fmt(n[1]), fmt(n[2])))
        self.normal_count = getattr(self, "normal_count", 0) + 1
        return self.normal_count

    def use(self, material):
        if material != self.material:
            self.lines.append("usemtl " + material)
            self.material = material

    def face(self, indices):
        self.lines.append("f " + " ".join(str(i) for i in indices))
        self.triangles += len(indices) - 2

    def save(self, name):
        write(name, "\n".join(self.lines) + "\n")


def write(name, text):
    with open(os.path.join(SCENES, name), "w", encoding="ascii", newline="\n") as out:
        out.write(text)


# Corners (i, j, k) in {0,1}^3 of a box, and its faces as corner lists wound counter-clockwise
# seen from outside (normal = cross(b - a, c - a) points out).
BOX_FACES = [
    [(0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0)],  # -x
    [(1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1)],  # +x
    [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)],  # -y
    [(0, 1, 0), (0, 1, 1), (1, 1, 1), (1, 1, 0)],  # +y
    [(0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0)],  # -z
    [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)],  # +z
]


def add_box(obj, center, half, yaw_degrees=0.0, inward=False):
    """An axis-aligned box turned by yaw_degrees about +y: 8 vertices, 12 triangles."""
    c, s = math.cos(math.radians(yaw_degrees)), math.sin(math.radians(yaw_degrees))
    index = {}
    for i in (0, 1):
        for j in (0, 1):
            for k in (0, 1):
                x, y, z = ((2 * i - 1) * half[0], (2 * j - 1) * half[1], (2 * k - 1) * half[2])
                # Rotation about +y: x' = c x + s z, z' = -s x + c z.
                index[(i, j, k)] = obj.vertex((center[0] + c * x + s * z, center[1] + y, center[2] - s * x + c * z))
    for corners in BOX_FACES:
        a, b, cc, d = (index[corner] for corner in corners)
        if inward:
            a, b, cc, d = a, d, cc, b
        obj.face([a, b, cc])
        obj.face([a, cc, d])


def mtl(comment, materials):
    """materials: (name, Kd, Ks, Ns, illum)."""
    lines = ["# " + comment, "# written by scripts/make_scenes.py; do not edit by hand"]
    for name, kd, ks, ns, illum in materials:
        lines += ["", "newmtl " + name, "Kd %s %s %s" % tuple(fmt(v) for v in kd),
                  "Ks %s %s %s" % tuple(fmt(v) for v in ks), "Ns " + fmt(ns), "illum %d" % illum]
    return "\n".join(lines) + "\n"


def to_json(value, indent=0):
    """JSON with objects one key a line and arrays of numbers on one line."""
    pad = "  " * indent
    if isinstance(value, dict):
        items = ['%s  "%s": %s' % (pad, key, to_json(v, indent + 1)) for key, v in value.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(value, list):
        if all(isinstance(v, (int, float)) for v in value):
            return "[" + ", ".join(to_json(v) for v in value) + "]"
        return "[\n" + ",\n".join(pad + "  " + to_json(v, indent + 1) for v in value) + "\n" + pad + "]"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return fmt(value)
    return '"%s"' % value


def scene_a():
    """Three boxes, one of them a mirror, floating in front of a coloured background."""
    obj = ObjWriter('Scene A "3 boxes": 36 triangles', "boxes.mtl")
    obj.use("red")
    add_box(obj, (-1.4, 0.5, 0.0), (0.5, 0.5, 0.5), 20.0)
    obj.use("mirror")
    add_box(obj, (0.3, 0.75, -0.9), (0.45, 0.75, 0.45), -15.0)
    obj.use("blue")
    add_box(obj, (1.5, 0.35, 0.6), (0.6, 0.35, 0.4), 35.0)
    assert obj.triangles == 36
    obj.save("boxes.obj")
    write("boxes.mtl", mtl('Scene A "3 boxes"', [
        ("red", (0.8, 0.15, 0.1), (0.3, 0.3, 0.3), 32, 2),
        ("mirror", (0.05, 0.05, 0.05), (0.85, 0.85, 0.85), 200, 3),  # illum 3: Ks is the reflectivity
        ("blue", (0.15, 0.3, 0.85), (0.3, 0.3, 0.3), 32, 2),
    ]))
    write("boxes.json", to_json({
        "meshes": [{"file": "boxes.obj"}],
        "lights": [
            {"position": [3.0, 5.0, 4.0], "color": [1.0, 0.95, 0.9], "intensity": 45.0},
            {"position": [-4.0, 3.0, 2.5], "color": [0.8, 0.85, 1.0], "intensity": 25.0},
        ],
        "camera": {"eye": [1.2, 2.6, 5.5], "target": [0.1, 0.55, 0.0], "up": [0.0, 1.0, 0.0], "fovy": 40.0},
        "background": [0.15, 0.2, 0.3],
        "render": {"size": [256, 256], "max_bounces": 3},
    }) + "\n")
    return obj.triangles


def scene_b():
    """A closed room (12 triangles) with 171 small cubes (2,052 triangles) in it, on the floor and
    floating at two heights on a jittered lattice; about one cube in eight is a mirror."""
    obj = ObjWriter('Scene B "cubes distributed in a room": 2,064 triangles', "room.mtl")
    obj.use("walls")
    add_box(obj, (0.0, 2.5, 0.0), (6.0, 2.5, 6.0), 0.0, inward=True)  # normals face into the room

    rng = Lcg(20050817)
    slots = []  # 9 x 8 columns between x = -5..5 and z = -5.5..3 (clear of the camera), 3 heights
    for level, y in enumerate((None, 1.7, 3.1)):
        for iz in range(8):
            for ix in range(9):
                slots.append((level, -5.0 + ix * 1.25, -5.5 + iz * (8.5 / 7), y))
    for i in range(len(slots) - 1, 0, -1):  # Fisher-Yates with the deterministic generator
        j = rng.below(i + 1)
        slots[i], slots[j] = slots[j], slots[i]
    colours = ["red", "green", "blue", "yellow", "white"]
    for level, x, z, y in sorted(slots[:171]):
        half = rng.uniform(0.15, 0.3)
        yaw = rng.uniform(0.0, 90.0)
        jitter_x, jitter_z = rng.uniform(-0.15, 0.15), rng.uniform(-0.15, 0.15)
        centre_y = half if y is None else y + rng.uniform(-0.2, 0.2)
        obj.use("mirror" if rng.uniform(0, 1) < 0.125 else colours[rng.below(len(colours))])
        add_box(obj, (x + jitter_x, centre_y, z + jitter_z), (half, half, half), yaw)
    assert obj.triangles == 2064, obj.triangles
    obj.save("room.obj")
    write("room.mtl", mtl('Scene B "cubes distributed in a room"', [
        ("walls", (0.75, 0.72, 0.65), (0.0, 0.0, 0.0), 1, 1),
        ("red", (0.8, 0.15, 0.1), (0.4, 0.4, 0.4), 32, 2),
        ("green", (0.2, 0.7, 0.25), (0.4, 0.4, 0.4), 32, 2),
        ("blue", (0.15, 0.3, 0.85), (0.4, 0.4, 0.4), 32, 2),
        ("yellow", (0.85, 0.75, 0.15), (0.4, 0.4, 0.4), 32, 2),
        ("white", (0.85, 0.85, 0.85), (0.4, 0.4, 0.4), 32, 2),
        ("mirror", (0.05, 0.05, 0.05), (0.8, 0.8, 0.8), 200, 3),
    ]))
    write("room.json", to_json({
        "meshes": [{"file": "room.obj"}],
        "lights": [
            {"position": [-3.5, 4.6, -2.0], "color": [1.0, 0.95, 0.85], "intensity": 9.0},
            {"position": [3.5, 4.6, -2.0], "color": [0.9, 0.95, 1.0], "intensity": 9.0},
            {"position": [0.0, 4.6, 3.5], "color": [1.0, 1.0, 1.0], "intensity": 6.0},
        ],
        "camera": {"eye": [0.0, 2.6, 5.6], "target": [0.0, 1.6, -3.0], "up": [0.0, 1.0, 0.0], "fovy": 60.0},
        "background": [0.0, 0.0, 0.0],
        "render": {"size": [256, 256], "max_bounces": 3},
    }) + "\n")
    return obj.triangles


def scene_c():
    """A 60,000-triangle torus beside three low-polygon solids on a floor; the cube is a mirror.
    The shapes are unit meshes placed by the JSON file's transforms and material overrides."""
    counts = {}

    floor = ObjWriter("A square in the xz plane, -1..1 (2 triangles)")
    corners = [floor.vertex(p) for p in [(-1, 0, -1), (-1, 0, 1), (1, 0, 1), (1, 0, -1)]]
    floor.face([corners[0], corners[1], corners[2]])
    floor.face([corners[0], corners[2], corners[3]])
    floor.save("floor.obj")
    counts["floor"] = floor.triangles

    # Torus about the y axis: major radius 1, minor 0.35; 250 x 120 quads, each fanned to 2 triangles.
    major_steps, minor_steps, major, minor = 250, 120, 1.0, 0.35
    torus = ObjWriter(["A torus about +y, radii 1 and 0.35, %d x %d quads (%d triangles)"
                       % (major_steps, minor_steps, 2 * major_steps * minor_steps)])
    for i in range(major_steps):
        u = 2 * math.pi * i / major_steps
        for j in range(minor_steps):
            v = 2 * math.pi * j / minor_steps
            ring = major + minor * math.cos(v)
            torus.vertex((ring * math.cos(u), minor * math.sin(v), -ring * math.sin(u)))
    for i in range(major_steps):
        for j in range(minor_steps):
            def at(a, b):
                return 1 + (a % major_steps) * minor_steps + (b % minor_steps)
            torus.face([at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)])
    torus.save("torus.obj")
    counts["torus"] = torus.triangles

    cube = ObjWriter("A unit cube, -0.5..0.5 (12 triangles)")
    add_box(cube, (0, 0, 0), (0.5, 0.5, 0.5))
    cube.save("cube.obj")
    counts["cube"] = cube.triangles

    # Regular tetrahedron with edge 1, its base on y = 0.
    tetra = ObjWriter("A regular tetrahedron, edge 1, base on y = 0 (4 triangles)")
    radius, height = 1 / math.sqrt(3), math.sqrt(2.0 / 3.0)
    base = [tetra.vertex((radius * math.cos(a), 0, -radius * math.sin(a)))
            for a in (math.pi / 2, math.pi / 2 + 2 * math.pi / 3, math.pi / 2 + 4 * math.pi / 3)]
    apex = tetra.vertex((0, height, 0))
    tetra.face([base[0], base[2], base[1]])  # bottom, facing -y
    tetra.face([base[0], base[1], apex])
    tetra.face([base[1], base[2], apex])
    tetra.face([base[2], base[0], apex])
    tetra.save("tetrahedron.obj")
    counts["tetrahedron"] = tetra.triangles

    octa = ObjWriter("A regular octahedron, vertices on the axes at distance 1 (8 triangles)")
    px, nx, py, ny, pz, nz = (octa.vertex(p) for p in
                              [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)])
    for top, ring in ((py, [px, nz, nx, pz]), (ny, [px, pz, nx, nz])):  # rings wound so normals point out
        for k in range(4):
            octa.face([top, ring[k], ring[(k + 1) % 4]])
    octa.save("octahedron.obj")
    counts["octahedron"] = octa.triangles

    write("highlow.json", to_json({
        "meshes": [
            {"file": "floor.obj", "transform": {"scale": [6.0, 1.0, 6.0]},
             "material": {"diffuse": [0.6, 0.6, 0.55]}},
            {"file": "torus.obj", "transform": {"translate": [-1.2, 1.4, -0.3], "rotate": [70.0, 20.0, 0.0]},
             "material": {"diffuse": [0.8, 0.35, 0.1], "specular": [0.6, 0.6, 0.6], "shininess": 48.0}},
            {"file": "cube.obj",
             "transform": {"translate": [1.6, 0.6, -0.8], "rotate": [0.0, 30.0, 0.0], "scale": 1.2},
             "material": {"name": "mirror", "diffuse": [0.05, 0.05, 0.05], "specular": [0.9, 0.9, 0.9],
                          "shininess": 200.0, "reflectivity": 0.85}},
            {"file": "tetrahedron.obj", "transform": {"translate": [1.5, 0.0, 1.3], "rotate": [0.0, 15.0, 0.0],
                                                      "scale": 1.1},
             "material": {"diffuse": [0.2, 0.7, 0.25], "specular": [0.3, 0.3, 0.3], "shininess": 32.0}},
            {"file": "octahedron.obj", "transform": {"translate": [-0.2, 0.55, 1.9], "scale": 0.55},
             "material": {"diffuse": [0.55, 0.25, 0.75], "specular": [0.3, 0.3, 0.3], "shininess": 32.0}},
        ],
        "lights": [
            {"position": [4.0, 6.0, 5.0], "color": [1.0, 0.97, 0.9], "intensity": 60.0},
            {"position": [-5.0, 4.0, 3.0], "color": [0.8, 0.85, 1.0], "intensity": 30.0},
        ],
        "camera": {"eye": [0.5, 2.6, 6.5], "target": [0.0, 0.9, 0.0], "up": [0.0, 1.0, 0.0], "fovy": 45.0},
        "background": [0.1, 0.12, 0.18],
        "render": {"size": [256, 256], "max_bounces": 3},
    }) + "\n")
    return sum(counts.values())


def add_quad(obj, corners):
    """A quad as two triangles (v0, v1, v2), (v0, v2, v3); wound as given."""
    index = [obj.vertex(c) for c in corners]
    obj.face(index)


def add_sphere(obj, center, radius, segments, rings):
    """A UV sphere wound outward, with its exact unit normals as vn."""
    rows = []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        row = []
        for k in range(segments):
            phi = 2 * math.pi * k / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
            v = obj.vertex(tuple(center[i] + radius * n[i] for i in range(3)))
            vn = obj.normal(n)
            row.append((v, vn))
        rows.append(row)
    for r in range(rings):
        for k in range(segments):
            a, b = rows[r][k], rows[r][(k + 1) % segments]
            c, d = rows[r + 1][(k + 1) % segments], rows[r + 1][k]
            ref = lambda p: "%d//%d" % p
            if r > 0:
                obj.lines.append("f %s %s %s" % (ref(a), ref(b), ref(c)))
                obj.triangles += 1
            if r < rings - 1:
                obj.lines.append("f %s %s %s" % (ref(a), ref(c), ref(d)))
                obj.triangles += 1


def globe(folder):
    """A textured UV sphere for the texture tests (scripts/make-test-assets.sh): radius 1 at the
    origin, 48 segments by 24 rings, vt (u, v) = (longitude / 2 pi, 1 - colatitude / pi) with the
    seam's column doubled, vn exact; its material maps checker.jpg."""
    segments, rings = 48, 24
    obj = ObjWriter("a UV sphere with texture coordinates (scripts/make_scenes.py globe)", "globe.mtl")
    obj.use("globe")
    index = {}
    texcoords = 0
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for k in range(segments + 1):
            phi = 2 * math.pi * k / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            v = obj.vertex(n)
            vn = obj.normal(n)
            obj.lines.append("vt %s %s" % (fmt(k / segments), fmt(1 - r / rings)))
            texcoords += 1
            index[r, k] = "%d/%d/%d" % (v, texcoords, vn)
    for r in range(rings):
        for k in range(segments):
            a, b, c, d = index[r, k], index[r + 1, k], index[r + 1, k + 1], index[r, k + 1]
            if r > 0:
                obj.lines.append("f %s %s %s" % (a, b, d))
                obj.triangles += 1
            if r < rings - 1:
                obj.lines.append("f %s %s %s" % (b, c, d))
                obj.triangles += 1
    text = "\n".join(obj.lines) + "\n"
    with open(os.path.join(folder, "globe.obj"), "w", encoding="ascii", newline="\n") as out:
        out.write(text)
    with open(os.path.join(folder, "globe.mtl"), "w", encoding="ascii", newline="\n") as out:
        out.write("# written by scripts/make_scenes.py globe\nnewmtl globe\nKd 1 1 1\nmap_Kd checker.jpg\n")
    return obj.triangles


def cornell_walls(obj):
    """The Cornell box's walls (Goral et al. 1984; the Cornell measurements' layout, 555 units a
    side) and its ceiling light."""
    w = 555.0
    obj.use("white")
    add_quad(obj, [(0, 0, 0), (0, 0, w), (w, 0, w), (w, 0, 0)])  # floor, facing up
    # The ceiling, facing down, with the light in a hole of its own (as in the real box): a light
    # hung below a closed ceiling would light the thin gap above it from its back, a hot spot that
    # paths find only rarely (fireflies).
    lx0, lx1, lz0, lz1 = 213.0, 343.0, 227.0, 332.0
    for x0, x1, z0, z1 in ((0, w, 0, lz0), (0, w, lz1, w), (0, lx0, lz0, lz1), (lx1, w, lz0, lz1)):
        add_quad(obj, [(x0, w, z0), (x1, w, z0), (x1, w, z1), (x0, w, z1)])
    add_quad(obj, [(0, 0, w), (0, w, w), (w, w, w), (w, 0, w)])  # back wall, facing -z
    # The camera looks along +z from z < 0, so +x is on its left: red there, green at x = 0.
    obj.use("red")
    add_quad(obj, [(w, 0, 0), (w, 0, w), (w, w, w), (w, w, 0)])  # left wall (x = 555), facing -x
    obj.use("green")
    add_quad(obj, [(0, 0, 0), (0, w, 0), (0, w, w), (0, 0, w)])  # right wall (x = 0), facing +x
    obj.use("light")
    add_quad(obj, [(lx0, w, lz0), (lx1, w, lz0), (lx1, w, lz1), (lx0, w, lz1)])  # facing down, in the hole


def cornell_materials(name, blocks):
    """The Cornell box's MTL: its walls, light (Ke) and the materials `blocks` of what stands in it."""
    lines = mtl(name, [
        ("white", (0.725, 0.71, 0.68), (0, 0, 0), 1, 1),
        ("red", (0.63, 0.065, 0.05), (0, 0, 0), 1, 1),
        ("green", (0.14, 0.45, 0.091), (0, 0, 0), 1, 1),
        ("light", (0.78, 0.78, 0.78), (0, 0, 0), 1, 1),
    ] + blocks).split("\n")
    out = []
    for line in lines:
        out.append(line)
        if line == "illum 1" and out[-5] == "newmtl light":
            out.append("Ke 34 26 16")
        if line == "illum 7":
            out += ["Ni 1.5", "Tf 0.98 0.98 0.98"]
    return "\n".join(out)


def cornell_json(obj_name, max_bounces):
    return to_json({
        "meshes": [{"file": obj_name}],
        "camera": {"eye": [278.0, 273.0, -800.0], "target": [278.0, 273.0, 0.0], "up": [0.0, 1.0, 0.0], "fovy": 39.0},
        "background": [0.0, 0.0, 0.0],
        "render": {"size": [512, 512], "max_bounces": max_bounces},
    }) + "\n"


def scene_d():
    """The Cornell box lit by its ceiling light, with a glass sphere and a mirror block."""
    obj = ObjWriter('Scene D "Cornell box": area light, glass sphere, mirror block', "cornell.mtl")
    cornell_walls(obj)
    obj.use("mirror")
    add_box(obj, (368.0, 165.0, 372.0), (82.5, 165.0, 82.5), -17.0)
    obj.use("glass")
    add_sphere(obj, (185.0, 100.0, 170.0), 100.0, 48, 24)
    obj.save("cornell.obj")
    write("cornell.mtl", cornell_materials('Scene D "Cornell box"', [
        ("mirror", (0.02, 0.02, 0.02), (0.9, 0.9, 0.9), 1000, 3),  # illum 3: Ks is the reflectivity
        ("glass", (0, 0, 0), (0, 0, 0), 1, 7),  # illum 7: glass, index Ni, filter Tf
    ]))
    write("cornell.json", cornell_json("cornell.obj", 6))
    return obj.triangles


def scene_e():
    """The classic Cornell box: its light and two diffuse blocks, 42 triangles (the scene path
    tracers compare on, as GLSL-PathTracer's cornell_box)."""
    obj = ObjWriter('Scene E "Cornell blocks": the classic box, area light, two white blocks', "cornell_blocks.mtl")
    cornell_walls(obj)
    obj.use("white")
    add_box(obj, (368.0, 165.0, 372.0), (82.5, 165.0, 82.5), -17.0)  # the tall block
    add_box(obj, (185.0, 82.5, 169.0), (82.5, 82.5, 82.5), 17.0)  # the short block
    obj.save("cornell_blocks.obj")
    write("cornell_blocks.mtl", cornell_materials('Scene E "Cornell blocks"', []))
    write("cornell_blocks.json", cornell_json("cornell_blocks.obj", 3))
    return obj.triangles


def scene_f():
    """The sphere grid of glTF materials (JSON metallic, roughness): one UV sphere mesh
    (sphere.obj, radius 1, exact normals) placed 25 times with a material each."""
    obj = ObjWriter("A UV sphere of radius 1 at the origin, 64 segments by 32 rings, exact vertex normals")
    add_sphere(obj, (0.0, 0.0, 0.0), 1.0, 64, 32)
    obj.save("sphere.obj")
    meshes = []
    for row in range(5):  # metallic, top row 0
        for column in range(5):  # roughness, left column 0
            metallic, roughness = row / 4.0, column / 4.0
            meshes.append({"file": "sphere.obj",
                           "transform": {"translate": [2.4 * (column - 2), 2.4 * (2 - row), 0.0]},
                           "material": {"name": "m%g r%g" % (metallic, roughness), "diffuse": [0.9, 0.55, 0.3],
                                        "metallic": metallic, "roughness": roughness}})
    write("metal_rough_spheres.json", to_json({
        "meshes": meshes,
        "environment": {"file": "sky.hdr", "strength": 1.0, "rotation": 30},
        "camera": {"eye": [0.0, 0.0, 17.0], "target": [0.0, 0.0, 0.0], "up": [0.0, 1.0, 0.0], "fovy": 40.0},
        "render": {"size": [480, 480], "max_bounces": 4},
    }) + "\n")
    return obj.triangles * 25


def scene_g():
    """Glass of glTF's model (JSON metallic, roughness, transmission, ior): sphere.obj five times
    (scene F writes it) on a slab (slab.obj, a thin box)."""
    obj = ObjWriter("A slab 24 x 0.2 x 14, its top at y = -1")
    add_box(obj, (0.0, -1.1, 0.0), (12.0, 0.1, 7.0), 0.0)
    obj.save("slab.obj")
    meshes = [{"file": "slab.obj", "material": {"name": "slab", "diffuse": [0.7, 0.7, 0.7], "metallic": 0, "roughness": 0.6}}]
    for k, (roughness, tint) in enumerate(((0.0, [1.0, 1.0, 1.0]), (0.1, [1.0, 1.0, 1.0]), (0.25, [1.0, 1.0, 1.0]),
                                           (0.5, [1.0, 1.0, 1.0]), (0.1, [0.55, 0.85, 0.65]))):
        meshes.append({"file": "sphere.obj", "transform": {"translate": [2.4 * (k - 2), 0.0, 0.0]},
                       "material": {"name": "glass r%g" % roughness, "diffuse": tint, "metallic": 0,
                                    "roughness": roughness, "transmission": 1, "ior": 1.5}})
    write("rough_glass.json", to_json({
        "meshes": meshes,
        "environment": {"file": "sky.hdr", "strength": 1.0, "rotation": 30},
        "camera": {"eye": [0.0, 2.2, 9.5], "target": [0.0, -0.2, 0.0], "up": [0.0, 1.0, 0.0], "fovy": 45.0},
        "render": {"size": [640, 320], "max_bounces": 8},
    }) + "\n")
    return obj.triangles + 5 * 64 * 32 * 2


def scene_h():
    """The layers of glTF's extensions (JSON clearcoat, clearcoat_roughness, specular_factor,
    specular_color, sheen_color, sheen_roughness): sphere.obj six times on slab.obj (scenes F and G
    write them), left to right a rough red plastic bare, under a smooth coat, under a rough coat, a
    black base without a specular layer under a smooth coat (the coat alone), a white one whose
    reflection is tinted blue, and a dark red velvet with a pale pink sheen."""
    red = {"diffuse": [0.5, 0.02, 0.01], "metallic": 0, "roughness": 0.45}
    spheres = [
        dict(red, name="red plastic"),
        dict(red, name="red, smooth coat", clearcoat=1),
        dict(red, name="red, rough coat", clearcoat=1, clearcoat_roughness=0.3),
        {"name": "coat alone", "diffuse": [0.0, 0.0, 0.0], "metallic": 0, "roughness": 1, "specular_factor": 0,
         "clearcoat": 1},
        {"name": "blue reflection", "diffuse": [0.8, 0.8, 0.8], "metallic": 0, "roughness": 0.2,
         "specular_factor": 1, "specular_color": [0.3, 0.8, 2.5]},
        {"name": "velvet", "diffuse": [0.25, 0.01, 0.03], "metallic": 0, "roughness": 0.9,
         "sheen_color": [1.0, 0.7, 0.75], "sheen_roughness": 0.4},
    ]
    meshes = [{"file": "slab.obj", "material": {"name": "slab", "diffuse": [0.7, 0.7, 0.7], "metallic": 0, "roughness": 0.6}}]
    for k, material in enumerate(spheres):
        meshes.append({"file": "sphere.obj", "transform": {"translate": [2.4 * (k - 2.5), 0.0, 0.0]}, "material": material})
    write("layers.json", to_json({
        "meshes": meshes,
        "environment": {"file": "sky.hdr", "strength": 1.0, "rotation": 30},
        "camera": {"eye": [0.0, 2.2, 11.0], "target": [0.0, -0.2, 0.0], "up": [0.0, 1.0, 0.0], "fovy": 40.0},
        "render": {"size": [720, 300], "max_bounces": 8},
    }) + "\n")
    return 0


def scene_i():
    """Coloured glass (KHR_materials_volume's Beer-Lambert absorption: JSON attenuation_color and
    attenuation_distance) on slab.obj: sphere.obj three times in one amber glass at radii 0.5, 0.8
    and 1.1 (light travels farther inside the larger ones), torus.obj upright in a blue-green glass
    and cube.obj in a rough green one."""
    def glass(name, colour, distance, roughness=0.0):
        return {"name": name, "diffuse": [1.0, 1.0, 1.0], "metallic": 0, "roughness": roughness, "transmission": 1,
                "ior": 1.5, "attenuation_color": colour, "attenuation_distance": distance}
    amber = glass("amber glass", [0.95, 0.6, 0.2], 0.8)
    meshes = [{"file": "slab.obj", "material": {"name": "slab", "diffuse": [0.7, 0.7, 0.7], "metallic": 0, "roughness": 0.6}}]
    for x, radius in ((-5.0, 0.5), (-3.3, 0.8), (-0.9, 1.1)):
        meshes.append({"file": "sphere.obj", "transform": {"translate": [x, radius - 1.0, 0.0], "scale": radius},
                       "material": amber})
    meshes.append({"file": "torus.obj", "transform": {"translate": [2.2, 0.08, 0.0], "rotate": [90.0, 0.0, 0.0], "scale": 0.8},
                   "material": glass("blue-green glass", [0.15, 0.65, 0.8], 0.4)})
    meshes.append({"file": "cube.obj", "transform": {"translate": [4.9, -0.4, 0.3], "rotate": [0.0, 30.0, 0.0], "scale": 1.2},
                   "material": glass("rough green glass", [0.35, 0.85, 0.4], 0.6, 0.15)})
    write("volume.json", to_json({
        "meshes": meshes,
        "environment": {"file": "sky.hdr", "strength": 1.0, "rotation": 30},
        "camera": {"eye": [0.0, 2.2, 10.0], "target": [0.0, -0.2, 0.0], "up": [0.0, 1.0, 0.0], "fovy": 42.0},
        "render": {"size": [720, 300], "max_bounces": 12},
    }) + "\n")
    return 0


def scene_j():
    """Thin films (KHR_materials_iridescence: JSON iridescence, iridescence_ior,
    iridescence_thickness) on sphere.obj six times on slab.obj: a near-black dielectric under films
    of index 2 and thickness 250, 350, 450 and 550 nm (the colours of beetles and oil), then a grey
    metal under films of index 2.2, 250 and 420 nm (anodised titanium)."""
    spheres = [{"name": "film %d nm" % d, "diffuse": [0.01, 0.01, 0.012], "metallic": 0, "roughness": 0.1,
                "iridescence": 1, "iridescence_ior": 2.0, "iridescence_thickness": d} for d in (250, 350, 450, 550)]
    spheres += [{"name": "titanium, %d nm" % d, "diffuse": [0.55, 0.52, 0.5], "metallic": 1, "roughness": 0.2,
                 "iridescence": 1, "iridescence_ior": 2.2, "iridescence_thickness": d} for d in (250, 420)]
    meshes = [{"file": "slab.obj", "material": {"name": "slab", "diffuse": [0.7, 0.7, 0.7], "metallic": 0, "roughness": 0.6}}]
    for k, material in enumerate(spheres):
        meshes.append({"file": "sphere.obj", "transform": {"translate": [2.4 * (k - 2.5), 0.0, 0.0]}, "material": material})
    write("iridescence.json", to_json({
        "meshes": meshes,
        "environment": {"file": "sky.hdr", "strength": 1.0, "rotation": 30},
        "camera": {"eye": [0.0, 2.2, 11.0], "target": [0.0, -0.2, 0.0], "up": [0.0, 1.0, 0.0], "fovy": 40.0},
        "render": {"size": [720, 300], "max_bounces": 8},
    }) + "\n")
    return 0


def scene_k():
    """Brushed metals (KHR_materials_anisotropy: JSON anisotropy, anisotropy_rotation) on sphere.obj
    six times on slab.obj. sphere.obj has no texture coordinates, so each tangent runs around the up
    axis (Blender's radial tangent): rotation 0 brushes along the parallels, pi / 2 along the
    meridians."""
    steel = [0.62, 0.62, 0.64]
    spheres = [{"name": "polished steel", "diffuse": steel, "metallic": 1, "roughness": 0.3},
               {"name": "brushed steel 0.5", "diffuse": steel, "metallic": 1, "roughness": 0.3, "anisotropy": 0.5},
               {"name": "brushed steel 0.9", "diffuse": steel, "metallic": 1, "roughness": 0.3, "anisotropy": 0.9},
               {"name": "steel brushed along the meridians", "diffuse": steel, "metallic": 1, "roughness": 0.3,
                "anisotropy": 0.9, "anisotropy_rotation": 1.5707963},
               {"name": "gold brushed in a spiral", "diffuse": [1.0, 0.78, 0.34], "metallic": 1, "roughness": 0.3,
                "anisotropy": 0.8, "anisotropy_rotation": 0.7853982},
               {"name": "copper", "diffuse": [0.95, 0.64, 0.54], "metallic": 1, "roughness": 0.15, "anisotropy": 1.0}]
    meshes = [{"file": "slab.obj", "material": {"name": "slab", "diffuse": [0.7, 0.7, 0.7], "metallic": 0, "roughness": 0.6}}]
    for k, material in enumerate(spheres):
        meshes.append({"file": "sphere.obj", "transform": {"translate": [2.4 * (k - 2.5), 0.0, 0.0]}, "material": material})
    write("anisotropy.json", to_json({
        "meshes": meshes,
        "environment": {"file": "sky.hdr", "strength": 1.0, "rotation": 30},
        "camera": {"eye": [0.0, 2.2, 11.0], "target": [0.0, -0.2, 0.0], "up": [0.0, 1.0, 0.0], "fovy": 40.0},
        "render": {"size": [720, 300], "max_bounces": 8},
    }) + "\n")
    return 0


def scene_l():
    """Thin walls (glTF's transmission without KHR_materials_volume, JSON thin_walled) beside
    solids, on sphere.obj five times on slab.obj: clear glass as a solid (the sky upside down in
    it) and as thin walls (a soap bubble's: seen through unbent), thin walls tinted blue by the base
    colour, frosted thin walls (roughness 0.3) and the same roughness as a solid."""
    def glass(name, thin, roughness=0.0, colour=(1.0, 1.0, 1.0)):
        m = {"name": name, "diffuse": list(colour), "metallic": 0, "roughness": roughness, "transmission": 1, "ior": 1.5}
        if thin:
            m["thin_walled"] = True
        return m
    spheres = [glass("clear solid", False), glass("clear thin walls", True),
               glass("blue thin walls", True, 0.0, (0.45, 0.7, 1.0)), glass("frosted thin walls", True, 0.3),
               glass("frosted solid", False, 0.3)]
    meshes = [{"file": "slab.obj", "material": {"name": "slab", "diffuse": [0.7, 0.7, 0.7], "metallic": 0, "roughness": 0.6}}]
    for k, material in enumerate(spheres):
        meshes.append({"file": "sphere.obj", "transform": {"translate": [2.4 * (k - 2.0), 0.0, 0.0]}, "material": material})
    write("thin_walls.json", to_json({
        "meshes": meshes,
        "environment": {"file": "sky.hdr", "strength": 1.0, "rotation": 30},
        "camera": {"eye": [0.0, 2.2, 10.0], "target": [0.0, -0.2, 0.0], "up": [0.0, 1.0, 0.0], "fovy": 40.0},
        "render": {"size": [720, 300], "max_bounces": 12},
    }) + "\n")
    return 0


def scene_m():
    """KHR_materials_dispersion (JSON dispersion): sphere.obj five times on slab.obj before a row of
    glowing white bars (bars.obj) under a dim sky, clear glass of index 1.6 whose dispersion grows
    left to right, 0 (none), 1 (Abbe number 20, a dense flint), 3, 6 and 12: the bars seen through
    each sphere split into ever wider red, green and blue images."""
    obj = ObjWriter("Twenty-four upright bars 0.1 x 3.6 x 0.1, 0.6 apart, standing on y = -1 at z = -3")
    for k in range(24):
        add_box(obj, (0.6 * (k - 11.5), 0.8, -3.0), (0.05, 1.8, 0.05), 0.0)
    obj.save("bars.obj")
    meshes = [{"file": "slab.obj", "material": {"name": "slab", "diffuse": [0.3, 0.3, 0.3], "metallic": 0, "roughness": 0.6}},
              {"file": "bars.obj", "material": {"name": "bars", "diffuse": [0.0, 0.0, 0.0], "emission": [3.0, 3.0, 3.0]}}]
    for k, dispersion in enumerate((0, 1, 3, 6, 12)):
        material = {"name": "glass dispersion %g" % dispersion, "diffuse": [1.0, 1.0, 1.0], "metallic": 0,
                    "roughness": 0, "transmission": 1, "ior": 1.6}
        if dispersion:
            material["dispersion"] = dispersion
        meshes.append({"file": "sphere.obj", "transform": {"translate": [2.4 * (k - 2.0), 0.0, 0.0]}, "material": material})
    write("dispersion.json", to_json({
        "meshes": meshes,
        "environment": {"file": "sky.hdr", "strength": 0.15, "rotation": 30},
        "camera": {"eye": [0.0, 1.2, 10.0], "target": [0.0, 0.0, 0.0], "up": [0.0, 1.0, 0.0], "fovy": 36.0},
        "render": {"size": [720, 300], "max_bounces": 12},
    }) + "\n")
    return obj.triangles


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "globe":
        print("globe %6d triangles" % globe(sys.argv[2]))
        return 0
    os.makedirs(SCENES, exist_ok=True)
    for name, make in (("A boxes", scene_a), ("B room", scene_b), ("C highlow", scene_c), ("D cornell", scene_d),
                       ("E cornell blocks", scene_e), ("F metal rough spheres", scene_f), ("G rough glass", scene_g),
                       ("H layers", scene_h), ("I volume", scene_i),
                       ("J iridescence", scene_j), ("K anisotropy", scene_k), ("L thin walls", scene_l),
                       ("M dispersion", scene_m)):
        print("%-10s %6d triangles" % (name, make()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
