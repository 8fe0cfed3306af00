#!/usr/bin/python3
"""The integrators' kernels (issue 24): the wavefront chain (--kernel fused) against the megakernels
(--kernel megakernel, and its --megakernel-bounces), and the cpu backend, on whole renders, back to
back and alternating, --runs times each. Prints a markdown table of the best total_ms (gpurt's
--stats=json: the render, without loading the scene) and the best wall clock of the command.

  scripts/bench-kernels.py [--runs 3] [--cases whitted,path,bounces] [--dragon]

Needs build/gpurt (./run.sh builds it) and ../shared/models; --dragon needs out/models/dragon.ply
(scripts/fetch-dragon.sh). Standard library only.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

from benchrender import GPURT, ROOT

# (label, scene, options) of each case; each runs with every variant of VARIANTS.
WHITTED = [
    ("bunny, Whitted, 1024x1024, 1 sample", "../shared/models/bunny.obj", ["--size", "1024x1024"]),
    ("bunny, Whitted, 512x512, --spp 16", "../shared/models/bunny.obj", ["--size", "512x512", "--spp", "16"]),
    ("Cornell box (glass, mirror), Whitted, 512x512, --spp 4", "scenes/cornell.json", ["--size", "512x512", "--spp", "4"]),
]
DRAGON = [("dragon, Whitted, 1024x1024, 1 sample", "out/models/dragon.ply", ["--size", "1024x1024"])]
PATH = [
    ("Cornell blocks, path, 2 bounces, 512x512, --spp 8", "scenes/cornell_blocks.json",
     ["--size", "512x512", "--integrator", "path", "--bounces", "2", "--spp", "8"]),
    ("Cornell blocks, path, 8 bounces, 512x512, --spp 4", "scenes/cornell_blocks.json",
     ["--size", "512x512", "--integrator", "path", "--bounces", "8", "--spp", "4"]),
    ("Cornell box (glass, mirror), path, 8 bounces, 512x512, --spp 4", "scenes/cornell.json",
     ["--size", "512x512", "--integrator", "path", "--bounces", "8", "--spp", "4"]),
    ("bunny under the default light, path, 8 bounces, 512x512, --spp 4", "../shared/models/bunny.obj",
     ["--size", "512x512", "--integrator", "path", "--bounces", "8", "--spp", "4"]),
]
VARIANTS = [("gl wavefront", ["--kernel", "fused"]), ("gl megakernel", ["--kernel", "megakernel"]),
            ("cpu", ["--backend", "cpu"])]
BOUNCES = [("megakernel, %d a pass" % n, ["--kernel", "megakernel", "--megakernel-bounces", str(n)]) for n in (1, 2, 3, 4)]


def run(scene, options):
    out = os.path.join(tempfile.gettempdir(), "bench-kernels.png")
    command = [GPURT, "render", os.path.join(ROOT, scene), "-o", out, "--stats=json"] + options
    start = time.perf_counter()
    result = subprocess.run(command, check=True, capture_output=True, text=True)
    wall = time.perf_counter() - start
    return json.loads(result.stdout)["total_ms"], wall * 1000.0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--cases", default="whitted,path")
    parser.add_argument("--dragon", action="store_true")
    args = parser.parse_args()
    if not os.path.exists(GPURT):
        print("bench-kernels: build/gpurt is missing (run ./run.sh)", file=sys.stderr)
        return 2
    kinds = args.cases.split(",")
    cases = []
    if "whitted" in kinds:
        cases += [(c, VARIANTS) for c in WHITTED + (DRAGON if args.dragon else [])]
    if "path" in kinds:
        cases += [(c, VARIANTS) for c in PATH]
    if "bounces" in kinds:
        cases += [(c, VARIANTS[:2] + BOUNCES) for c in PATH[:2]]
    print("| render | variant | total_ms (best of %d) | wall ms (best) | / gl wavefront |" % args.runs)
    print("|---|---|---:|---:|---:|")
    for (label, scene, options), variants in cases:
        best = {name: (float("inf"), float("inf")) for name, _ in variants}
        for _ in range(args.runs):  # alternating, so that a busy moment hits every variant alike
            for name, extra in variants:
                total, wall = run(scene, options + extra)
                best[name] = (min(best[name][0], total), min(best[name][1], wall))
        base = best[variants[0][0]][0]
        for name, _ in variants:
            total, wall = best[name]
            print("| %s | %s | %.0f | %.0f | %.2fx |" % (label, name, total, wall, base / total))
        sys.stdout.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main())
