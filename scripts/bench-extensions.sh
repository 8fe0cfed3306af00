#!/usr/bin/env bash
# What a glTF material extension costs the path integrator (docs/PERFORMANCE.md, "glTF's material
# layers (issue 38)"): scenes/volume.json, iridescence.json and anisotropy.json against the same
# scenes with the extension's keys removed (the core material alone), 360x150, 16 samples a pixel,
# gl and cpu, in alternating rounds; prints "round scene backend samples/s" per run.
#   scripts/bench-extensions.sh GPURT [ROUNDS]
set -euo pipefail
gpurt=$(realpath "$1")
rounds=${2:-3}
cd "$(dirname "$0")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp scenes/slab.obj scenes/sphere.obj scenes/torus.obj scenes/cube.obj scenes/sky.hdr scenes/volume.json \
   scenes/iridescence.json scenes/anisotropy.json "$work"
python3 - "$work" <<'PY'
import json, os, sys
for name, keys in (("volume", ["attenuation_color", "attenuation_distance"]),
                   ("iridescence", ["iridescence", "iridescence_ior", "iridescence_thickness"]),
                   ("anisotropy", ["anisotropy", "anisotropy_rotation"])):
    scene = json.load(open(os.path.join(sys.argv[1], name + ".json")))
    for mesh in scene["meshes"]:
        for key in keys:
            mesh["material"].pop(key, None)
    json.dump(scene, open(os.path.join(sys.argv[1], name + "_core.json"), "w"))
PY
for round in $(seq "$rounds"); do
  for scene in volume volume_core iridescence iridescence_core anisotropy anisotropy_core; do
    for backend in gl cpu; do
      rate=$("$gpurt" render "$work/$scene.json" -o "$work/out.png" --size 360x150 --integrator path --spp 16 \
             --backend "$backend" --stats=json 2>/dev/null | python3 -c "import json, sys; print('%.3g' % json.load(sys.stdin)['samples_per_s'])")
      echo "$round $scene $backend $rate"
    done
  done
done
