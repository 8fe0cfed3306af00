#!/usr/bin/python3
"""The cost of the pictures' features (docs/PERFORMANCE.md): --spp 16 against one sample, and glass
against the same scene with the glass made diffuse, on the gl and cpu backends, back to back and
alternating (runs of each, the minimum of gpurt's --stats=json total_ms and of the wall time).

  scripts/bench-pictures.py [--runs N] [--size WxH]

Needs build/gpurt (./run.sh builds it) and ../shared/models. Standard library only.
"""

import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

from benchrender import GPURT, ROOT, parse_args


def run(scene, backend, size, extra):
    command = [GPURT, "render", scene, "-o", os.path.join(tempfile.gettempdir(), "bench-pictures.png"),
               "--size", size, "--backend", backend, "--stats=json"] + extra
    start = time.monotonic()
    out = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    wall = (time.monotonic() - start) * 1000.0
    return json.loads(out)["total_ms"], wall


def main():
    args = parse_args(__doc__, "bench-pictures")
    if args is None:
        return 2
    # The Cornell box with its glass sphere made diffuse: the plain render of the same scene.
    folder = tempfile.mkdtemp(prefix="gpurt-bench-")
    for name in ("cornell.obj", "cornell.json"):
        shutil.copy(os.path.join(ROOT, "scenes", name), folder)
    with open(os.path.join(ROOT, "scenes", "cornell.mtl")) as mtl:
        text = mtl.read().replace("newmtl glass\nKd 0 0 0\nKs 0 0 0\nNs 1\nillum 7",
                                  "newmtl glass\nKd 0.7 0.7 0.7\nKs 0 0 0\nNs 1\nillum 1")
    assert "illum 7" not in text
    with open(os.path.join(folder, "cornell.mtl"), "w") as mtl:
        mtl.write(text)
    bunny = os.path.join(ROOT, "..", "shared", "models", "bunny.obj")
    cases = [
        ("bunny, 1 sample", bunny, []),
        ("bunny, --spp 16", bunny, ["--spp", "16"]),
        ("Cornell box, glass sphere diffuse, --spp 4", os.path.join(folder, "cornell.json"), ["--spp", "4"]),
        ("Cornell box with its glass sphere, --spp 4", os.path.join(ROOT, "scenes", "cornell.json"), ["--spp", "4"]),
    ]
    best = {}
    for _ in range(args.runs):
        for label, scene, extra in cases:
            for backend in ("gl", "cpu"):
                total, wall = run(scene, backend, args.size, extra)
                key = (label, backend)
                old = best.get(key, (float("inf"), float("inf")))
                best[key] = (min(old[0], total), min(old[1], wall))
    shutil.rmtree(folder)
    print("| %s at %s (min of %d runs) | gl total_ms | gl wall ms | cpu total_ms | cpu wall ms |" % ("render", args.size, args.runs))
    print("|---|---:|---:|---:|---:|")
    for label, _, _ in cases:
        gl, cpu = best[(label, "gl")], best[(label, "cpu")]
        print("| %s | %.0f | %.0f | %.0f | %.0f |" % (label, gl[0], gl[1], cpu[0], cpu[1]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
