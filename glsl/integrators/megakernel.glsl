// What the integrators' megakernels (path/megakernel.frag, whitted/megakernel.frag) share: the
// hooks of the shared integrators (common/integrators/README.md) for kernels that trace their own
// rays, with the scene's accelerator traced inside (accel/trace.glsl) where the wavefront chain
// spreads the work over passes (surface.frag, shadowgen.frag, light.frag, bounce.frag), and the
// pass's counters.
#include "accel/trace.glsl"
#include "scene/shading.glsl"
#include "scene/camera.glsl"
#include "common/sampling.h"
#include "integrators/hooks.glsl"

// The point lights (GpuTracer's list): texels 2k and 2k + 1 hold light k's (position, intensity)
// and (colour, 0).
uniform sampler2D punctualLights;
uniform int punctualLightCount;
uniform vec3 background;  // what a ray that misses sees without an environment

// The pass's counters (RenderStats), added once a fragment: texel k of `counters`
// (GPURT_COUNT_*); GPURT_COUNT_DEPTH + b: the paths whose last ray in the pass was at depth b.
layout(r32ui) uniform uimage2D counters;
#define GPURT_COUNT_PACKED 0
#define GPURT_COUNT_SHADOW 1
#define GPURT_COUNT_OVERFLOW 2  // camera rays stopped at the step limit (as the wavefront chain counts)
#define GPURT_COUNT_DEPTH 3
#define GPURT_COUNTED_DEPTHS 256  // deeper rays count at the last depth counted

// The stream element's shadow rays, and whether its camera ray reached the step limit.
int shadowRays = 0;
bool cameraOverflow = false;

// The element's pixel: its sample's numbers (integrators/hooks.glsl) and the coverage key of its
// rays (alpha: scene/alpha.glsl's coverageSample and seed).
void beginPixel(uvec2 pixel) {
    samplePixel = pixel;
#ifdef SCENE_ALPHA
    rayCoverageKey = coverageKey(pixel.x, pixel.y, coverageSample, coverageSeed);
#endif
}

// AOVS: the megakernel writes its camera rays' AOVs too (aovs.frag, the pixel centres' own pass,
// declares its outputs itself).
#if defined(AOVS) && !defined(PIXEL_CENTRE_AOVS)
#define MEGAKERNEL_AOVS
#endif
#ifdef MEGAKERNEL_AOVS
layout(location = 1) out vec4 hitOut;     // (t, u, v, triangle | -1) of the camera ray
layout(location = 2) out vec4 normalOut;  // (facing geometric normal, 0)
layout(location = 3) out ivec4 stepsOut;  // w: the cells or nodes its trace visited
#endif

// The closest hit of o + t d, as the trace kernels write it: (t, u, v, triangle | -1). camera:
// the ray is the element's camera ray (its overflow is counted).
vec4 traceClosest(vec3 o, vec3 d, float tLimit, bool camera, out int steps) {
    float t, u, v;
    int state;
    int id = accelTrace(o, d, tLimit, false, t, u, v, steps, state);
    // As GpuPipeline::readHitAovs counts: the rays whose steps reached the limit.
    if (camera && steps >= accelStepLimit()) cameraOverflow = true;
    return vec4(id >= 0 ? t : GPURT_FAR, u, v, float(id));
}

// The shared integrators' trace (common/integrators/README.md): the closest hit of a ray of depth
// (round) b; the camera ray's hit and steps are AOVs.
vec4 integratorTrace(vec3 o, vec3 d, int b) {
    int steps;
    vec4 h = traceClosest(o, d, GPURT_FAR, b == 0, steps);
#ifdef MEGAKERNEL_AOVS
    if (b == 0) {
        hitOut = h;
        stepsOut = ivec4(0, 0, 0, steps);
        normalOut = vec4(0.0f);
    }
#endif
    return h;
}

// The camera ray's hit h and its facing normal n (AOVS).
void recordPrimary(vec4 h, vec3 n) {
#ifdef MEGAKERNEL_AOVS
    normalOut = vec4(n, 0.0f);
#endif
}

// Whether nothing blocks the shadow ray from origin along dir up to limit (CpuTracer::unblocked).
bool unblockedRay(vec3 origin, vec3 dir, float limit) {
    shadowRays += 1;
    float t, u, v;
    int steps, state;
    return accelTrace(origin, dir, limit, true, t, u, v, steps, state) < 0;
}

// The surface record of hit h of the ray o + t d (surface.frag; CpuTracer::surfaceAt): the point,
// the geometric normal facing the ray, the shading normal, and the material as the ray meets it.
SurfaceHit surfaceAt(vec4 h, vec3 o, vec3 d) {
    int id = int(h.w);
    vec3 v0, e1, e2;
    int material;
    fetchTriangle(id, v0, e1, e2, material);
    vec2 t = fetchTexcoord(id, h.y, h.z);
    SurfaceHit s;
    s.front = frontFace(e1, e2, d);
    s.m = materialFacing(fetchMaterialRecord(material, id, h.yz, d), s.front);
    s.p = o + h.x * d;
    s.n = facingNormal(e1, e2, d);
    s.ns = fetchMappedNormal(material, id, e1, e2, d, s.n, fetchShadingNormal(id, h.y, h.z, s.n), t, h.yz);
    return s;
}

// Light k (PunctualLights.h lightTexels: four texels a light).
PunctualLight punctualLight(int k) {
    vec4 a = texelFetch(punctualLights, ivec2(4 * k, 0), 0);
    vec4 b = texelFetch(punctualLights, ivec2(4 * k + 1, 0), 0);
    vec4 c = texelFetch(punctualLights, ivec2(4 * k + 2, 0), 0);
    vec4 e = texelFetch(punctualLights, ivec2(4 * k + 3, 0), 0);
    return PunctualLight(int(b.w), a.xyz, c.xyz, b.xyz, a.w, e.xy, c.w);
}

// The emitter point for the sample numbers u, on a triangle of edges e1, e2 and its emission
// (scene/shading.glsl emitterPointOf).
void emitterPointAt(vec2 u, out vec3 q, out vec3 e1, out vec3 e2, out vec3 emission) {
#ifdef SCENE_EMITTERS
    int id;
    q = emitterPointOf(u, id);
    vec3 v0;
    int material;
    fetchTriangle(id, v0, e1, e2, material);
    emission = fetchEmission(material);
#endif
}

// The element's camera ray of the pass's sample (through the pixel centre with PIXEL_CENTRE), the
// pixel begun (beginPixel).
void beginCameraSample(out vec3 o, out vec3 d) {
    uvec2 pixel = imagePixel();
    beginPixel(pixel);
#ifdef PIXEL_CENTRE
    cameraRay(pixel, primaryDirection(), o, d);
#else
    cameraRay(pixel, sampleDirection(), o, d);
#endif
}

#define GPURT_TRACE_HOOKS
#include "common/integrators/lights.h"

// Adds the element's counters to the pass's: its shadow rays, its camera ray's overflow, and that
// its last ray in the pass was at depth `last`. (Overflows are counted as the wavefront chain
// counts them: the camera rays'.)
void countRays(int last) {
    imageAtomicAdd(counters, ivec2(GPURT_COUNT_DEPTH + min(last, GPURT_COUNTED_DEPTHS - 1), 0), 1u);
    if (shadowRays > 0) imageAtomicAdd(counters, ivec2(GPURT_COUNT_SHADOW, 0), uint(shadowRays));
    if (cameraOverflow) imageAtomicAdd(counters, ivec2(GPURT_COUNT_OVERFLOW, 0), 1u);
}
