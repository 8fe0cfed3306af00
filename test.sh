#!/usr/bin/env bash
# Installs what is missing, builds Release into build/ and runs the whole test suite with ctest.
#   ./test.sh             the suite
#   ./test.sh -R PATTERN  only the tests whose names match (ctest -R)
set -euo pipefail
cd "$(dirname "$0")"
./tools/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
cd build
ctest --output-on-failure -j"$(nproc)" --timeout 600 "$@"
