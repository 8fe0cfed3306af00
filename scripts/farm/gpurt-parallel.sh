#!/usr/bin/env bash
# Renders one image as N tiles with GNU parallel, on this machine's cores or on other hosts
# (--sshlogin, as GNU parallel takes it; the paths must be the same there, e.g. a shared folder),
# then stitches them (docs/FARM.md). Each tile is one `gpurt render --tile I/N` task; their files
# go to OUT.tiles/ beside OUT with a GNU parallel job log, so that running the same command again
# with --resume re-runs only the tiles that failed or never ran.
#
#   scripts/farm/gpurt-parallel.sh --tiles N -o OUT.png [--jobs J] [--sshlogin LOGIN]... [--resume]
#                                [--gpurt PATH] SCENE [gpurt render options...]
#
# Exits non-zero, naming the failed tiles' log, when any tile fails; OUT appears only once every
# tile is there (gpurt writes each file atomically).
set -euo pipefail

tiles="" output="" jobs="" resume="" gpurt="$(cd "$(dirname "$0")/../.." && pwd)/build/gpurt"
logins=()
while [ $# -gt 0 ]; do
  case "$1" in
    --tiles) tiles="$2"; shift 2 ;;
    -o|--output) output="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --sshlogin) logins+=(--sshlogin "$2"); shift 2 ;;
    --resume) resume="--resume-failed"; shift ;;
    --gpurt) gpurt="$2"; shift 2 ;;
    *) break ;;
  esac
done
if [ -z "$tiles" ] || [ -z "$output" ] || [ $# -lt 1 ]; then
  echo "usage: $0 --tiles N -o OUT.png [--jobs J] [--sshlogin LOGIN]... [--resume] [--gpurt PATH] SCENE [render options...]" >&2
  exit 1
fi
if ! command -v parallel >/dev/null; then
  echo "$0: GNU parallel is not installed (Debian: apt-get install parallel)" >&2
  exit 2
fi
scene="$1"
shift
work="$output.tiles"
mkdir -p "$work"
last=$((tiles - 1))
# One task a tile; {} is its index. --halt never: every tile runs, then the log says which failed.
if ! parallel --will-cite --halt never ${jobs:+--jobs "$jobs"} "${logins[@]}" $resume \
      --joblog "$work/joblog" \
      "$gpurt" render "$scene" -o "$work/tile{}.png" --tile "{}/$tiles" "$@" ::: $(seq 0 "$last"); then
  echo "$0: some tiles failed (see $work/joblog; run again with --resume to re-run them alone)" >&2
  exit 1
fi
files=()
for i in $(seq 0 "$last"); do files+=("$work/tile$i.png"); done
"$gpurt" stitch -o "$output" "${files[@]}"
