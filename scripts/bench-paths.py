#!/usr/bin/python3
"""The path integrator's speed (docs/PERFORMANCE.md): samples per second on the Cornell box (glass
sphere, mirror block, 8 bounces), the classic Cornell box with two blocks (2 bounces, the bounce
count of GLSL-PathTracer's anchor) and the bunny under its sky, on the gl and cpu backends, back to
back and alternating; then, from the gl runs, each kernel's share of the pass time and the live
paths after each round.

  scripts/bench-paths.py [--runs N] [--size WxH]

samples/s is pixel samples (width x height x spp) over gpurt's --stats=json total_ms (the best of
the runs); spp/s is that over the pixels. Needs build/gpurt (./run.sh builds it) and
../shared/models. Standard library only.
"""

import json
import os
import subprocess
import sys
import tempfile

from benchrender import GPURT, ROOT, parse_args

# (label, short name for the columns, scene, options)
CASES = [
    ("Cornell box (glass, mirror), 8 bounces, --spp 4", "Cornell 8", "scenes/cornell.json", ["--spp", "4", "--bounces", "8"]),
    ("the same, --mask-paths", "masked", "scenes/cornell.json", ["--spp", "4", "--bounces", "8", "--mask-paths"]),
    ("Cornell blocks, 2 bounces, --spp 8", "blocks 2", "scenes/cornell_blocks.json", ["--spp", "8", "--bounces", "2"]),
    ("Cornell blocks, 8 bounces, --spp 4", "blocks 8", "scenes/cornell_blocks.json", ["--spp", "4", "--bounces", "8"]),
    ("bunny (lit by the sky), 8 bounces, --spp 4", "bunny 8", "../shared/models/bunny.obj", ["--spp", "4", "--bounces", "8"]),
]


def run(scene, backend, size, extra):
    command = [GPURT, "render", os.path.join(ROOT, scene), "-o", os.path.join(tempfile.gettempdir(), "bench-paths.png"),
               "--size", size, "--backend", backend, "--integrator", "path", "--stats=json"] + extra
    return json.loads(subprocess.run(command, check=True, capture_output=True, text=True).stdout)


def main():
    args = parse_args(__doc__, "bench-paths")
    if args is None:
        return 2
    best = {}
    for _ in range(args.runs):
        for label, _, scene, extra in CASES:
            for backend in ("gl", "cpu"):
                if backend == "cpu" and "--mask-paths" in extra:
                    continue  # a gl option
                stats = run(scene, backend, args.size, extra)
                key = (label, backend)
                if key not in best or stats["total_ms"] < best[key]["total_ms"]:
                    best[key] = stats
    pixels = None
    print("| path integrator at %s (best of %d runs) | gl samples/s | gl spp/s | cpu samples/s | cpu spp/s |" % (args.size, args.runs))
    print("|---|---:|---:|---:|---:|")
    for label, _, _, _ in CASES:
        cells = []
        for backend in ("gl", "cpu"):
            s = best.get((label, backend))
            if s is None:
                cells += ["", ""]
                continue
            pixels = s["width"] * s["height"]
            cells += ["%.3g M" % (s["samples_per_s"] / 1e6), "%.2f" % (s["samples_per_s"] / pixels)]
        print("| %s | %s |" % (label, " | ".join(cells)))
    print()
    print("| gl, kernel share of the pass time | %s |" % " | ".join(short for _, short, _, _ in CASES))
    print("|---|%s" % ("---:|" * len(CASES)))
    kernels = sorted({k for label, _, _, _ in CASES for k in best[(label, "gl")]["passes"]})
    for k in kernels:
        row = []
        for label, _, _, _ in CASES:
            passes = best[(label, "gl")]["passes"]
            total = sum(p["ms"] for p in passes.values())
            row.append("%.0f%%" % (100.0 * passes[k]["ms"] / total) if k in passes else "")
        if any(row):
            print("| %s | %s |" % (k, " | ".join(row)))
    print()
    print("| gl, live paths after each round (all samples) | paths per bounce |")
    print("|---|---|")
    for label, _, _, _ in CASES:
        print("| %s | %s |" % (label, " ".join(str(n) for n in best[(label, "gl")]["paths_per_bounce"])))
    return 0


if __name__ == "__main__":
    sys.exit(main())
