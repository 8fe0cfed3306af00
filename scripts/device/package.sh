#!/bin/bash
# Packs gpurt for the device machine (no Debian libraries, no network there) into DEST (default .gpu).
# Run from the repository root on this Debian 12 machine, after a Release build:
#   BIN=build/gpurt bash scripts/device/package.sh          (APT=0 skips the glvnd debs' download)
# Then make the llvmpipe references with the SAME binary (about 10 min on 2 cores):
#   OUT=/tmp/ref-run IMG=/tmp/gpurt-ref-img REPEAT=1 T=900 DEADLINE=100000 bash .gpu/run.sh
#   mkdir -p .gpu/ref && cp /tmp/gpurt-ref-img/*.png .gpu/ref/
# and call the device: run(command="bash .gpu/run.sh", carry=[".gpu"], timeout_s=360), then give_back.
set -eu
BIN=${BIN:-build/gpurt}
DEST=${DEST:-.gpu}
L=/lib/x86_64-linux-gnu
grep -qx '/.gpu/' .git/info/exclude 2>/dev/null || echo /.gpu/ >>.git/info/exclude
mkdir -p "$DEST"/{bin,lib,libc,xz,src,debs,scenes,models}
cp -p "$BIN" "$DEST/bin/gpurt"
cp scripts/device/run.sh scripts/device/compare.py "$DEST/"
# What gpurt and its libraries need, less Mesa (libOSMesa -> gallium, libLLVM: ~100 MB, stubbed)
# and less glibc (kept apart in libc/, so that the machine's own loader can be tried as well).
for l in libglfw.so.3 libEGL.so.1 libGLdispatch.so.0 libtinyobjloader.so.2rc10 libtinygltf.so.2d libpng16.so.16 \
         libjpeg.so.62 libOpenEXR-3_1.so.30 libImath-3_1.so.29 libIlmThread-3_1.so.30 libIex-3_1.so.30 libz.so.1 \
         libtbb.so.12 libstdc++.so.6 libgcc_s.so.1 libX11.so.6 libxcb.so.1 libXau.so.6 libXdmcp.so.6 libbsd.so.0 \
         libmd.so.0 libstb.so.0; do
  cp -L "$L/$l" "$DEST/lib/"
done
for l in libc.so.6 libm.so.6 libdl.so.2 libpthread.so.0 librt.so.1 libresolv.so.2; do cp -L "$L/$l" "$DEST/libc/"; done
cp -L /lib64/ld-linux-x86-64.so.2 "$DEST/libc/"
# Embree (42 MB) travels xz-compressed (8.4 MB); run.sh unpacks it into /tmp/gpurt-lib.
xz -T2 -9 -c "$L/libembree3.so.3" >"$DEST/xz/libembree3.so.3.xz"
# The OSMesa stub: the four entry points gpurt imports, each failing (gpurt runs with --gl egl there).
cat >"$DEST/src/osmesa_stub.c" <<'EOF'
/* Stub libOSMesa.so.8 for the device run: gpurt links OSMesa but runs with --gl egl there.
   Every entry point fails, so --gl osmesa reports "no OpenGL 4.5 core context". */
#include <stddef.h>
typedef struct osmesa_context *OSMesaContext;
typedef void (*OSMESAproc)(void);
OSMesaContext OSMesaCreateContextAttribs(const int *attribList, OSMesaContext sharelist) { (void)attribList; (void)sharelist; return NULL; }
void OSMesaDestroyContext(OSMesaContext ctx) { (void)ctx; }
unsigned char OSMesaMakeCurrent(OSMesaContext ctx, void *buffer, unsigned type, int width, int height) { (void)ctx; (void)buffer; (void)type; (void)width; (void)height; return 0; }
OSMESAproc OSMesaGetProcAddress(const char *funcName) { (void)funcName; return NULL; }
EOF
gcc -shared -fPIC -O2 -Wl,-soname,libOSMesa.so.8 -o "$DEST/lib/libOSMesa.so.8" "$DEST/src/osmesa_stub.c"
# Anything the binary needs that is not packed (a new dependency since this list was made)?
missing=$(LD_LIBRARY_PATH="$DEST/lib:$DEST/libc" ldd "$DEST/bin/gpurt" | awk '/=>/ {print $1, $3}' |
          grep -v -e "$DEST/" -e libembree3 || true)
[ -n "$missing" ] && { echo "package.sh: not packed (add to the list?):"; echo "$missing"; }
# glvnd's libraries as debs (the device README's recipe); run.sh unpacks them to / there.
if [ "${APT:-1}" = 1 ]; then
  mkdir -p /tmp/amd64/partial
  o='-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64'
  apt-get $o update >/dev/null
  (cd "$DEST/debs" && apt-get $o download libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2)
fi
# Scenes and the bunny (../shared does not travel).
cp scenes/cornell_blocks.json scenes/cornell_blocks.obj scenes/cornell_blocks.mtl scenes/cornell.json \
   scenes/cornell.obj scenes/cornell.mtl scenes/sky.hdr "$DEST/scenes/"
cp ../shared/models/bunny.obj "$DEST/models/"
{ git rev-parse HEAD; echo "binary: $BIN, mtime $(stat -c %y "$BIN"), $(git status --short | wc -l) changed paths in the tree"
  echo "sha256 $(sha256sum "$DEST/bin/gpurt" | cut -d' ' -f1)"; } >"$DEST/HEAD.txt"
du -sh "$DEST"
