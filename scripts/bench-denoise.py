#!/usr/bin/env python3
"""Issue 35's tables (docs/PERFORMANCE.md, "The denoiser"): the denoiser's quality, its cost and the
time to a clean picture, and README's side-by-side crops.

  python3 scripts/bench-denoise.py [--size 256] [--reference-spp 4096] [--work out/bench-denoise]
                                   [--crops docs/images]

For each scene (the Cornell blocks; the bunny under the HDR sky; pbr_spheres.glb, textured and
normal-mapped, under the same sky): a reference of --reference-spp samples (gl, seed 99, so that its
noise is independent of the renders measured), then raw renders of 16, 128 and 1024 samples and
the 16-sample render denoised (render --denoise; its picture as gpurt denoise writes it from the
render's AOVs, linear). relMSE as scripts/bench-sampling.py: mean over pixels and channels of
(x - ref)^2 / (ref^2 + 0.01). Cost: the denoiser's time in a 512x512 render of each scene against
the time of its samples (4 samples a pixel). Time to a clean picture: `render --spp 16 --denoise`
of the Cornell blocks (--size, 8 bounces) against raw uniform sampling with this round's starting
settings (--sampler stratified --clamp-indirect 0) at growing sample counts until its error is as
low. Needs build/gpurt; run it on a quiet machine (a second process slows llvmpipe).
"""
import argparse
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from pfm import read_pfm, rel_mse  # noqa: E402
import png  # noqa: E402

G = os.path.join(ROOT, "build", "gpurt")
SKY = ["--env", "scenes/sky.hdr"]
SCENES = {
    "cornell blocks": ["scenes/cornell_blocks.json"],
    "bunny under the sky": ["../shared/models/bunny.obj", *SKY],
    "pbr spheres under the sky": ["tests/assets/cycles/pbr_spheres.glb", *SKY, "--eye", "0,0.4,3.6",
                                  "--target", "0,-0.1,0", "--fovy", "40"],
}
AOVS = ("albedo", "shading_normal", "depth", "variance")


def render(scene, work, name, size, options, denoise=False):
    """(linear colour values, stats, png path): the denoised picture's values with `denoise`."""
    color = os.path.join(work, name + ".pfm")
    png_path = os.path.join(work, name + ".png")
    cmd = [G, "render", *SCENES[scene], "-o", png_path, "--size", f"{size}x{size}", "--integrator", "path",
           "--aov", "color=" + color, "--stats=json", *options]
    if denoise:
        cmd += ["--denoise"] + [f"--aov={a}={os.path.join(work, name + '_' + a + '.pfm')}" for a in AOVS]
    out = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True).stdout
    stats = json.loads(out.strip().splitlines()[-1])
    if not denoise:
        return read_pfm(color)[3], stats, png_path
    denoised = os.path.join(work, name + "_denoised.pfm")
    aov = {a: os.path.join(work, name + "_" + a + ".pfm") for a in AOVS}
    subprocess.run([G, "denoise", color, "--albedo", aov["albedo"], "--normal", aov["shading_normal"], "--depth",
                    aov["depth"], "--variance", aov["variance"], "-o", denoised], cwd=ROOT, check=True)
    return read_pfm(denoised)[3], stats, png_path


def sample_ms(stats):
    """The integrator's passes' time (ms) in a render."""
    return sum(p["ms"] for name, p in stats["passes"].items() if not name.startswith("denoise"))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--reference-spp", type=int, default=4096)
    ap.add_argument("--work", default=os.path.join(ROOT, "out", "bench-denoise"))
    ap.add_argument("--crops", default="", help="write README's crops (raw 16, denoised 16, raw 1024) here")
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--reuse-reference", action="store_true", help="keep the references of an earlier run in --work")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    size = args.size
    print(f"### Quality at {size}x{size} (relMSE against {args.reference_spp} samples)\n")
    print("| scene | raw 16 | denoised 16 | raw 128 | raw 1024 | denoised 16 / raw 128 | denoise ms |")
    print("|---|---|---|---|---|---|---|")
    for scene in args.scenes.split(","):
        key = scene.replace(" ", "_")
        ref_file = os.path.join(args.work, key + "_ref.pfm")
        if args.reuse_reference and os.path.exists(ref_file):
            ref = read_pfm(ref_file)[3]
        else:
            ref = render(scene, args.work, key + "_ref", size, ["--spp", str(args.reference_spp), "--seed", "99"])[0]
        raw16, _, raw16_png = render(scene, args.work, key + "_raw16", size, ["--spp", "16"])
        den16, st, den16_png = render(scene, args.work, key + "_den16", size, ["--spp", "16"], denoise=True)
        raw128 = render(scene, args.work, key + "_raw128", size, ["--spp", "128"])[0]
        raw1024, _, raw1024_png = render(scene, args.work, key + "_raw1024", size, ["--spp", "1024"])
        e = [rel_mse(x, ref) for x in (raw16, den16, raw128, raw1024)]
        print(f"| {scene} | {e[0]:.2e} | {e[1]:.2e} | {e[2]:.2e} | {e[3]:.2e} | {e[1] / e[2]:.2f} "
              f"| {st['denoise']['ms']:.0f} |")
        sys.stdout.flush()
        if args.crops:
            w = size // 2
            pictures = [png.crop(png.read_png(p), size // 4, size // 4, w, w) for p in (raw16_png, den16_png, raw1024_png)]
            out = os.path.join(args.crops, f"denoise_{key}.png")
            png.write_png(out, *png.side_by_side(pictures))
    print("\n### Cost at 512x512: the denoiser against 4 samples a pixel\n")
    print("| scene | denoise (ms) | 4 samples (ms) | ratio |")
    print("|---|---|---|---|")
    for scene in args.scenes.split(","):
        key = scene.replace(" ", "_")
        st = render(scene, args.work, key + "_cost", 512, ["--spp", "4"], denoise=True)[1]
        print(f"| {scene} | {st['denoise']['ms']:.0f} | {sample_ms(st):.0f} | {st['denoise']['ms'] / sample_ms(st):.2f} |")
        sys.stdout.flush()
    scene = "cornell blocks"
    key = scene.replace(" ", "_")
    ref = read_pfm(os.path.join(args.work, key + "_ref.pfm"))[3]
    print(f"\n### Time to a clean picture: {scene}, {size}x{size}, 8 bounces\n")
    print("| render | relMSE | wall time (s) |")
    print("|---|---|---|")
    img, st, _ = render(scene, args.work, key + "_clean", size, ["--spp", "16", "--bounces", "8"], denoise=True)
    target, fast = rel_mse(img, ref), st["total_ms"] / 1e3
    print(f"| --spp 16 --denoise | {target:.2e} | {fast:.2f} |")
    spp = 64
    while spp <= 8192:
        img, st, _ = render(scene, args.work, f"{key}_uniform{spp}", size,
                            ["--spp", str(spp), "--bounces", "8", "--sampler", "stratified", "--clamp-indirect", "0"])
        e, t = rel_mse(img, ref), st["total_ms"] / 1e3
        print(f"| --spp {spp} --sampler stratified --clamp-indirect 0 | {e:.2e} | {t:.2f} ({t / fast:.1f}x) |")
        sys.stdout.flush()
        if e <= target:
            break
        spp *= 2


if __name__ == "__main__":
    main()
