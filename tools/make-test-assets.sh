#!/usr/bin/env bash
# Writes the committed test assets of tests/assets/ from the shared OBJ models with tools others
# wrote: Assimp's command line (Debian assimp-utils) for PLY, Cesium's obj2gltf for glTF, checked
# with Khronos' glTF-Validator (both from the npm registry, into a temporary folder; npm and
# assimp-utils are installed if missing). The files are small and committed; run this again only
# to remake them (the tests read the committed files).
#   ply/teapot_ascii.ply      assimp export -fply   (ASCII)
#   ply/teapot_binary.ply     assimp export -fplyb  (binary little endian)
#   ply/cornell_box_be.ply    the same as binary big endian: Assimp writes only little endian, so
#                             tools/ply-byteswap.py swaps its data (header and values are Assimp's)
#   gltf/teapot.gltf + .bin  obj2gltf --separate (JSON with an external buffer)
#   gltf/cornell_box.glb      obj2gltf (binary glTF)
# The models are public domain (teapot) and Apache-2.0 (Embree's Cornell box); the Stanford scans
# stay out of the tree (../shared/models/README.md).
set -euo pipefail
cd "$(dirname "$0")/.."
models=../shared/models
out=tests/assets
if ! command -v assimp >/dev/null; then
  echo "make-test-assets: installing assimp-utils" >&2
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends assimp-utils >/dev/null
fi
command -v npm >/dev/null || DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends npm >/dev/null
mkdir -p "$out/ply" "$out/gltf"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
assimp export "$models/teapot.obj" "$work/teapot_ascii.ply" -fply >/dev/null
assimp export "$models/teapot.obj" "$work/teapot_binary.ply" -fplyb >/dev/null
assimp export "$models/cornell_box.obj" "$work/cornell_box_le.ply" -fplyb >/dev/null
python3 tools/ply-byteswap.py "$work/cornell_box_le.ply" "$work/cornell_box_be.ply"
cp "$work/teapot_ascii.ply" "$work/teapot_binary.ply" "$work/cornell_box_be.ply" "$out/ply/"
(cd "$work" && npm install --silent --no-save obj2gltf@3.2.0 gltf-validator@2.0.0-dev.3.10 >/dev/null)
"$work/node_modules/.bin/obj2gltf" -i "$models/teapot.obj" -o "$work/teapot.gltf" --separate >/dev/null
"$work/node_modules/.bin/obj2gltf" -i "$models/cornell_box.obj" -o "$work/cornell_box.glb" >/dev/null
NODE_PATH="$work/node_modules" node tools/gltf/validate.js "$work/teapot.gltf" "$work/cornell_box.glb"
cp "$work/teapot.gltf" "$work/teapot.bin" "$work/cornell_box.glb" "$out/gltf/"
ls -l "$out/ply" "$out/gltf"
