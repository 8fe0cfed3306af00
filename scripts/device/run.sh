#!/bin/bash
# gpurt's first run on a GPU (device machine: NVIDIA H200) through EGL, with timings.
# Run from the repository root:  bash .gpu/run.sh     (OUT=... for where results go)
# Env knobs: QUICK=1 (rehearsal sizes), REPEAT=N (runs of each render; default 2: cold, warm),
#            T=seconds (timeout of each command), DEADLINE=seconds (no new render/bench after it),
#            SKIP_DEBS=1 (never unpack the debs to /); FORCE_DEVICE=1 SKIP_DEBS=1 NVJSON_OVERRIDE=FILE
#            rehearse the device branch on a machine without NVIDIA.
set -u
set -o pipefail
export PATH=$PATH:/usr/local/nvidia/bin
START=$(date +%s.%N)
cd "$(dirname "$0")/.." || exit 1
ROOT=$PWD
G=$ROOT/.gpu
OUT=${OUT:-/tmp/gpurt-out}
mkdir -p "$OUT"
LOG=$OUT/log.txt
STATS=$OUT/stats.jsonl
: >"$STATS"
IMG=${IMG:-/tmp/gpurt-img}
rm -rf "$IMG"; mkdir -p "$IMG"
T=${T:-60}
DEADLINE=${DEADLINE:-230}
REPEAT=${REPEAT:-2}
QUICK=${QUICK:-0}
if [ "$QUICK" = 1 ]; then
  CB_SIZE=128x128; CB_SPP=4; BUNNY_SIZE=256x256; BP_SPP=2; BENCH_SIZE=256x256; BENCH_RUNS=1
else
  CB_SIZE=512x512; CB_SPP=64; BUNNY_SIZE=1024x1024; BP_SPP=16; BENCH_SIZE=1024x1024; BENCH_RUNS=3
fi

log() { echo "$*" 2>&1 | tee -a "$LOG"; }
elapsed() { echo "$(date +%s.%N) $START" | awk '{printf "%.1f", $1-$2}'; }
past_deadline() { awk -v e="$(elapsed)" -v d="$DEADLINE" 'BEGIN{exit !(e>d)}'; }
# step NAME CMD...: runs CMD with a timeout, output into the log; never stops the script.
step() {
  local name=$1; shift
  log "=== [$(elapsed)s] $name: $*"
  timeout -k 5 "$T" "$@" 2>&1 | tee -a "$LOG"
  local rc=$?
  log "=== $name rc=$rc"
  return 0
}

log "gpurt device run, $(date -u), host $(hostname), QUICK=$QUICK REPEAT=$REPEAT T=$T DEADLINE=$DEADLINE"
log "binary sha256 $(sha256sum "$G/bin/gpurt" | cut -c1-16), repo HEAD $(cat "$G/HEAD.txt" 2>/dev/null)"

# ---- a. the machine, the libraries, the GL context --------------------------------------------
DEVICE=0
if command -v nvidia-smi >/dev/null 2>&1 || [ -d /usr/local/nvidia ]; then DEVICE=1; fi
DEVICE=${FORCE_DEVICE:-$DEVICE}  # FORCE_DEVICE=1: rehearse the device branch here
log "DEVICE=$DEVICE"
step nvidia-smi nvidia-smi
step nvidia-smi-q bash -c "nvidia-smi -q -d CLOCK,PERFORMANCE 2>&1 | head -60"
step os bash -c "cat /etc/os-release | head -3; ldd --version 2>&1 | head -1; uname -a; nproc; free -g | head -2"
if [ "$DEVICE" = 1 ] && [ "${SKIP_DEBS:-0}" != 1 ]; then
  step unpack-debs bash -c "for f in $G/debs/*.deb; do dpkg -x \$f / || echo failed \$f; done; ldconfig; echo unpacked"
fi
# Embree travels compressed (42 MB).
mkdir -p /tmp/gpurt-lib
step unpack-embree bash -c "xz -dc $G/xz/libembree3.so.3.xz >/tmp/gpurt-lib/libembree3.so.3 2>/dev/null || python3 -c 'import lzma,sys; open(\"/tmp/gpurt-lib/libembree3.so.3\",\"wb\").write(lzma.open(sys.argv[1]).read())' $G/xz/libembree3.so.3.xz; ls -la /tmp/gpurt-lib"

# The NVIDIA EGL vendor library and its JSON.
NVLIB=
for f in $(find /usr/local/nvidia /usr/lib/x86_64-linux-gnu /usr/lib64 /lib64 -maxdepth 3 -name 'libEGL_nvidia.so*' 2>/dev/null); do
  NVLIB=$(dirname "$f"); break
done
NVJSON=
for f in /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json /usr/share/glvnd/egl_vendor.d/10_nvidia.json /etc/glvnd/egl_vendor.d/10_nvidia.json; do
  [ -f "$f" ] && { NVJSON=$f; break; }
done
[ -z "$NVJSON" ] && NVJSON=$(find /usr/local/nvidia /usr/share /etc -name '*nvidia*.json' -path '*egl_vendor*' 2>/dev/null | head -1)
NVJSON=${NVJSON_OVERRIDE:-$NVJSON}  # rehearsal only
log "NVLIB=$NVLIB NVJSON=$NVJSON"
step driver-files bash -c "ls /usr/local/nvidia /usr/local/nvidia/* 2>&1 | head -40; [ -n '$NVJSON' ] && cat '$NVJSON'; ls /usr/share/glvnd/egl_vendor.d /etc/glvnd/egl_vendor.d 2>&1; ls -la /dev/nvidia* /dev/dri 2>&1 | head; ldconfig -p | grep -E 'EGL|GLdispatch|nvidia-egl|glcore' | head -20"

LP_BASE=$G/lib:/tmp/gpurt-lib
[ -n "$NVLIB" ] && NVPATH=":$NVLIB" || NVPATH=":/usr/local/nvidia/lib64:/usr/local/nvidia/lib"
# Ways to start the binary, tried in order until `info --gl egl` gives a context that is not a
# software renderer (on the device) or any context (here):
#   carried: Debian's loader and glibc (.gpu/libc), NVIDIA's vendor JSON named
#   carried-novendor: the same, glvnd left to find its vendors
#   system: the machine's own loader and glibc, .gpu/lib on LD_LIBRARY_PATH
MODE=none
GP=()
try_mode() {
  local mode=$1 vendor=$2; shift 2
  local -a cmd=("$@")
  if [ -n "$vendor" ]; then export __EGL_VENDOR_LIBRARY_FILENAMES=$vendor; else unset __EGL_VENDOR_LIBRARY_FILENAMES; fi
  log "=== [$(elapsed)s] info ($mode, __EGL_VENDOR_LIBRARY_FILENAMES=${vendor:-unset}): ${cmd[*]} info --gl egl"
  local text
  text=$(timeout -k 5 30 "${cmd[@]}" info --gl egl 2>&1); local rc=$?
  echo "$text" | tee -a "$LOG"
  log "=== info ($mode) rc=$rc"
  if [ $rc -eq 0 ]; then
    if echo "$text" | grep -E '^renderer' | grep -qiE 'llvmpipe|softpipe|swrast|lavapipe'; then
      log "CHECK: renderer is a SOFTWARE renderer in mode $mode"
      [ "$DEVICE" = 1 ] && return 1
    fi
    if [ "$DEVICE" = 1 ] && ! echo "$text" | grep -E '^(vendor|renderer)' | grep -qi nvidia; then
      log "CHECK: vendor/renderer is not NVIDIA in mode $mode"
      return 1
    fi
    MODE=$mode; GP=("${cmd[@]}")
    log "CHECK: using mode $mode: $(echo "$text" | grep -E '^(context|vendor|renderer|version)' | tr -s ' ' | tr '\n' ';')"
    return 0
  fi
  return 1
}
CARRIED=("$G/libc/ld-linux-x86-64.so.2" --library-path "$LP_BASE:$G/libc$NVPATH" "$G/bin/gpurt")
SYSTEM=(env "LD_LIBRARY_PATH=$LP_BASE$NVPATH" "$G/bin/gpurt")
if [ "$DEVICE" = 1 ] && [ -n "$NVJSON" ]; then try_mode carried "$NVJSON" "${CARRIED[@]}" || try_mode carried-novendor "" "${CARRIED[@]}" || try_mode system "$NVJSON" "${SYSTEM[@]}" || try_mode system-novendor "" "${SYSTEM[@]}"
else try_mode carried-novendor "" "${CARRIED[@]}" || try_mode system-novendor "" "${SYSTEM[@]}"
fi
if [ "$MODE" = none ]; then
  log "CHECK FAILED: no GL context of the kind wanted; the renders below will fail or be skipped. EGL debug:"
  export EGL_LOG_LEVEL=debug __GL_DEBUG=1
  timeout -k 5 30 env LD_DEBUG=libs "${CARRIED[@]}" info --gl egl 2>&1 | grep -E 'EGL|nvidia|error|cannot' | head -60 | tee -a "$LOG"
  unset EGL_LOG_LEVEL __GL_DEBUG
  GP=("${CARRIED[@]}")
fi
log "MODE=$MODE __EGL_VENDOR_LIBRARY_FILENAMES=${__EGL_VENDOR_LIBRARY_FILENAMES:-unset}"

# ---- b. renders ----------------------------------------------------------------------------------
# render LABEL ARGS...: REPEAT runs (the first cold: shader compile), --stats=json to stats.jsonl,
# gpurt's total_ms and the wall clock of the command; the image goes to $IMG/LABEL.png.
render() {
  local label=$1; shift
  local run
  for run in $(seq 1 "$REPEAT"); do
    if past_deadline; then log "=== SKIPPED $label run $run: past the deadline ($(elapsed)s > ${DEADLINE}s)"; return 0; fi
    log "=== [$(elapsed)s] render $label run $run: gpurt render $* -o $IMG/$label.png --gl egl --stats=json"
    local t0 t1 rc
    t0=$(date +%s.%N)
    timeout -k 5 "$T" "${GP[@]}" render "$@" -o "$IMG/$label.png" --gl egl --stats=json >"$IMG/$label.json" 2>"$IMG/$label.err"
    rc=$?
    t1=$(date +%s.%N)
    local wall; wall=$(echo "$t1 $t0" | awk '{printf "%.3f", $1-$2}')
    cat "$IMG/$label.err" | tee -a "$LOG"
    python3 - "$label" "$run" "$rc" "$wall" "$IMG/$label.json" "$STATS" "$*" <<'EOF' 2>&1 | tee -a "$LOG"
import json, sys
label, run, rc, wall, path, stats, args = sys.argv[1:]
try:
    j = json.load(open(path))
except Exception as e:
    j = {"parse_error": str(e), "stdout": open(path, errors="replace").read()[:2000]}
j.update({"label": label, "run": int(run), "rc": int(rc), "wall_s": float(wall), "args": args})
with open(stats, "a") as f:
    f.write(json.dumps(j, sort_keys=True) + "\n")
ph = j.get("phases_ms", {})
print("RESULT %-28s run %s rc %s wall %.3f s  total_ms %s  Mrays/s %s  samples/s %s  compile %s  trace %s  shade %s  context %s" % (
    label, run, rc, float(wall), round(j.get("total_ms", -1), 1), round(j.get("mrays_per_s", -1), 2),
    round(j.get("samples_per_s", -1)), round(ph.get("compile", -1), 1), round(ph.get("trace", -1), 1),
    round(ph.get("shade", -1), 1), round(ph.get("context", -1), 1)))
if "parse_error" in j:
    print("stdout was:", j["stdout"][:500])
EOF
  done
}

CB=("$G/scenes/cornell_blocks.json" --integrator path --size "$CB_SIZE" --spp "$CB_SPP")
render cb_path_megakernel "${CB[@]}" --kernel megakernel
render cb_path_fused "${CB[@]}" --kernel fused
render cb_path_split "${CB[@]}" --kernel split
BUNNY=("$G/models/bunny.obj" --size "$BUNNY_SIZE")
render bunny_whitted_default "${BUNNY[@]}"
render bunny_whitted_megakernel "${BUNNY[@]}" --kernel megakernel
BP=("${BUNNY[@]}" --integrator path --env "$G/scenes/sky.hdr" --spp "$BP_SPP")
render bunny_path_sky_default "${BP[@]}"
render bunny_path_sky_megakernel "${BP[@]}" --kernel megakernel

# ---- c. bench: tracing alone, gl against Embree --------------------------------------------------
for rays in primary shadow; do
  if past_deadline; then log "=== SKIPPED bench $rays: past the deadline"; continue; fi
  log "=== [$(elapsed)s] bench $rays"
  t0=$(date +%s.%N)
  timeout -k 5 "$T" "${GP[@]}" bench "$G/models/bunny.obj" --size "$BENCH_SIZE" --rays $rays --backend gl --backend embree --runs "$BENCH_RUNS" --gl egl 2>&1 | tee -a "$LOG"
  rc=$?
  log "=== bench $rays rc=$rc wall $(echo "$(date +%s.%N) $t0" | awk '{printf "%.3f", $1-$2}') s"
done

# ---- extra: the Cornell box with glass and mirror, path, two kernel forms (only if time is left) ---
CG=("$G/scenes/cornell.json" --integrator path --size "$CB_SIZE" --spp "$CB_SPP")
render cornell_path_megakernel "${CG[@]}" --kernel megakernel
render cornell_path_fused "${CG[@]}" --kernel fused

# ---- d. the GPU's images against llvmpipe's (made beforehand with the same binary and options) ---
log "=== [$(elapsed)s] compare against $G/ref (llvmpipe)"
T=60 step compare python3 "$G/compare.py" "$G/ref" "$IMG"
log "=== [$(elapsed)s] summary (each render's runs)"
python3 - "$STATS" <<'EOF' 2>&1 | tee -a "$LOG"
import json, sys
for line in open(sys.argv[1]):
    j = json.loads(line)
    print("SUMMARY %-28s run %d rc %d wall_s %7.3f total_ms %9.1f compile_ms %8.1f Mrays/s %8.2f" % (
        j["label"], j["run"], j["rc"], j["wall_s"], j.get("total_ms", -1), j.get("phases_ms", {}).get("compile", -1),
        j.get("mrays_per_s", -1)))
EOF
step nvidia-smi-after bash -c "nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.mem,temperature.gpu,power.draw --format=csv"
for f in cb_path_fused cb_path_megakernel bunny_whitted_default bunny_path_sky_default; do
  [ -f "$IMG/$f.png" ] && cp "$IMG/$f.png" "$OUT/$f.png"
done
log "=== done in $(elapsed)s; MODE=$MODE"
