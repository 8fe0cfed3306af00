#!/usr/bin/python3
"""The whole render, as a user times it (issue 16): `gpurt render MODEL -o OUT.png --size WxH` on
the gl and cpu backends, alternating, --runs times each; wall clock from the shell's point of view
(process start to exit). Then one run of each with --stats=json for the phase breakdown and the
time in kernel passes (gl). Prints a markdown table. Standard library only.

  scripts/bench-render.py [--runs 3] [--size 1024x1024] [MODEL...]
  (default models: ../shared/models/bunny.obj and out/models/dragon.ply when fetched)
"""

import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import benchrender


def wall(cmd):
    start = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def main():
    args = benchrender.parse_args(__doc__, "bench-render", models=True, size="1024x1024")
    if args is None:
        return 2
    models = args.models or [m for m in (os.path.join(benchrender.ROOT, "..", "shared", "models", "bunny.obj"),
                                         os.path.join(benchrender.ROOT, "out", "models", "dragon.ply"))
                             if os.path.exists(m)]
    out = tempfile.mkdtemp(prefix="gpurt-bench-render-")
    png = os.path.join(out, "r.png")
    print("| model | backend | wall s (min, median of %d) | total_ms | kernel passes ms | outside passes | phases_ms |" % args.runs)
    print("|---|---|---:|---:|---:|---:|---|")
    for model in models:
        base = [benchrender.GPURT, "render", model, "-o", png, "--size", args.size]
        times = {"gl": [], "cpu": []}
        for _ in range(args.runs):
            for backend in ("gl", "cpu"):
                times[backend].append(wall(base + ["--backend", backend]))
        for backend in ("gl", "cpu"):
            stats = json.loads(subprocess.run(base + ["--backend", backend, "--stats=json"], check=True,
                                              capture_output=True, text=True).stdout.strip().splitlines()[-1])
            phases = stats.get("phases_ms", {})
            passes = sum(p["ms"] for p in stats.get("passes", {}).values())
            w = times[backend]
            wall_ms = 1000 * statistics.median(w)
            outside = "%.0f%%" % (100 * (1 - passes / wall_ms)) if backend == "gl" else ""
            print("| %s | %s | %.2f, %.2f | %.0f | %s | %s | %s |" % (
                os.path.basename(model), backend, min(w), statistics.median(w), stats["total_ms"],
                "%.0f" % passes if backend == "gl" else "", outside,
                ", ".join("%s %.0f" % (k, v) for k, v in phases.items())))
    return 0


if __name__ == "__main__":
    sys.exit(main())
