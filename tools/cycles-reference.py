#!/usr/bin/env python3
"""Reference images from Blender's Cycles (Debian `blender`, its bundled glTF importer) for a glTF
scene seen by gpurt's camera (CONTRACT.md), and the comparison of gpurt's image with it.

Needs Blender and numpy: scripts/install-deps.sh --cycles (not installed for ./test.sh: no test runs it; the tests read the EXRs it wrote).

Render (inside Blender):
  blender -b --factory-startup -noaudio --python-exit-code 1 -P tools/cycles-reference.py -- \\
      render SCENE.glb --eye X,Y,Z --target X,Y,Z [--up X,Y,Z] [--fovy DEG] --size WxH --spp N \\
      [--env FILE.hdr --env-strength S --env-rotate DEG] [--bounces N] [--seed S] [--threads N]
      [--half] [--distribution GGX|MULTI_GGX] [--lambert R,G,B] -o OUT.exr [--png OUT.png]
  --bounces N is gpurt's (the longest path in hits); Cycles gets max_bounces N - 1, which counts
  the scatterings after the first hit (max_bounces 0 is direct light only, gpurt's --bounces 1).
  Filter Glossy is 0 (its default 1 blurs glossy lobes after diffuse ones), clamping and
  denoising are off. KHR_materials_volume's absorption is turned into the extension's Beer-Lambert
  (beer_lambert: Blender 3.4's importer absorbs 1 - attenuationColor instead), and
  KHR_materials_clearcoat into the extension's layering (glTF_clearcoat: Blender 3.4's Principled
  coat is Disney's, a quarter as strong, over an undimmed base). --lambert R,G,B replaces every material by a Lambert diffuse of that colour
  (light transport alone, against gpurt's classic Lambert material). The references of
  tests/assets/cycles/ were made with it (README.txt there).
Compare (inside Blender too: it reads the EXRs):
  blender -b --factory-startup -noaudio --python-exit-code 1 -P tools/cycles-reference.py -- \\
      compare GPURT.exr CYCLES.exr [--regions N] [--side-by-side OUT.png]
  prints, for an N x N grid of regions, the mean of each image's luminance there and their ratio;
  --side-by-side writes both (clamped, sRGB) next to each other.

Conventions: gpurt's scene is +Y up, as glTF's; Blender's importer turns it to +Z up, (x, y, z) ->
(x, -z, y), and the camera is placed in those coordinates. The environment: gpurt reads direction
d at u = 0.5 + atan2(d.x, -d.z) / 2 pi; Cycles' equirectangular map reads Blender's direction b at
u = 0.5 + atan2(b.y, -b.x) / 2 pi = 0.5 + atan2(-d.z, -d.x) / 2 pi, a quarter turn further, so
the map is turned by -90 degrees (plus --env-rotate) about Blender's z. Cycles' pixel filter is
narrowed to a box of nearly a point, as gpurt samples pixels uniformly.
"""

import argparse
import math
import sys


def parse_vector(text):
    values = [float(v) for v in text.split(",")]
    if len(values) != 3:
        raise argparse.ArgumentTypeError("expected X,Y,Z: " + text)
    return values


def to_blender(v):
    return (v[0], -v[2], v[1])


def beer_lambert(node):
    """KHR_materials_volume as its specification says, in a Volume Absorption node the importer made.
    Blender 3.4's importer sets Color = attenuationColor c and Density = 1 / attenuationDistance D,
    and Cycles absorbs sigma = (1 - Color) Density: exp(-(1 - c) d / D) over a distance d, where the
    extension says c^(d / D) = exp(ln(c) d / D). Per channel sigma = -ln(c) / D is the same node with
    Density = the largest sigma and Color = 1 - sigma / Density."""
    color, density = node.inputs["Color"].default_value, node.inputs["Density"].default_value
    sigma = [-math.log(max(c, 1e-6)) * density for c in color[:3]]
    largest = max(sigma)
    if largest <= 0.0:
        return
    node.inputs["Density"].default_value = largest
    node.inputs["Color"].default_value = tuple(1.0 - s / largest for s in sigma) + (1.0,)


def glTF_clearcoat(material, principled):
    """KHR_materials_clearcoat as its specification layers it: the coat's GGX lobe weighted by
    clearcoat x Fresnel (ior 1.5) over the base scaled by 1 - clearcoat x Fresnel. Blender 3.4's
    Principled BSDF has Disney's coat instead (Cycles weights it 0.25 x clearcoat and leaves the base
    as it is), so the importer's Clearcoat inputs are moved into a Glossy BSDF (GGX, the same
    roughness mapping) mixed over the Principled BSDF by clearcoat x a Fresnel node (evaluated at the
    coat's normal and the view: the specification's Fresnel at the half vector for the coat, at the
    normal for the base; the same for a smooth coat)."""
    nodes, links = material.node_tree.nodes, material.node_tree.links
    factor, roughness, normal = (principled.inputs[name] for name in
                                 ("Clearcoat", "Clearcoat Roughness", "Clearcoat Normal"))
    if not factor.is_linked and factor.default_value <= 0.0:
        return
    outputs = [link for link in links if link.from_node == principled and link.to_node.type == "OUTPUT_MATERIAL"]
    if not outputs:
        return
    glossy = nodes.new("ShaderNodeBsdfGlossy")
    glossy.distribution = "GGX"
    glossy.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    fresnel = nodes.new("ShaderNodeFresnel")
    fresnel.inputs["IOR"].default_value = 1.5
    weight = nodes.new("ShaderNodeMath")
    weight.operation = "MULTIPLY"
    mix = nodes.new("ShaderNodeMixShader")

    def move(socket, targets):  # the importer's value or link, onto each of targets
        source = socket.links[0].from_socket if socket.is_linked else None
        for target in targets:
            if source is not None:
                links.new(source, target)
            else:
                target.default_value = socket.default_value
        for link in list(socket.links):
            links.remove(link)

    move(factor, [weight.inputs[0]])
    move(roughness, [glossy.inputs["Roughness"]])
    move(normal, [glossy.inputs["Normal"], fresnel.inputs["Normal"]])
    factor.default_value = 0.0
    links.new(fresnel.outputs["Fac"], weight.inputs[1])
    links.new(weight.outputs["Value"], mix.inputs["Fac"])
    links.new(principled.outputs["BSDF"], mix.inputs[1])
    links.new(glossy.outputs["BSDF"], mix.inputs[2])
    for link in outputs:
        surface = link.to_socket
        links.remove(link)
        links.new(mix.outputs["Shader"], surface)


def render(args):
    import bpy
    from mathutils import Matrix, Vector

    import numpy
    # Debian 12's Blender 3.4 glTF importer still says numpy.bool, which numpy 1.24 removed.
    if "bool" not in numpy.__dict__:
        numpy.bool = bool
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=args.scene)
    scene = bpy.context.scene
    width, height = (int(v) for v in args.size.split("x"))

    eye, target, up = Vector(to_blender(args.eye)), Vector(to_blender(args.target)), Vector(to_blender(args.up))
    forward = (target - eye).normalized()
    right = forward.cross(up).normalized()
    true_up = right.cross(forward)
    camera_data = bpy.data.cameras.new("gpurt")
    camera_data.sensor_fit = "VERTICAL"
    camera_data.angle_y = math.radians(args.fovy)
    # gpurt's camera clips nothing; a new Blender camera clips nearer than 0.1 and past 1000 units
    # (a Cornell box of 556 units seen from 800 units away lost its back wall).
    camera_data.clip_start = 1e-4 * (target - eye).length
    camera_data.clip_end = 1e4 * max((target - eye).length, 1.0)
    camera = bpy.data.objects.new("gpurt", camera_data)
    scene.collection.objects.link(camera)
    rotation = Matrix((right, true_up, -forward)).transposed()  # columns: camera x, y, z
    camera.matrix_world = Matrix.Translation(eye) @ rotation.to_4x4()
    scene.camera = camera

    world = bpy.data.worlds.new("gpurt")
    scene.world = world
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    background = nodes["Background"]
    if args.env:
        texture = nodes.new("ShaderNodeTexEnvironment")
        texture.image = bpy.data.images.load(args.env)
        texture.interpolation = "Linear"
        mapping = nodes.new("ShaderNodeMapping")
        coordinates = nodes.new("ShaderNodeTexCoord")
        mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(-90.0 - args.env_rotate))
        links.new(coordinates.outputs["Generated"], mapping.inputs["Vector"])
        links.new(mapping.outputs["Vector"], texture.inputs["Vector"])
        links.new(texture.outputs["Color"], background.inputs["Color"])
        background.inputs["Strength"].default_value = args.env_strength
    else:
        background.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)

    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = args.spp
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    # gpurt's --bounces N is the longest path in hits: next-event estimation at the first N - 1
    # hits, the N-th hit only seen (its emission, or the environment past it). Cycles' max_bounces
    # counts the scatterings after the first hit: max_bounces 0 is direct light only, gpurt's 1.
    cycles_bounces = max(0, args.bounces - 1) if args.cycles_bounces is None else args.cycles_bounces
    scene.cycles.max_bounces = cycles_bounces
    scene.cycles.diffuse_bounces = scene.cycles.glossy_bounces = scene.cycles.transmission_bounces = cycles_bounces
    scene.cycles.sample_clamp_direct = scene.cycles.sample_clamp_indirect = 0.0
    scene.cycles.blur_glossy = 0.0  # Filter Glossy (default 1) blurs glossy lobes after diffuse ones: biased
    scene.cycles.seed = args.seed
    if args.threads:
        scene.render.threads_mode = "FIXED"
        scene.render.threads = args.threads
    for material in bpy.data.materials:
        for node in list(material.node_tree.nodes) if material.node_tree else []:  # glTF_clearcoat adds nodes
            if node.type == "BSDF_PRINCIPLED":
                node.distribution = args.distribution
                glTF_clearcoat(material, node)
            if node.type == "VOLUME_ABSORPTION" and not node.inputs["Color"].is_linked:
                beer_lambert(node)
    if args.lambert:
        # Every material a Lambert Diffuse BSDF (roughness 0) of one colour: light transport without
        # the Principled BSDF's differences from glTF's Appendix B, to compare with gpurt's classic
        # Lambert material (an OBJ without MTL is 0.8 grey).
        lambert = bpy.data.materials.new("lambert")
        lambert.use_nodes = True
        tree = lambert.node_tree
        tree.nodes.clear()
        diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Color"].default_value = tuple(args.lambert) + (1.0,)
        diffuse.inputs["Roughness"].default_value = 0.0
        output = tree.nodes.new("ShaderNodeOutputMaterial")
        tree.links.new(diffuse.outputs["BSDF"], output.inputs["Surface"])
        for obj in scene.objects:
            if obj.type == "MESH":
                obj.data.materials.clear()
                obj.data.materials.append(lambert)
                for polygon in obj.data.polygons:
                    polygon.material_index = 0
    scene.cycles.filter_width = 0.01
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_mode = "RGB"
    scene.render.image_settings.color_depth = "16" if args.half else "32"
    scene.render.image_settings.exr_codec = "ZIP"
    scene.render.filepath = args.output
    bpy.ops.render.render(write_still=True)
    if args.png:
        scene.render.image_settings.file_format = "PNG"
        scene.render.image_settings.color_depth = "8"
        bpy.data.images["Render Result"].save_render(args.png)


def read_exr(path):
    import bpy
    import numpy

    image = bpy.data.images.load(path)
    image.colorspace_settings.name = "Non-Color"
    width, height = image.size
    pixels = numpy.array(image.pixels[:], dtype=numpy.float64).reshape(height, width, 4)[::-1, :, :3]
    return pixels


def compare(args):
    import bpy
    import numpy

    a, b = read_exr(args.gpurt), read_exr(args.cycles)
    if a.shape != b.shape:
        sys.exit("compare: %s is %dx%d, %s %dx%d" % (args.gpurt, a.shape[1], a.shape[0], args.cycles, b.shape[1], b.shape[0]))
    weights = numpy.array([0.2126, 0.7152, 0.0722])
    la, lb = a @ weights, b @ weights
    n = args.regions
    height, width = la.shape
    print("region  gpurt    cycles   gpurt/cycles")
    ratios = []
    for j in range(n):
        for i in range(n):
            ys, xs = slice(j * height // n, (j + 1) * height // n), slice(i * width // n, (i + 1) * width // n)
            ma, mb = la[ys, xs].mean(), lb[ys, xs].mean()
            ratio = ma / mb if mb > 1e-6 else float("nan")
            ratios.append(ratio)
            print("%d,%d     %.4f   %.4f   %.3f" % (i, j, ma, mb, ratio))
    print("whole   %.4f   %.4f   %.3f" % (la.mean(), lb.mean(), la.mean() / max(lb.mean(), 1e-9)))
    if args.side_by_side:
        def srgb(x):
            x = numpy.clip(x, 0.0, 1.0)
            return numpy.where(x <= 0.0031308, 12.92 * x, 1.055 * numpy.power(x, 1.0 / 2.4) - 0.055)
        both = numpy.concatenate([srgb(a), numpy.ones((height, 4, 3)), srgb(b)], axis=1)
        out = bpy.data.images.new("side", both.shape[1], both.shape[0], alpha=False)
        out.colorspace_settings.name = "Non-Color"
        rgba = numpy.concatenate([both, numpy.ones(both.shape[:2] + (1,))], axis=2)[::-1]
        out.pixels[:] = rgba.ravel()
        out.filepath_raw = args.side_by_side
        out.file_format = "PNG"
        out.save()


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog="cycles-reference.py")
    commands = parser.add_subparsers(dest="command", required=True)
    r = commands.add_parser("render")
    r.add_argument("scene")
    r.add_argument("--eye", type=parse_vector, required=True)
    r.add_argument("--target", type=parse_vector, required=True)
    r.add_argument("--up", type=parse_vector, default=[0.0, 1.0, 0.0])
    r.add_argument("--fovy", type=float, default=45.0)
    r.add_argument("--size", default="320x240")
    r.add_argument("--spp", type=int, default=64)
    r.add_argument("--bounces", type=int, default=4, help="gpurt's --bounces (Cycles gets max_bounces N - 1)")
    r.add_argument("--cycles-bounces", type=int, help="Cycles' max_bounces itself (overrides --bounces)")
    r.add_argument("--distribution", default="GGX", choices=["GGX", "MULTI_GGX"],
                   help="the Principled BSDFs' microfacet distribution (glTF's is GGX, single scattering)")
    r.add_argument("--lambert", type=parse_vector, metavar="R,G,B",
                   help="replace every material by a Lambert diffuse of this linear colour")
    r.add_argument("--seed", type=int, default=0)
    r.add_argument("--threads", type=int, default=0, help="render threads (default: all)")
    r.add_argument("--half", action="store_true", help="write half-float RGB (else 32-bit float)")
    r.add_argument("--env")
    r.add_argument("--env-strength", type=float, default=1.0)
    r.add_argument("--env-rotate", type=float, default=0.0)
    r.add_argument("-o", "--output", required=True)
    r.add_argument("--png")
    c = commands.add_parser("compare")
    c.add_argument("gpurt")
    c.add_argument("cycles")
    c.add_argument("--regions", type=int, default=4)
    c.add_argument("--side-by-side")
    args = parser.parse_args(argv)
    if args.command == "render":
        render(args)
    else:
        compare(args)


if __name__ == "__main__":
    main()
