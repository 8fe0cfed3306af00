#!/bin/sh
# Issue 24's targets, one run each, back to back (docs/PERFORMANCE.md "The targets, fourth round"):
# the whole render at 1024x1024 (bunny, dragon; gl against cpu, wall clock), the path integrator on
# the Cornell blocks (gl wavefront, gl megakernel, cpu), the viewer's frame rate, and the trace
# against Embree's best (primary and shadow rays). Run it on a quiet machine, under the build lock
# where others share it:  flock /work/.buildlock scripts/bench-targets.sh
# Needs build/gpurt, ../shared/models, out/models/dragon.ply (scripts/fetch-dragon.sh), xvfb-run.
set -eu
cd "$(dirname "$0")/.."
G=build/gpurt
echo "## whole render, 1024x1024 (scripts/bench-render.py --runs 3)"
python3 scripts/bench-render.py --runs 3
echo
echo "## path integrator and Whitted, gl wavefront / gl megakernel / cpu (scripts/bench-kernels.py --runs 3)"
python3 scripts/bench-kernels.py --runs 3 --cases whitted,path
echo
echo "## viewer, 640x480, bunny (gpurt view --bench; the default kernel, then the wavefront chain)"
xvfb-run -a $G view ../shared/models/bunny.obj --size 640x480 --bench | tail -1
xvfb-run -a $G view ../shared/models/bunny.obj --size 640x480 --bench --kernel fused | tail -1
echo
echo "## trace against Embree (gpurt bench --size 1024x1024 --runs 3)"
for m in ../shared/models/bunny.obj out/models/dragon.ply; do
  for r in primary shadow; do
    $G bench "$m" --size 1024x1024 --runs 3 --rays $r --backend gl --backend cpu --backend embree
  done
done
