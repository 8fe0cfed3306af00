// What the integrators' megakernels (path/megakernel.frag, whitted/megakernel.frag) share: a
// path's work that the wavefront chain spreads over passes (surface.frag, shadowgen.frag,
// light.frag, bounce.frag) done inside one pass, as the cpu backend does it per ray (CpuTracer's
// surfaceAt, lightVisible, emitterVisible and environmentVisible, word for word), with the
// scene's accelerator traced inside (accel/trace.glsl), and the pass's counters.
#include "accel/trace.glsl"
#include "scene/shading.glsl"
#include "scene/camera.glsl"
#include "common/sampling.h"

// The point lights (GpuTracer's list): texels 2k and 2k + 1 hold light k's (position, intensity)
// and (colour, 0).
uniform sampler2D pointLights;
uniform int pointLightCount;
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

// The coverage key of the rays of `pixel` (alpha: scene/alpha.glsl's coverageSample and seed).

void setPixelCoverage(uvec2 pixel) {
#ifdef SCENE_ALPHA
    rayCoverageKey = coverageKey(pixel.x, pixel.y, coverageSample, coverageSeed);
#endif
}

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

// Whether nothing blocks the shadow ray from origin along dir up to limit (CpuTracer::unblocked).
bool unblocked(vec3 origin, vec3 dir, float limit) {
    shadowRays += 1;
    float t, u, v;
    int steps, state;
    return accelTrace(origin, dir, limit, true, t, u, v, steps, state) < 0;
}

// The surface record of hit h of the ray o + t d (surface.frag; CpuTracer::surfaceAt): the point,
// the geometric normal facing the ray, the shading normal, and the material as the ray meets it.
struct SurfaceHit {
    vec3 p;
    vec3 n;
    vec3 ns;
    bool front;
    MaterialRecord m;
};

SurfaceHit surfaceAt(vec4 h, vec3 o, vec3 d) {
    int id = int(h.w);
    vec3 v0, e1, e2;
    int material;
    fetchTriangle(id, v0, e1, e2, material);
    vec2 t = fetchTexcoord(id, h.y, h.z);
    SurfaceHit s;
    s.front = frontFace(e1, e2, d);
    s.m = materialFacing(fetchMaterialRecord(material, id, h.yz), s.front);
    s.p = o + h.x * d;
    s.n = facingNormal(e1, e2, d);
    s.ns = fetchMappedNormal(material, id, e1, e2, d, s.n, fetchShadingNormal(id, h.y, h.z, s.n), t, h.yz);
    return s;
}

// Point light k: position, colour, intensity.
void pointLight(int k, out vec3 position, out vec3 color, out float intensity) {
    vec4 a = texelFetch(pointLights, ivec2(2 * k, 0), 0);
    position = a.xyz;
    intensity = a.w;
    color = texelFetch(pointLights, ivec2(2 * k + 1, 0), 0).xyz;
}

// Whether point light `position` is in front of p and unblocked (CpuTracer::lightVisible).
bool lightVisible(vec3 p, vec3 n, vec3 position) {
    if (!lightInFront(p, n, position)) return false;
    vec3 o, d;
    float limit;
    shadowRay(p, n, rayOffset, position, o, d, limit);
    return unblocked(o, d, limit);
}

// The emitter point of the pixel's sample in dimension GPURT_DIM_EMITTER + depth, q on triangle
// `id`, when it is in front of p and unblocked (shadowgen.frag EMITTER; CpuTracer::emitterVisible).
bool emitterVisible(uvec2 pixel, int depth, vec3 p, vec3 n, out vec3 q, out int id) {
    q = emitterSamplePoint(pixel, sampleIndex, sampleCount, seed, samplerKind, uint(depth), id);
    if (!lightInFront(p, n, q)) return false;
    vec3 o, d;
    float limit;
    emitterShadowRay(p, n, rayOffset, q, o, d, limit);
    return unblocked(o, d, limit);
}

// Adds the element's counters to the pass's: its shadow rays, its camera ray's overflow, and that
// its last ray in the pass was at depth `last`. (Overflows are counted as the wavefront chain
// counts them: the camera rays'.)
void countRays(int last) {
    imageAtomicAdd(counters, ivec2(GPURT_COUNT_DEPTH + min(last, GPURT_COUNTED_DEPTHS - 1), 0), 1u);
    if (shadowRays > 0) imageAtomicAdd(counters, ivec2(GPURT_COUNT_SHADOW, 0), uint(shadowRays));
    if (cameraOverflow) imageAtomicAdd(counters, ivec2(GPURT_COUNT_OVERFLOW, 0), 1u);
}
