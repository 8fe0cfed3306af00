#!/usr/bin/env bash
# Installs the Debian 12 packages gpurt builds and tests with (only those missing): toolchain,
# glad (GL loader generator), EGL + Mesa llvmpipe + OSMesa, GLFW, GLM, glslang, GoogleTest,
# Xvfb and xdotool (the viewer's window tests: a real X server, real input), GNU parallel and
# Slurm with munge (the farm drivers' tests run both for real, tests/farm/slurm-localhost.sh),
# tinyobjloader, tinygltf, Draco (glTF KHR_draco_mesh_compression), meshoptimizer (glTF EXT_meshopt_compression, decode), nlohmann-json, libpng and libjpeg-turbo (textures), zlib (CRC-32 of packed scenes), stb (stb_image: Radiance .hdr environment maps), OpenEXR (EXR output and .exr environment maps; its
# exrheader tool checks our files in the tests) and Embree (benchmark
# baseline, test cross-checks); clang with its libFuzzer and sanitizer runtimes and llvm-symbolizer
# for the fuzz targets.
set -euo pipefail

packages=(
  build-essential cmake pkg-config python3 python3-glad
  libegl-dev libegl-mesa0 libgl1-mesa-dri libosmesa6-dev
  libglfw3-dev libglm-dev glslang-tools libglx-mesa0 xvfb xdotool parallel
  slurmctld slurmd slurm-client munge iproute2
  libgtest-dev libgmock-dev
  libtinyobjloader-dev nlohmann-json3-dev libpng-dev libjpeg62-turbo-dev zlib1g-dev libcli11-dev libopenexr-dev openexr libtinygltf-dev libdraco-dev libmeshoptimizer-dev libstb-dev
  libembree-dev
  clang libclang-rt-14-dev llvm
)
# `--cycles`: also Blender and numpy for tools/cycles-reference.py, which remakes the Cycles
# reference images in tests/assets/cycles/. No test runs Blender (the images are committed), so
# ./test.sh does not ask for them.
if [ "${1:-}" = "--cycles" ]; then
  packages+=(blender python3-numpy)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}" >&2
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q >/dev/null || true
$sudo apt-get install -y -q --no-install-recommends "${missing[@]}" >/dev/null
