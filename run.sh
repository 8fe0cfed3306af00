#!/usr/bin/env bash
# Installs what is missing, builds Release into build/, renders the default scene to a PNG and
# prints its path.
set -euo pipefail
cd "$(dirname "$0")"
./scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target gpurt >/dev/null
mkdir -p out
./build/gpurt render scenes/boxes.json -o out/boxes.png --size 512x512 >&2
echo "$(pwd)/out/boxes.png"
