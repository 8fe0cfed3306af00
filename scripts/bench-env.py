#!/usr/bin/python3
"""The environment light's cost and gain (docs/PERFORMANCE.md): the bunny under the procedural
sky scenes/sky.hdr (scripts/make-sky.py: a small sun), path traced with the environment sampled by
its luminance and weighed by MIS (--env-sampling mis, the default) and with BSDF sampling alone
(--env-sampling bsdf), on the gl and cpu backends, alternating; samples/s from --stats=json (the
best of the runs). Then the noise at equal samples: each mode's RMS error of the linear colour
(--aov color) against a long render (MIS, --ref-spp samples), over the pixels.

  scripts/bench-env.py [--runs N] [--size WxH] [--spp N] [--ref-spp N]

Needs build/gpurt and ../shared/models. Standard library only.
"""

import json
import math
import os
import struct
import subprocess
import sys
import tempfile

import argparse

from benchrender import GPURT, ROOT

SCENE = os.path.join(ROOT, "../shared/models/bunny.obj")
SKY = os.path.join(ROOT, "scenes/sky.hdr")


def render(backend, size, spp, sampling, color=None):
    command = [GPURT, "render", SCENE, "-o", os.path.join(tempfile.gettempdir(), "bench-env.png"), "--size", size,
               "--backend", backend, "--integrator", "path", "--spp", str(spp), "--env", SKY, "--env-sampling",
               sampling, "--stats=json"] + (["--aov", "color=" + color] if color else [])
    return json.loads(subprocess.run(command, check=True, capture_output=True, text=True).stdout)


def read_pfm(path):
    data = open(path, "rb").read()
    parts = data.split(b"\n", 3)
    width, height = (int(v) for v in parts[1].split())
    little = float(parts[2]) < 0
    n = width * height * 3
    return struct.unpack(("<" if little else ">") + "f" * n, parts[3][:4 * n])


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--size", default="256x256")
    parser.add_argument("--spp", type=int, default=16)
    parser.add_argument("--ref-spp", type=int, default=256)
    args = parser.parse_args()
    if not os.path.exists(GPURT):
        print("bench-env: build/gpurt is missing (run ./run.sh)", file=sys.stderr)
        return 2
    spp, ref_spp = args.spp, args.ref_spp
    best = {}
    for _ in range(args.runs):
        for sampling in ("mis", "bsdf"):
            for backend in ("gl", "cpu"):
                s = render(backend, args.size, spp, sampling)
                key = (sampling, backend)
                if key not in best or s["total_ms"] < best[key]["total_ms"]:
                    best[key] = s
    print("| bunny under scenes/sky.hdr, %s, --spp %d, 8 bounces (best of %d) | gl samples/s | cpu samples/s |" % (args.size, spp, args.runs))
    print("|---|---:|---:|")
    for sampling, label in (("mis", "environment sampled, MIS (default)"), ("bsdf", "BSDF sampling only (--env-sampling bsdf)")):
        print("| %s | %.3g M | %.3g M |" % (label, best[(sampling, "gl")]["samples_per_s"] / 1e6, best[(sampling, "cpu")]["samples_per_s"] / 1e6))
    with tempfile.TemporaryDirectory() as tmp:
        ref = os.path.join(tmp, "ref.pfm")
        render("gl", args.size, ref_spp, "mis", ref)
        reference = read_pfm(ref)
        print()
        print("| RMS error of the colour at --spp %d against --spp %d (gl) | RMS error |" % (spp, ref_spp))
        print("|---|---:|")
        for sampling in ("mis", "bsdf"):
            out = os.path.join(tmp, sampling + ".pfm")
            render("gl", args.size, spp, sampling, out)
            values = read_pfm(out)
            rms = math.sqrt(sum((a - b) ** 2 for a, b in zip(values, reference)) / len(values))
            print("| %s | %.4f |" % (sampling, rms))
    return 0


if __name__ == "__main__":
    sys.exit(main())
