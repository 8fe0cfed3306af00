#!/bin/sh
# Runs one test program of the sanitizer build (./test.sh --sanitize; CMake makes it the test
# programs' CROSSCOMPILING_EMULATOR, so ctest and test discovery start every test through it).
# Programs the tests start in turn (the gpurt binary) inherit the environment.
here=$(cd "$(dirname "$0")" && pwd)

# ASan: report leaks; also catch static initialisation order bugs. UBSan: -fno-sanitize-recover
# already makes undefined behaviour fatal; print where it happened.
export ASAN_OPTIONS="detect_leaks=1:check_initialization_order=1:strict_init_order=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export LSAN_OPTIONS="suppressions=$here/lsan.supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"

# Mesa unloads its DRI driver (swrast_dri.so, llvmpipe) at eglTerminate. LeakSanitizer then no
# longer sees the driver's global variables, reports the memory they still point to as leaked, and
# cannot name the unloaded driver in its stack traces, so no suppression can match. Preloading the
# driver keeps it mapped until exit. A dynamic sanitizer runtime (GCC) must come first.
for driver in /usr/lib/x86_64-linux-gnu/dri/swrast_dri.so /usr/lib64/dri/swrast_dri.so; do
  if [ -f "$driver" ]; then
    runtime=$(ldd "$1" 2>/dev/null | awk '/libasan\.so/ { print $3; exit }')
    export LD_PRELOAD="${runtime:+$runtime }$driver${LD_PRELOAD:+ $LD_PRELOAD}"
    break
  fi
done
exec "$@"
