#!/usr/bin/env python3
"""Two gpurt binaries timed back to back, alternating, on the same workloads (a refactoring must
not cost speed; docs/PERFORMANCE.md records the result):

  scripts/compare-speed.py OLD_GPURT NEW_GPURT [--rounds 3] [--only TEXT ...]

- `gpurt bench` (tracing alone): the bunny at 1024x1024, primary and shadow rays, gl and cpu:
  Mrays/s (gpurt bench's own median of its runs);
- whole renders with --stats=json: Whitted (the bunny at 1024x1024; the glass Cornell box at
  512x512, --spp 4) and the path integrator's cases of scripts/bench-paths.py (Cornell 8 bounces,
  blocks 2 and 8 bounces, the bunny), gl and cpu: samples/s.
Each figure is the median of the rounds, with their range; the ratio is of the medians, new / old.
Needs ../shared/models. Standard library only."""

import argparse
import json
import os
import statistics
import subprocess
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
BUNNY = os.path.join(ROOT, "..", "shared", "models", "bunny.obj")
OUT = os.path.join(tempfile.gettempdir(), "compare-speed.png")

BENCH = [("bench bunny primary", ["--rays", "primary"]), ("bench bunny shadow", ["--rays", "shadow"])]
RENDERS = [
    ("whitted bunny 1024^2", BUNNY, ["--size", "1024x1024"]),
    ("whitted Cornell glass 512^2 spp 4", "scenes/cornell.json", ["--size", "512x512", "--spp", "4"]),
    ("path Cornell 8 bounces spp 4", "scenes/cornell.json", ["--size", "512x512", "--integrator", "path", "--spp", "4", "--bounces", "8"]),
    ("path blocks 2 bounces spp 8", "scenes/cornell_blocks.json", ["--size", "512x512", "--integrator", "path", "--spp", "8", "--bounces", "2"]),
    ("path blocks 8 bounces spp 4", "scenes/cornell_blocks.json", ["--size", "512x512", "--integrator", "path", "--spp", "4", "--bounces", "8"]),
    ("path bunny 8 bounces spp 4", BUNNY, ["--size", "512x512", "--integrator", "path", "--spp", "4", "--bounces", "8"]),
]


def bench(binary, backend, extra):
    out = subprocess.run([binary, "bench", BUNNY, "--size", "1024x1024", "--backend", backend, "--json", "--runs", "5"] + extra,
                         check=True, capture_output=True, text=True, cwd=ROOT).stdout
    return json.loads(out)["mrays_per_s"]


def render(binary, backend, scene, extra):
    out = subprocess.run([binary, "render", os.path.join(ROOT, scene), "-o", OUT, "--backend", backend, "--stats=json"] + extra,
                         check=True, capture_output=True, text=True, cwd=ROOT).stdout
    return json.loads(out)["samples_per_s"]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--only", action="append", default=[],
                        help="only the workloads whose label contains this text (repeatable)")
    args = parser.parse_args()
    binaries = [os.path.abspath(args.old), os.path.abspath(args.new)]
    rows = []
    for backend in ("gl", "cpu"):
        for label, extra in BENCH:
            rows.append((f"{label}, {backend}", "Mrays/s", lambda b, backend=backend, extra=extra: bench(b, backend, extra)))
        for label, scene, extra in RENDERS:
            rows.append((f"{label}, {backend}", "samples/s",
                         lambda b, backend=backend, scene=scene, extra=extra: render(b, backend, scene, extra)))
    if args.only:
        rows = [row for row in rows if any(text in row[0] for text in args.only)]
    print("| workload | unit | old: median [range] | new: median [range] | new / old |")
    print("|---|---|---|---|---|")
    for label, unit, measure in rows:
        runs = [[], []]
        for r in range(args.rounds):
            order = (0, 1) if r % 2 == 0 else (1, 0)  # alternating which goes first
            for k in order:
                runs[k].append(measure(binaries[k]))
        median = [statistics.median(x) for x in runs]
        cells = [f"{m:.4g} [{min(x):.3g}-{max(x):.3g}]" for m, x in zip(median, runs)]
        print(f"| {label} | {unit} | {cells[0]} | {cells[1]} | {median[1] / median[0]:.3f} |", flush=True)


if __name__ == "__main__":
    main()
