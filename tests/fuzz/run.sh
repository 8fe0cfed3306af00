#!/usr/bin/env bash
# Builds the libFuzzer targets with clang into build-fuzz/ (GPURT_FUZZ=ON) and runs each for a
# bounded time on its committed seed corpus (tests/fuzz/corpus/NAME) plus the inputs earlier runs
# found (build-fuzz/corpus/NAME). Any crash, sanitizer report, leak, timeout or out-of-memory fails.
#   tests/fuzz/run.sh [SECONDS_PER_TARGET]      default 10 (GPURT_FUZZ_SECONDS)
# A failing input is kept as build-fuzz/artifacts/NAME-crash-*; replay it with
#   build-fuzz/tests/fuzz/fuzz_NAME build-fuzz/artifacts/NAME-crash-...
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds="${1:-${GPURT_FUZZ_SECONDS:-10}}"

CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGPURT_FUZZ=ON \
  >/dev/null
cmake --build build-fuzz -j"$(nproc)"

status=0
for name in obj json packed tile ply gltf texture envmap denoise; do
  # Every run first replays its whole corpus: past about a thousand inputs that alone would take
  # the time given (long runs with GPURT_FUZZ_SECONDS collect that many), so start afresh from
  # the seeds then.
  if [ -d "build-fuzz/corpus/$name" ] &&
     [ "$(find "build-fuzz/corpus/$name" -type f | wc -l)" -gt 1000 ]; then
    rm -r "build-fuzz/corpus/$name"
  fi
  mkdir -p "build-fuzz/corpus/$name" build-fuzz/artifacts
  log="build-fuzz/fuzz_$name.log"
  # One process, so that the time bound holds on a loaded machine; -timeout is per input.
  maxLen=4096 dict=(-dict="tests/fuzz/$name.dict")
  if [ "$name" = packed ]; then maxLen=8192 dict=(); fi  # binary: seeds up to 4 KB, no dictionary
  if [ "$name" = ply ]; then maxLen=8192; fi  # binary PLY seeds up to 2 KB
  if [ "$name" = gltf ]; then maxLen=8192; fi  # the GLB seeds are 2 KB
  if [ "$name" = texture ]; then maxLen=4096; fi  # PNG and JPEG seeds up to 1 KB
  if [ "$name" = envmap ]; then maxLen=4096; fi   # .hdr and .exr seeds up to 1 KB
  if "build-fuzz/tests/fuzz/fuzz_$name" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -max_len="$maxLen" "${dict[@]}" -print_final_stats=1 \
      -artifact_prefix="build-fuzz/artifacts/$name-" \
      "build-fuzz/corpus/$name" "tests/fuzz/corpus/$name" >"$log" 2>&1; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    echo "fuzz_$name: ${runs:-?} inputs in ${seconds} s, no failure"
  else
    status=1
    echo "fuzz_$name: FAILED (full log: $log)" >&2
    grep -v '# Uses:' "$log" | tail -n 60 >&2
  fi
done
exit "$status"
