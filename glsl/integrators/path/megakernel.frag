// The path integrator as a megakernel (--kernel megakernel): each element takes its path through
// up to `bounces` depths inside this one pass, running the control flow PathCpu runs per pixel
// (common/integrators/path.h pathTrace: the same random numbers and sums): trace (the accelerator
// inside, accel/trace.glsl), emission weighed against next-event estimation, the point lights,
// the environment direction and the emitter point each with its shadow ray, then the BSDF's next
// direction and Russian roulette. The
// wavefront chain (surface, shadowgen, light, bounce passes) writes each of these steps to
// streams; here the path stays in registers. A path that ends leaves its colour in its pixel's
// element of pixelColor; a path alive after the pass's last depth is packed to the front of the
// next pass's streams (an atomic counter gives each its slot: Purcell's stream compaction), so the
// next pass covers only the live paths and its count ends the loop (PathMegakernelGl).
// CAMERA: the first pass, one path per pixel from the camera ray of the sample (raygen.frag), no
// streams read. AOVS (with CAMERA): the primary hit, facing normal and step count as well.
// PIXEL_LIST (with CAMERA; adaptive sampling): one path per pixel of the packed list of active
// pixels the last convergence pass made (integrators/converge.frag), element k for its k-th.
// FEATURES (the denoiser's): each path leaves its sample's albedo and shading normal in its pixel's
// elements of pixelAlbedo and pixelNormal (common/path.h featuresOpenAfter); the live paths carry
// whether theirs are still open (state w: 0 open, 1 recorded).
#include "integrators/megakernel.glsl"
#include "common/path.h"

uniform int depth;     // the depth of the pass's first rays (0 with CAMERA)
uniform int bounces;   // the depths a pass takes each path through
uniform int maxDepth;  // a path's last depth (--bounces): its emission only
uniform float clampDirect;    // --clamp-direct (common/path.h clampContribution)
uniform float clampIndirect;  // --clamp-indirect
uniform int packWidth;  // the streams' width: live path k goes to element (k % width, k / width)
layout(rgba32f) uniform image2D pixelColor;  // per pixel: the colour of its path once it has ended
#ifdef FEATURES
layout(rgba32f) uniform image2D pixelAlbedo;  // per pixel: the albedo and shading normal of its sample
layout(rgba32f) uniform image2D pixelNormal;
#endif
#ifdef PIXEL_LIST
uniform sampler2D activePixels;  // (stream x, stream y, 0, 0) of each active pixel
uniform uint listLength;         // how many: the elements from the `listLength`-th on hold none
#endif
#ifndef CAMERA
// The live paths of the last pass, packed: ray, (throughput, 1), (pdf, pixel x, pixel y, 0),
// colour so far.
uniform sampler2D rayOrigin;
uniform sampler2D rayDir;
uniform sampler2D weightState;
uniform sampler2D pathStateIn;
uniform sampler2D colorState;
uniform uint paths;  // how many: the elements from the `paths`-th on hold none
#endif
// The live paths for the next pass, packed: slot k is element (k % W, k / W).
layout(rgba32f) uniform image2D nextOrigin;
layout(rgba32f) uniform image2D nextDir;
layout(rgba32f) uniform image2D nextWeight;
layout(rgba32f) uniform image2D nextState;
layout(rgba32f) uniform image2D nextColor;

layout(location = 0) out vec4 lives;  // (1 if the path goes on, 0, 0, 0)

// The sample's features at a hit of albedo a and shading normal n (or the background's).
void recordFeatures(vec3 a, vec3 n) {
#ifdef FEATURES
    imageStore(pixelAlbedo, ivec2(samplePixel) - ivec2(0, tileRow), vec4(a, 0.0f));
    imageStore(pixelNormal, ivec2(samplePixel) - ivec2(0, tileRow), vec4(n, 0.0f));
#endif
}

#include "common/integrators/path.h"

void main() {
    lives = vec4(0.0f);
#ifdef CAMERA
#ifdef PIXEL_LIST
    uvec2 element = uvec2(gl_FragCoord.xy);
    if (element.y * uint(packWidth) + element.x >= listLength) discard;  // no pixel in this element
    uvec2 pixel = uvec2(texelFetch(activePixels, ivec2(element), 0).xy) + uvec2(0u, uint(tileRow));
    vec3 d = sampleDirectionAt(pixel);
#else
    uvec2 pixel = imagePixel();
#endif
#ifdef PIXEL_LIST
#elif defined(PIXEL_CENTRE)
    vec3 d = primaryDirection();
#else
    vec3 d = sampleDirection();
#endif
    vec3 o;
    cameraRay(pixel, d, o, d);
    PathState st = pathStart(o, d, true);  // without FEATURES recordFeatures records nothing
#else
    uvec2 element = uvec2(gl_FragCoord.xy);
    if (element.y * uint(packWidth) + element.x >= paths) discard;  // no path in this element
    vec4 w = readStream(weightState);
    vec4 state = readStream(pathStateIn);
    uvec2 pixel = uvec2(state.yz);
    PathState st;
    st.o = readStream(rayOrigin).xyz;
    st.d = readStream(rayDir).xyz;
    vec4 c = readStream(colorState);
    st.color = c.xyz;
    st.weight = w.xyz;
    st.prevPdf = state.x;
    st.open = state.w == 0.0f;
    st.dispersed = c.w > 0.0f;
#endif
    beginPixel(pixel);
    bool alive;
    int b = pathTrace(st, depth, depth + bounces - 1, alive);
    countRays(b);
    if (!alive) {
        imageStore(pixelColor, ivec2(pixel) - ivec2(0, tileRow), vec4(st.color, 0.0f));  // the stream element of the pixel
        return;
    }
    uint k = imageAtomicAdd(counters, ivec2(GPURT_COUNT_PACKED, 0), 1u);
    int width = packWidth;
    ivec2 at = ivec2(int(k) % width, int(k) / width);
    imageStore(nextOrigin, at, vec4(st.o, GPURT_FAR));
    imageStore(nextDir, at, vec4(st.d, GPURT_A_RAY));
    imageStore(nextWeight, at, vec4(st.weight, 1.0f));
    imageStore(nextState, at, vec4(st.prevPdf, float(pixel.x), float(pixel.y), st.open ? 0.0f : 1.0f));
    imageStore(nextColor, at, vec4(st.color, st.dispersed ? 1.0f : 0.0f));
    lives = vec4(1.0f, 0.0f, 0.0f, 0.0f);
}
