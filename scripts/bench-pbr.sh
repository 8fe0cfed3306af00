#!/usr/bin/env bash
# The glTF model's cost (docs/PERFORMANCE.md, issue 22), two rounds, samples/s from --stats=json:
#   scripts/bench-pbr.sh OLD_GPURT NEW_GPURT HELMET.glb
# - the bunny (../shared/models/bunny.obj) under scenes/sky.hdr with a classic material and with a
#   glTF one of the same base colour (metallic 0.5, roughness 0.4), NEW_GPURT, both integrators
#   and backends, 512x512, --spp 4;
# - a textured PBR asset (HELMET: e.g. the DamagedHelmet) path traced with each binary.
# Run it under the build lock on a quiet machine: flock /work/.buildlock scripts/bench-pbr.sh ...
set -euo pipefail
old=$1 new=$2 helmet=$3
root=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
bunny=$(realpath "$root/../shared/models/bunny.obj")
sky=$root/scenes/sky.hdr
echo "{\"meshes\":[{\"file\":\"$bunny\",\"material\":{\"diffuse\":[0.8,0.6,0.4]}}],\"environment\":{\"file\":\"$sky\"}}" >"$tmp/classic.json"
echo "{\"meshes\":[{\"file\":\"$bunny\",\"material\":{\"diffuse\":[0.8,0.6,0.4],\"metallic\":0.5,\"roughness\":0.4}}],\"environment\":{\"file\":\"$sky\"}}" >"$tmp/pbr.json"
rate() { python3 -c "import json,sys; j=json.load(sys.stdin); print(round(j['width']*j['height']*4/j['total_ms']*1000))"; }
for round in 1 2; do
  for integrator in whitted path; do for backend in gl cpu; do for material in classic pbr; do
    echo "$round bunny-$integrator $backend $material $("$new" render "$tmp/$material.json" --size 512x512 --spp 4 \
      --integrator "$integrator" --backend "$backend" --stats=json -o "$tmp/x.png" 2>/dev/null | rate)"
  done; done; done
  for binary in "$old" "$new"; do for backend in gl cpu; do
    echo "$round helmet-path $backend $binary $("$binary" render "$helmet" --eye 0,0,3 --target 0,0,0 --size 512x512 --spp 4 \
      --integrator path --env "$sky" --backend "$backend" --stats=json -o "$tmp/x.png" 2>/dev/null | rate)"
  done; done
done
