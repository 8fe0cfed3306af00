#!/usr/bin/env python3
"""Issue 34's speed table (docs/PERFORMANCE.md, "Samplers and adaptive sampling"): error and wall time
of the samplers and of adaptive sampling, on the Cornell blocks and the bunny under the HDR sky.

  python3 scripts/bench-sampling.py [--size 128] [--reference-spp 4096] [--work out/bench-sampling]

For each scene: a reference of --reference-spp samples (cpu backend, seed 99, so its noise is
independent of the renders measured); then, on the gl backend (the default kernel), each sampler at
16, 64 and 256 samples with 1 and 8 bounces, and adaptive sampling at thresholds 0.05, 0.02 and
0.01 (--spp 1024; --max-spp, --thresholds) against uniform sobol sampling of the same mean samples a pixel. The error is
relMSE: the mean over pixels and channels of (x - ref)^2 / (ref^2 + 0.01); the time is gpurt's
total_ms (load, grid, context and render). Efficiency = 1 / (relMSE x seconds). Prints Markdown.
Needs build/gpurt; run it on a quiet machine (a second process slows llvmpipe).
"""
import argparse
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from pfm import read_pfm, rel_mse  # noqa: E402
G = os.path.join(ROOT, "build", "gpurt")
SCENES = {
    "cornell blocks": ["scenes/cornell_blocks.json"],
    "bunny under the sky": ["../shared/models/bunny.obj", "--env", "scenes/sky.hdr"],
}


def render(scene, work, name, size, options):
    color = os.path.join(work, name + ".pfm")
    cmd = [G, "render", *SCENES[scene], "-o", os.path.join(work, name + ".png"), "--size", f"{size}x{size}",
           "--integrator", "path", "--aov", "color=" + color, "--stats=json", *options]
    out = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True).stdout
    stats = json.loads(out.strip().splitlines()[-1])
    return read_pfm(color)[3], stats


def per_sample_us(stats):
    """Microseconds a pixel sample in the integrator's sample passes (the camera pass of the path
    megakernel, or the wavefront chain's raygen): masked passes cost in proportion to the active
    pixels when this is the same with and without adaptive sampling."""
    passes = stats["passes"]
    ms = sum(p["ms"] for name, p in passes.items() if name not in ("converge", "mask:active"))
    return 1e3 * ms / max(1, stats["samples"])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--reference-spp", type=int, default=4096)
    ap.add_argument("--work", default=os.path.join(ROOT, "out", "bench-sampling"))
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--max-spp", type=int, default=1024, help="--spp of the adaptive renders")
    ap.add_argument("--thresholds", default="0.05,0.02,0.01")
    ap.add_argument("--adaptive-only", action="store_true", help="skip the samplers' tables and the 1-bounce reference")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    for scene in args.scenes.split(","):
        key = scene.replace(" ", "_")
        for bounces in ((8,) if args.adaptive_only else (8, 1)):
            ref_name = f"{key}_ref_b{bounces}"
            ref, stats = render(scene, args.work, ref_name, args.size,
                                ["--backend", "cpu", "--spp", str(args.reference_spp), "--seed", "99",
                                 "--bounces", str(bounces)])
            print(f"\n### {scene}, {bounces} bounce{'s' if bounces > 1 else ''}, {args.size}x{args.size} "
                  f"(reference: {args.reference_spp} spp, cpu, {stats['total_ms'] / 1e3:.0f} s)\n")
            if not args.adaptive_only:
                print("| sampler | spp | relMSE | time (s) |")
                print("|---|---|---|---|")
            for spp in (() if args.adaptive_only else (16, 64, 256)):
                for sampler in ("random", "stratified", "sobol"):
                    img, st = render(scene, args.work, f"{key}_{sampler}_{spp}_b{bounces}", args.size,
                                     ["--sampler", sampler, "--spp", str(spp), "--bounces", str(bounces)])
                    print(f"| {sampler} | {spp} | {rel_mse(img, ref):.3e} | {st['total_ms'] / 1e3:.2f} |")
            sys.stdout.flush()
            if bounces != 8:
                continue
            print(f"\n#### adaptive sampling against uniform sobol of the same mean spp ({scene})\n")
            print("| threshold | mean spp | relMSE | time (s) | uniform spp | relMSE | time (s) | efficiency gain "
                  "| us a pixel sample, adaptive / uniform |")
            print("|---|---|---|---|---|---|---|---|---|")
            # Warm-up: the first adaptive render of a scene compiles the kernel of its later rounds
            # (the path megakernel over the packed list of active pixels), about a second with
            # Mesa's shader cache cold, which would fall on the first threshold's row.
            render(scene, args.work, f"{key}_warmup", args.size,
                   ["--spp", "32", "--min-spp", "16", "--noise-threshold", "0.05", "--bounces", "8"])
            for t in args.thresholds.split(","):
                img, st = render(scene, args.work, f"{key}_adaptive_{t}", args.size,
                                 ["--spp", str(args.max_spp), "--noise-threshold", t, "--bounces", "8"])
                mean_spp = st["mean_spp"]
                uspp = max(1, round(mean_spp))
                uimg, ust = render(scene, args.work, f"{key}_uniform_{uspp}", args.size,
                                   ["--spp", str(uspp), "--bounces", "8"])
                e, ue = rel_mse(img, ref), rel_mse(uimg, ref)
                ts, uts = st["total_ms"] / 1e3, ust["total_ms"] / 1e3
                gain = (1.0 / (e * ts)) / (1.0 / (ue * uts))
                rounds = " ".join(f"{r['samples']}:{r['active']}" for r in st["adaptive"][:6])
                cost = per_sample_us(st), per_sample_us(ust)
                print(f"| {t} | {mean_spp:.1f} | {e:.3e} | {ts:.2f} | {uspp} | {ue:.3e} | {uts:.2f} | {gain:.2f}x "
                      f"| {cost[0]:.2f} / {cost[1]:.2f} |")
                print(f"<!-- active pixels after the first rounds: {rounds} -->")
                sys.stdout.flush()


if __name__ == "__main__":
    main()
