#!/usr/bin/env bash
# Installs what is missing, builds and runs the whole test suite with ctest.
#   ./test.sh             Release build in build/, the suite, then each libFuzzer target for a
#                         bounded time (tests/fuzz/run.sh: clang, build-fuzz/, 10 s a target, nine targets)
#   ./test.sh --sanitize  the suite built with AddressSanitizer and UndefinedBehaviorSanitizer in
#                         build-sanitize/ (tests/sanitize/: options and leak suppressions)
#   ./test.sh --fuzz      only the fuzz targets
#   ./test.sh -R PATTERN  only the tests whose names match (other arguments go to ctest); no fuzzing
# GPURT_FUZZ_SECONDS sets the seconds per fuzz target (default 10).
set -euo pipefail
cd "$(dirname "$0")"
# scripts/install-deps.sh installs every package the build and the tests need, among them xvfb and
# xdotool (the viewer's window tests), slurm and munge (the Slurm farm driver's test), parallel.
# No test runs blender: the Cycles reference EXRs of tests/assets/cycles/ are committed, and only
# tools/cycles-reference.py, which remakes them, needs blender (scripts/install-deps.sh --cycles).
./scripts/install-deps.sh

mode=plain
case "${1:-}" in
  --sanitize) mode=sanitize; shift ;;
  --fuzz) mode=fuzz; shift ;;
esac

if [ "$mode" = fuzz ]; then
  exec tests/fuzz/run.sh
fi

build=build
config=(-DCMAKE_BUILD_TYPE=Release)
if [ "$mode" = sanitize ]; then
  build=build-sanitize
  config=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DGPURT_SANITIZE=ON)
fi
cmake -S . -B "$build" "${config[@]}" >/dev/null
cmake --build "$build" -j"$(nproc)"
(cd "$build" && ctest --output-on-failure -j"$(nproc)" --timeout 600 "$@")

if [ "$mode" = plain ] && [ $# -eq 0 ]; then
  tests/fuzz/run.sh
fi
