#!/usr/bin/env bash
# Renders one image as N tiles, or a range of frames, as a Slurm job array (docs/FARM.md).
# Tiles: task I runs `gpurt render --tile I/N` into OUT.tiles/tileI.png, and a stitch job that
# waits on the whole array (afterok) writes OUT. Frames: task F runs `gpurt render --frames F:F`,
# gpurt putting F in place of OUT's %d. Each task logs to slurm-ARRAYJOB_TASK.out in OUT.tiles/
# (frames: OUT.frames/, OUT without its %d). --resume submits only the tiles or frames whose files
# are missing. Every node must see the same paths (a shared folder); tasks run in this folder.
# --denoise (tiles, --integrator path): each tile writes the denoiser's AOVs as well (color,
# albedo, shading_normal, depth, variance), the stitch job stitches each (the raw picture to
# OUT.tiles/raw.png) and `gpurt denoise` writes OUT from them: the filter looks across tiles, so it
# runs on the whole image, and OUT is `gpurt render --denoise`'s picture.
#
#   scripts/farm/gpurt-slurm.sh (--tiles N [--denoise] | --frames A:B) -o OUT [--wait] [--resume]
#                             [--gpurt PATH] [--sbatch OPT]... SCENE [gpurt render options...]
#
# Prints the job ids. --wait waits for the jobs to end, and exits non-zero naming the failed tiles
# or frames and their logs when any fails (then the stitch job is cancelled); without it the exit
# status says only whether Slurm took the jobs.
set -euo pipefail

tiles="" frames="" output="" wait="" resume="" denoise="" gpurt="$(cd "$(dirname "$0")/../.." && pwd)/build/gpurt"
sbatch_opts=()
usage() {
  echo "usage: $0 (--tiles N [--denoise] | --frames A:B) -o OUT [--wait] [--resume] [--gpurt PATH] [--sbatch OPT]... SCENE [render options...]" >&2
  exit 1
}
while [ $# -gt 0 ]; do
  case "$1" in
    --tiles|--frames|-o|--output|--gpurt|--sbatch) [ $# -ge 2 ] || usage ;;
  esac
  case "$1" in
    --tiles) tiles="$2"; shift 2 ;;
    --frames) frames="$2"; shift 2 ;;
    -o|--output) output="$2"; shift 2 ;;
    --wait) wait=1; shift ;;
    --resume) resume=1; shift ;;
    --denoise) denoise=1; shift ;;
    --gpurt) gpurt="$2"; shift 2 ;;
    --sbatch) sbatch_opts+=("$2"); shift 2 ;;
    *) break ;;
  esac
done
if [ -z "$output" ] || [ $# -lt 1 ] || { [ -n "$tiles" ] && [ -n "$frames" ]; } || { [ -n "$denoise" ] && [ -z "$tiles" ]; }; then
  usage
fi
if [ -n "$tiles" ]; then
  [[ "$tiles" =~ ^[1-9][0-9]*$ ]] || usage
elif [[ "$frames" =~ ^([0-9]+):([0-9]+)$ ]]; then
  first=$((10#${BASH_REMATCH[1]})) last=$((10#${BASH_REMATCH[2]}))
  [ "$first" -le "$last" ] || usage
else
  usage
fi
needed=(sbatch)
[ -z "$wait" ] || needed+=(squeue scancel)
for cmd in "${needed[@]}"; do
  if ! command -v "$cmd" >/dev/null; then
    echo "$0: $cmd is not installed (Debian: apt-get install slurm-client)" >&2
    exit 2
  fi
done

# Tasks run wherever Slurm puts them: absolute paths, and the submit folder as their cwd.
abs() { case "$1" in /*) echo "$1" ;; *) echo "$PWD/$1" ;; esac; }
scene="$(abs "$1")"
shift
output="$(abs "$output")"
case "$gpurt" in */*) gpurt="$(abs "$gpurt")" ;; esac

# The job scripts go to sbatch on stdin, each word quoted for bash.
quote() { [ $# -eq 0 ] || printf ' %q' "$@"; }
# sbatch expands %A, %a, %j... in --output; a literal % is %%.
pattern() { echo "${1//%/%%}"; }
# ranges I...: 0 1 2 5 7 8 -> 0-2,5,7-8 (an --array index list)
ranges() {
  local out="" from="$1" to="$1" i
  shift
  for i in "$@" ""; do
    if [ -n "$i" ] && [ "$i" -eq $((to + 1)) ]; then to="$i"; continue; fi
    out+="${out:+,}$from"
    [ "$to" -eq "$from" ] || out+="-$to"
    from="$i" to="$i"
  done
  echo "$out"
}
submit() {  # submit SBATCH-OPTIONS... <<<SCRIPT: prints the job id
  local id
  id="$(sbatch --parsable --chdir="$PWD" "$@" "${sbatch_opts[@]}")" || exit 1
  echo "${id%%;*}"
}

# Without slurmdbd a job's state lives in slurmctld for MinJobAge (300 s by default) after it ends,
# so polling squeue from the moment of submission always sees it; a job gone from squeue (or one
# never seen) counts by its files alone.
final="COMPLETED|FAILED|CANCELLED|TIMEOUT|NODE_FAIL|PREEMPTED|BOOT_FAIL|DEADLINE|OUT_OF_MEMORY"
finish() {  # finish JOB: waits until no task of JOB is pending or running; prints "INDEX STATE" lines
  local out errors=0
  while :; do
    if out="$(squeue -h -r -t all -j "$1" -o '%K %T' 2>&1)"; then
      errors=0
      [ -n "$out" ] || return 0
      if ! grep -qvE " ($final)\$" <<<"$out"; then echo "$out"; return 0; fi
    elif grep -q "Invalid job id" <<<"$out"; then
      return 0
    elif [ $((errors += 1)) -ge 60 ]; then
      echo "$0: cannot follow job $1: $out" >&2
      exit 1
    fi
    sleep 1
  done
}
state() { awk -v i="$1" '$1 == i { print $2 }' <<<"$2"; }  # state INDEX LINES
# report WHAT INDEX... LOG...: the one-line message for failed tiles or frames
report() {
  local what="$1" n=$(( ($# - 1) / 2 ))
  shift
  [ "$n" -eq 1 ] || what+="s"
  echo "$0: $what $(ranges "${@:1:n}") failed (see ${*:n+1}); the same command with --resume re-runs them alone" >&2
}

if [ -n "$tiles" ]; then
  work="$output.tiles"
  mkdir -p "$work"
  todo=() files=()
  # --denoise: the AOVs the filter reads, each tile's beside its picture.
  aovs=()
  [ -z "$denoise" ] || aovs=(color albedo shading_normal depth variance)
  for ((i = 0; i < tiles; i++)); do
    files+=("$work/tile$i.png")
    missing=""
    for f in "$work/tile$i.png" "${aovs[@]/#/$work/tile$i.}"; do
      case "$f" in *.png) ;; *) f="$f.pfm" ;; esac
      [ -f "$f" ] && [ -f "$f.tile" ] || missing=1
    done
    if [ -z "$resume" ] || [ -n "$missing" ]; then todo+=("$i"); fi
  done
  aovArgs=""
  for a in "${aovs[@]}"; do aovArgs+=" --aov $(printf %q "$a")=$(printf %q "$work")/tile\$i.$a.pfm"; done
  array=""
  if [ ${#todo[@]} -gt 0 ]; then
    array="$(submit --array="$(ranges "${todo[@]}")" --job-name=gpurt-tile \
               --output="$(pattern "$work")/slurm-%A_%a.out" <<<"#!/bin/bash
i=\$SLURM_ARRAY_TASK_ID
exec$(quote "$gpurt" render "$scene" -o)$(quote "$work")/tile\$i.png --tile \"\$i/$tiles\"$aovArgs$(quote "$@")")"
    echo "tiles $(ranges "${todo[@]}"): job $array"
  fi
  # kill_invalid_depend in slurm.conf cancels the stitch once a tile fails; --wait does it anyway.
  # The stitch job: the picture, or (--denoise) the raw picture and each AOV, then the filter with
  # the render's picture options.
  if [ -z "$denoise" ]; then
    job="exec$(quote "$gpurt" stitch -o "$output" "${files[@]}")"
  else
    job="set -e
$(quote "$gpurt" stitch -o "$work/raw.png" "${files[@]}")"
    for a in "${aovs[@]}"; do
      parts=()
      for ((i = 0; i < tiles; i++)); do parts+=("$work/tile$i.$a.pfm"); done
      job+="
$(quote "$gpurt" stitch -o "$work/$a.pfm" "${parts[@]}")"
    done
    picture=()
    args=("$@")
    for ((k = 0; k < ${#args[@]}; k++)); do
      case "${args[k]}" in
        --exposure|--tonemap|--gl|--backend) picture+=("${args[k]}" "${args[k + 1]:-}") ;;
        --exposure=*|--tonemap=*|--gl=*|--backend=*) picture+=("${args[k]}") ;;
      esac
    done
    job+="
exec$(quote "$gpurt" denoise "$work/color.pfm" --albedo "$work/albedo.pfm" --normal "$work/shading_normal.pfm" \
        --depth "$work/depth.pfm" --variance "$work/variance.pfm" -o "$output" "${picture[@]}")"
  fi
  stitch="$(submit ${array:+--dependency=afterok:$array} --job-name=gpurt-stitch \
              --output="$(pattern "$work")/slurm-%j.out" <<<"#!/bin/bash
$job")"
  echo "stitch: job $stitch"
  [ -n "$wait" ] || exit 0
  if [ -n "$array" ]; then
    lines="$(finish "$array")"
    failed=() logs=()
    for i in "${todo[@]}"; do
      s="$(state "$i" "$lines")"
      if { [ -n "$s" ] && [ "$s" != COMPLETED ]; } || [ ! -f "$work/tile$i.png" ] || [ ! -f "$work/tile$i.png.tile" ]; then
        failed+=("$i") logs+=("$work/slurm-${array}_$i.out")
      fi
    done
    if [ ${#failed[@]} -gt 0 ]; then
      scancel "$stitch" 2>/dev/null || true
      report tile "${failed[@]}" "${logs[@]}"
      exit 1
    fi
  fi
  lines="$(finish "$stitch")"
  s="$(state N/A "$lines")"
  if { [ -n "$s" ] && [ "$s" != COMPLETED ]; } || [ ! -f "$output" ]; then
    echo "$0: the stitch job $stitch ${s:-failed} (see $work/slurm-$stitch.out)" >&2
    exit 1
  fi
  exit 0
fi

# Frames: gpurt fills in OUT's %d; printf does the same here to find each frame's file.
# shellcheck disable=SC2059
frame_file() { printf -- "$output" "$1"; }
# shellcheck disable=SC2001
work="$(sed 's/%[0-9]*d//g' <<<"$output").frames"
mkdir -p "$work"
todo=()
for ((f = first; f <= last; f++)); do
  if [ -z "$resume" ] || [ ! -f "$(frame_file "$f")" ]; then todo+=("$f"); fi
done
if [ ${#todo[@]} -eq 0 ]; then
  echo "frames $first-$last: all there"
  exit 0
fi
array="$(submit --array="$(ranges "${todo[@]}")" --job-name=gpurt-frame \
           --output="$(pattern "$work")/slurm-%A_%a.out" <<<"#!/bin/bash
f=\$SLURM_ARRAY_TASK_ID
exec$(quote "$gpurt" render "$scene" -o "$output") --frames \"\$f:\$f\"$(quote "$@")")"
echo "frames $(ranges "${todo[@]}"): job $array"
[ -n "$wait" ] || exit 0
lines="$(finish "$array")"
failed=() logs=()
for f in "${todo[@]}"; do
  s="$(state "$f" "$lines")"
  if { [ -n "$s" ] && [ "$s" != COMPLETED ]; } || [ ! -f "$(frame_file "$f")" ]; then
    failed+=("$f") logs+=("$work/slurm-${array}_$f.out")
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  report frame "${failed[@]}" "${logs[@]}"
  exit 1
fi
