// The path integrator as a megakernel (--kernel megakernel): each element takes its path through
// up to `bounces` depths inside this one pass, as PathCpu does per pixel (word for word, the same
// random numbers and sums): trace (the accelerator inside, accel/trace.glsl), emission weighed
// against next-event estimation, the point lights, the environment direction and the emitter
// point each with its shadow ray, then the BSDF's next direction and Russian roulette. The
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
#ifdef AOVS
layout(location = 1) out vec4 hitOut;     // (t, u, v, triangle | -1) of the camera ray
layout(location = 2) out vec4 normalOut;  // (facing geometric normal, 0)
layout(location = 3) out ivec4 stepsOut;  // w: the cells or nodes its trace visited
#endif

// Next-event estimation at surface s hit along d (PathCpu directLight): each visible point light
// through the BSDF, the depth's environment direction and emitter point, each weighed against
// the BSDF's sampling of it.
vec3 directLight(uvec2 pixel, SurfaceHit s, vec3 d, int b) {
    vec3 local = vec3(0.0f);
    for (int k = 0; k < pointLightCount; ++k) {
        vec3 position, color;
        float intensity;
        pointLight(k, position, color, intensity);
        if (lightVisible(s.p, s.n, position))
            local = local + pathLightContribution(s.m, s.p, s.ns, d, position, color, intensity);
    }
#ifdef ENVIRONMENT_LIGHT  // the environment is sampled (CpuTracer::environmentVisible)
    vec2 u = sample2D(samplerKind, pixel.x, pixel.y, sampleIndex, sampleCount, seed, GPURT_DIM_ENVIRONMENT + uint(b));
    vec3 l;
    float pdf;
    if (sampleEnvironment(u, l, pdf) && dot(s.n, l) > 0.0f && unblocked(offsetOrigin(s.p, s.n, rayOffset), l, GPURT_FAR))
        local = local + pathEnvironmentContribution(s.m, s.ns, d, l, environmentRadiance(l), pdf);
#endif
#ifdef SCENE_EMITTERS
    vec3 q;
    int id;
    if (emitterVisible(pixel, b, s.p, s.n, q, id)) {
        vec3 v0, e1, e2;
        int material;
        fetchTriangle(id, v0, e1, e2, material);
        local = local + pathLightContribution(s.m, s.p, s.ns, d, q, fetchEmission(material),
                                              emitterIntensity(s.p, q, e1, e2, emitterArea)) *
                            emitterSampleWeight(s.m, s.p, q, e1, e2, emitterArea, s.ns, d);
    }
#endif
    return local;
}

// The sample's features at a hit of albedo a and shading normal n (or the background's).
void recordFeatures(uvec2 pixel, vec3 a, vec3 n) {
#ifdef FEATURES
    imageStore(pixelAlbedo, ivec2(pixel) - ivec2(0, tileRow), vec4(a, 0.0f));
    imageStore(pixelNormal, ivec2(pixel) - ivec2(0, tileRow), vec4(n, 0.0f));
#endif
}

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
    vec3 o = eye;
#ifdef PIXEL_LIST
#elif defined(PIXEL_CENTRE)
    vec3 d = primaryDirection();
#else
    vec3 d = sampleDirection();
#endif
    vec3 color = vec3(0.0f);
    vec3 weight = vec3(1.0f);
    float prevPdf = 0.0f;  // the camera ray: its emission counts in full
    bool open = true;      // the sample's features are still to be recorded
#else
    uvec2 element = uvec2(gl_FragCoord.xy);
    if (element.y * uint(packWidth) + element.x >= paths) discard;  // no path in this element
    vec4 w = readStream(weightState);
    vec4 state = readStream(pathStateIn);
    uvec2 pixel = uvec2(state.yz);
    vec3 o = readStream(rayOrigin).xyz;
    vec3 d = readStream(rayDir).xyz;
    vec3 color = readStream(colorState).xyz;
    vec3 weight = w.xyz;
    float prevPdf = state.x;
    bool open = state.w == 0.0f;
#endif
    setPixelCoverage(pixel);
    bool alive = false;
    int b = depth;
    int last = depth + bounces - 1;
    for (;; ++b) {
        int steps;
        vec4 h = traceClosest(o, d, GPURT_FAR, b == 0, steps);
#ifdef AOVS
        if (b == 0) {
            hitOut = h;
            stepsOut = ivec4(0, 0, 0, steps);
            normalOut = vec4(0.0f);
        }
#endif
        if (h.w < 0.0f) {
            if (open) recordFeatures(pixel, vec3(GPURT_BACKGROUND_ALBEDO), vec3(0.0f));
#ifdef SCENE_ENVIRONMENT
            color = color + clampContribution(weight * (environmentRadiance(d) * environmentHitWeight(prevPdf, environmentLightPdf(d))),
                                              b, clampDirect, clampIndirect);
#else
            color = color + clampContribution(weight * background, b, clampDirect, clampIndirect);
#endif
            break;
        }
        SurfaceHit s = surfaceAt(h, o, d);
        if (open) recordFeatures(pixel, materialAlbedo(s.m), s.ns);
#ifdef AOVS
        if (b == 0) normalOut = vec4(s.n, 0.0f);
#endif
        float mis = s.m.emitterLight ? emissionWeight(prevPdf, h.x, s.n, d, emitterArea) : 1.0f;
        color = color + clampContribution(weight * (materialEmitted(s.m, s.ns) * mis), b, clampDirect, clampIndirect);
        if (b == maxDepth) break;
        if (materialLit(s.m))
            color = color + clampContribution(weight * directLight(pixel, s, d, b), b, clampDirect, clampIndirect);

        // The next direction (path/bounce.frag).
        uint dim = GPURT_DIM_SCATTER + 2u * uint(b);
        vec2 u = sample2D(samplerKind, pixel.x, pixel.y, sampleIndex, sampleCount, seed, dim);
        vec2 choice = sampleChoice(samplerKind, pixel.x, pixel.y, sampleIndex, sampleCount, seed, dim + 1u);
        vec3 dir, factor;
        float pdf, side;
        if (!materialSample(s.m, d, s.n, s.ns, s.front, u, choice.x, dir, factor, pdf, side)) break;
        weight = weight * factor;
        open = featuresOpenAfter(open, pdf);
        if (!russianRoulette(b, weight, choice.y)) break;
        prevPdf = pdf;
        o = offsetOrigin(s.p, side * s.n, rayOffset);
        d = dir;
        if (b == last) {  // the pass's last depth: the path goes on in the next pass
            alive = true;
            break;
        }
    }
    countRays(b);
    if (!alive) {
        imageStore(pixelColor, ivec2(pixel) - ivec2(0, tileRow), vec4(color, 0.0f));  // the stream element of the pixel
        return;
    }
    uint k = imageAtomicAdd(counters, ivec2(GPURT_COUNT_PACKED, 0), 1u);
    int width = packWidth;
    ivec2 at = ivec2(int(k) % width, int(k) / width);
    imageStore(nextOrigin, at, vec4(o, GPURT_FAR));
    imageStore(nextDir, at, vec4(d, GPURT_A_RAY));
    imageStore(nextWeight, at, vec4(weight, 1.0f));
    imageStore(nextState, at, vec4(prevPdf, float(pixel.x), float(pixel.y), open ? 0.0f : 1.0f));
    imageStore(nextColor, at, vec4(color, 0.0f));
    lives = vec4(1.0f, 0.0f, 0.0f, 0.0f);
}
