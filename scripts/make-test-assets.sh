#!/usr/bin/env bash
# Writes the committed test assets of tests/assets/ from the shared OBJ models with tools others
# wrote: Assimp's command line (Debian assimp-utils) for PLY, Cesium's obj2gltf for glTF, checked
# with Khronos' glTF-Validator (both from the npm registry, into a temporary folder; npm and
# assimp-utils are installed if missing). The files are small and committed; run this again only
# to remake them (the tests read the committed files).
#   ply/teapot_ascii.ply      assimp export -fply   (ASCII)
#   ply/teapot_binary.ply     assimp export -fplyb  (binary little endian)
#   ply/cornell_box_be.ply    the same as binary big endian: Assimp writes only little endian, so
#                             scripts/ply-byteswap.py swaps its data (header and values are Assimp's)
#   gltf/teapot.gltf + .bin  obj2gltf --separate (JSON with an external buffer)
#   gltf/cornell_box.glb      obj2gltf (binary glTF)
#   gltf/teapot_meshopt.glb, teapot_meshopt_q.gltf (+ .bin)  gltfpack -c -noq / -cc of teapot.gltf
#                             (EXT_meshopt_compression; the second also KHR_mesh_quantization)
#   textures/quadrants.png    ImageMagick: 4 x 4 texels, quadrants red (top left), green, blue, white
#   textures/checker.png, .jpg  ImageMagick: a 256 x 128 checkerboard of 32-texel squares, cream
#                             and a colour that runs from blue (left) to red (right), the top-left
#                             square coloured; lossless and as JPEG (quality 92)
#   textures/quad.obj + .mtl  a unit square facing +z with vt (0, 0) at its bottom left, map_Kd
#                             quadrants.png (written here: the geometry is four lines)
#   textures/globe.obj + .mtl a UV sphere (scripts/make_scenes.py globe), map_Kd checker.jpg
#   textures/quad.glb, globe.glb  obj2gltf of those (the textures embedded), validated
#   textures/quad_separate.gltf (+ .bin, quadrants.png beside it)  obj2gltf --separate
# The models are public domain (teapot) and Apache-2.0 (Embree's Cornell box); the Stanford scans
# stay out of the tree (../shared/models/README.md).
set -euo pipefail
cd "$(dirname "$0")/.."
models=../shared/models
out=tests/assets
if ! command -v convert-im6.q16 >/dev/null; then
  echo "make-test-assets: installing imagemagick" >&2
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends imagemagick >/dev/null
fi
if ! command -v assimp >/dev/null; then
  echo "make-test-assets: installing assimp-utils" >&2
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends assimp-utils >/dev/null
fi
command -v npm >/dev/null || DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends npm >/dev/null
mkdir -p "$out/ply" "$out/gltf" "$out/textures"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
assimp export "$models/teapot.obj" "$work/teapot_ascii.ply" -fply >/dev/null
assimp export "$models/teapot.obj" "$work/teapot_binary.ply" -fplyb >/dev/null
assimp export "$models/cornell_box.obj" "$work/cornell_box_le.ply" -fplyb >/dev/null
python3 scripts/ply-byteswap.py "$work/cornell_box_le.ply" "$work/cornell_box_be.ply"
cp "$work/teapot_ascii.ply" "$work/teapot_binary.ply" "$work/cornell_box_be.ply" "$out/ply/"
(cd "$work" && npm install --silent --no-save obj2gltf@3.2.0 gltf-validator@2.0.0-dev.3.10 >/dev/null)
"$work/node_modules/.bin/obj2gltf" -i "$models/teapot.obj" -o "$work/teapot.gltf" --separate >/dev/null
"$work/node_modules/.bin/obj2gltf" -i "$models/cornell_box.obj" -o "$work/cornell_box.glb" >/dev/null
NODE_PATH="$work/node_modules" node scripts/gltf/validate.js "$work/teapot.gltf" "$work/cornell_box.glb"
cp "$work/teapot.gltf" "$work/teapot.bin" "$work/cornell_box.glb" "$out/gltf/"
# EXT_meshopt_compression as meshoptimizer's own gltfpack writes it (Debian gltfpack 0.18): the
# vertex codec on float positions (-noq) in a GLB, and the codec with quantized positions
# (KHR_mesh_quantization, -cc) in a .gltf with its .bin. gltfpack reorders the triangles for the
# vertex cache: the same teapot, another triangle numbering.
command -v gltfpack >/dev/null || DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends gltfpack >/dev/null
gltfpack -i "$work/teapot.gltf" -o "$out/gltf/teapot_meshopt.glb" -c -noq >/dev/null
gltfpack -i "$work/teapot.gltf" -o "$out/gltf/teapot_meshopt_q.gltf" -cc >/dev/null

# Textures (ImageMagick 6) and textured models.
im=convert-im6.q16
tex="$work/textures"
mkdir -p "$tex"
$im -size 2x2 xc:red xc:lime +append \( -size 2x2 xc:blue xc:white +append \) -append "$tex/quadrants.png"
$im -size 256x128 xc:'rgb(240,230,196)' \( -size 128x256 gradient:'rgb(40,60,200)-rgb(232,60,20)' -rotate -90 \) \
  \( -size 256x128 xc: -fx "((floor(i/32)+floor(j/32))%2)" -negate \) -composite -depth 8 -define png:color-type=2 \
  "$tex/checker.png"
$im "$tex/checker.png" -quality 92 "$tex/checker.jpg"
cat >"$tex/quad.mtl" <<'MTL'
newmtl quadrants
Kd 1 1 1
map_Kd quadrants.png
MTL
cat >"$tex/quad.obj" <<'OBJ'
mtllib quad.mtl
v -1 -1 0
v 1 -1 0
v 1 1 0
v -1 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
usemtl quadrants
f 1/1/1 2/2/1 3/3/1 4/4/1
OBJ
python3 scripts/make_scenes.py globe "$tex"
"$work/node_modules/.bin/obj2gltf" -i "$tex/quad.obj" -o "$tex/quad.glb" >/dev/null
"$work/node_modules/.bin/obj2gltf" -i "$tex/globe.obj" -o "$tex/globe.glb" >/dev/null
mkdir -p "$tex/separate"
"$work/node_modules/.bin/obj2gltf" -i "$tex/quad.obj" -o "$tex/separate/quad_separate.gltf" --separate >/dev/null
NODE_PATH="$work/node_modules" node scripts/gltf/validate.js "$tex/quad.glb" "$tex/globe.glb" "$tex/separate/quad_separate.gltf"
cp "$tex"/quadrants.png "$tex"/checker.png "$tex"/checker.jpg "$tex"/quad.obj "$tex"/quad.mtl "$tex"/globe.obj \
  "$tex"/globe.mtl "$tex"/quad.glb "$tex"/globe.glb "$out/textures/"
cp "$tex"/separate/* "$out/textures/"
ls -l "$out/ply" "$out/gltf" "$out/textures"
