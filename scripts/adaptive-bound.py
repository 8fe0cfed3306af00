#!/usr/bin/env python3
"""The most adaptive sampling could gain on a scene (docs/PERFORMANCE.md, "Samplers and adaptive
sampling", issue 34): the efficiency (1 / (relMSE x seconds)) of the best allocation of samples to
pixels, computed from each pixel's measured variance and cost, against uniform sampling.

  /usr/bin/python3 scripts/adaptive-bound.py [--size 128] [--spp 1024] [--work out/adaptive-bound]

Needs numpy and build/gpurt; run it on a quiet machine. For each scene (the Cornell blocks and the
bunny under the HDR sky, as scripts/bench-sampling.py):
- one uniform render of --spp samples (gl backend, sobol) with the color, variance and depth AOVs:
  each pixel's variance of one sample, e_i = sum over channels of variance x spp / (mean^2 + 0.01) / 3,
  is what one sample adds to relMSE (the benchmark's metric) in that pixel, divided by the samples;
- each pixel's cost of one sample: a render of the same scene with the camera turned to the empty
  sky gives a missed pixel's (the integrator's pass time over its pixel samples, a pass's fixed
  cost included, which makes misses look dearer and the bound more generous); the uniform render's
  pass time then gives the mean cost of a pixel that hits something.
With n_i samples in pixel i, relMSE = mean(e_i / n_i) and the time is sum(n_i c_i). Uniform
sampling's efficiency is 1 / (mean(e) x sum(c)); the best any rule can do, knowing every e_i and c_i
exactly, takes n_i proportional to sqrt(e_i / c_i) (Lagrange), for 1 / (sum(sqrt(e_i c_i))^2 / P).
"At a budget" holds the time to that of B uniform samples and every pixel to --min-spp M at least and
--spp S at most, as an adaptive render must. "Cycles' criterion" allocates as a pixel that stops
once Cycles' error (the channels' standard deviations summed over the square root of the channels'
mean, common/adaptive.h) is below a threshold would with that error known exactly: n_i proportional
to (sum sigma / sqrt(sum mean))^2, clamped to [M, S].
"""
import argparse
import json
import os
import subprocess
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from pfm import read_pfm  # noqa: E402
G = os.path.join(ROOT, "build", "gpurt")
SCENES = {
    "cornell blocks": ["scenes/cornell_blocks.json"],
    "bunny under the sky": ["../shared/models/bunny.obj", "--env", "scenes/sky.hdr"],
}
# (mean spp, --min-spp, --spp) of the adaptive renders in PERFORMANCE.md's "--spp 256" table:
# thresholds 0.02 and 0.01 (Cycles' default --min-spp 52 and 64).
BUDGETS = {
    "cornell blocks": [(101, 52, 256), (193, 64, 256)],
    "bunny under the sky": [(60, 52, 256), (104, 64, 256)],
}
AWAY = ["--eye", "1000,1000,1000", "--target", "2000,2000,2000"]


def image(path):
    w, h, c, v = read_pfm(path)
    return np.array(v, dtype=np.float64).reshape(h, w, c)


def render(scene, work, name, size, spp, extra, aovs):
    cmd = [G, "render", *SCENES[scene], "-o", os.path.join(work, name + ".png"), "--size", f"{size}x{size}",
           "--integrator", "path", "--spp", str(spp), "--stats=json", "--quiet", *extra]
    for aov in aovs:
        cmd += ["--aov", f"{aov}={os.path.join(work, name + '_' + aov + '.pfm')}"]
    out = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True).stdout
    stats = json.loads(out.strip().splitlines()[-1])
    ms = sum(p["ms"] for n, p in stats["passes"].items() if n.startswith("path"))
    return 1e3 * ms / (spp * size * size)  # us a pixel sample


def allocate(weight, cost, budget, least, most):
    """n_i = clamp(lam x weight_i, least, most) with sum(n c) = budget (bisection on lam)."""
    lo, hi = 1e-12, 1e12
    for _ in range(200):
        lam = np.sqrt(lo * hi)
        if (np.clip(lam * weight, least, most) * cost).sum() > budget:
            hi = lam
        else:
            lo = lam
    return np.clip(lo * weight, least, most)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--work", default=os.path.join(ROOT, "out", "adaptive-bound"))
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    print("| scene | cost a sample, miss / hit (us) | hits | best rule, unbounded | budget: mean spp, --min-spp | best rule | Cycles' criterion, exact | the same, equal costs: best / Cycles' |")
    print("|---|---|---|---|---|---|---|---|")
    for scene in SCENES:
        key = scene.replace(" ", "_")
        hit_mean = render(scene, args.work, key, args.size, args.spp, [], ["color", "variance", "depth"])
        miss = render(scene, args.work, key + "_away", args.size, 64, AWAY, [])
        mean = image(os.path.join(args.work, key + "_color.pfm"))
        var = image(os.path.join(args.work, key + "_variance.pfm")) * args.spp
        depth = image(os.path.join(args.work, key + "_depth.pfm"))[..., 0]
        missed = ~np.isfinite(depth) | (depth <= 0) | (depth > 1e20)
        hits = 1.0 - missed.mean()
        hit = (hit_mean - (1.0 - hits) * miss) / hits
        cost = np.where(missed, miss, hit)
        e = (var / (mean ** 2 + 0.01)).sum(axis=2) / 3.0
        cycles = (np.sqrt(var).sum(axis=2) / (1e-4 + np.sqrt(np.maximum(mean.sum(axis=2), 0.0)))) ** 2
        unbounded = e.mean() * cost.sum() / (np.sqrt(e * cost).sum() ** 2 / e.size)
        for spp, least, most in BUDGETS[scene]:
            gains = []
            for c in (cost, np.ones_like(cost)):
                uniform = e.mean() / spp
                best = allocate(np.sqrt(e / c), c, spp * c.sum(), least, most)
                crit = allocate(cycles, c, spp * c.sum(), least, most)
                gains.append((uniform / (e / best).mean(), uniform / (e / crit).mean()))
            print(f"| {scene} | {miss:.2f} / {hit:.2f} | {100 * hits:.0f}% | {unbounded:.2f}x | {spp}, {least} | "
                  f"{gains[0][0]:.2f}x | {gains[0][1]:.2f}x | {gains[1][0]:.2f}x / {gains[1][1]:.2f}x |")


if __name__ == "__main__":
    main()
