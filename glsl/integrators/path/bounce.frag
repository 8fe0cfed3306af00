// The path integrator's last step of a round (common/path.h): colour += throughput * the light
// that next-event estimation gathered at the hit (the point lights' in localColor, and the
// emitter point's, whose shadow ray the last trace answered, added here: the light pass of the
// emitters fused into this one), then the path's next ray: a direction from the
// BSDF (materialSample, the sample's numbers of this depth), the throughput times f cos / pdf, and
// Russian roulette. A path that ends (missed, absorbed, below the surface, roulette) leaves its
// colour in its pixel's element of pixelColor. The paths that go on stay in their elements, or
// with PACK are packed to the front of the next round's streams (an atomic counter gives each
// its slot: Purcell's stream compaction), so that the next rounds' passes cover only them; the
// packing costs, so PathGl::sample packs only once many paths end.
// The path's state w says whether its sample's features (the denoiser's) are still open: 0 until
// a hit's sampled lobe is not a delta (common/path.h featuresOpenAfter; surface.frag records them).
#include "scene/shading.glsl"
#include "common/sampling.h"
#include "common/path.h"

#include "integrators/surface_streams.glsl"
uniform sampler2D hitState;     // the emitter shadow rays' hits
uniform sampler2D lightSample;  // (q, emitting triangle | -1): the emitter point of the hit
uniform uint sampleIndex;
uniform uint sampleCount;
uniform uint seed;
uniform uint samplerKind;
uniform int depth;  // the hits' depth (0: the camera rays' hits)
uniform float clampDirect;    // --clamp-direct (common/path.h clampContribution)
uniform float clampIndirect;  // --clamp-indirect
uniform vec3 background;      // (unused here: common/integrators/path.h's pathMiss needs it)
layout(rgba32f) uniform image2D pixelColor;  // per pixel: the colour of its path once it has ended
#ifdef PACK
// The live paths, packed for the next round: slot k is element (k % W, k / W), k from the counter.
layout(rgba32f) uniform image2D nextOrigin;
layout(rgba32f) uniform image2D nextDir;
layout(rgba32f) uniform image2D nextWeight;
layout(rgba32f) uniform image2D nextState;
layout(rgba32f) uniform image2D nextColor;
layout(r32ui) uniform uimage2D pathCount;

layout(location = 0) out vec4 lives;  // (1 if the path goes on, 0, 0, 0)
#else
// The path's next state in place.
layout(location = 0) out vec4 colorOut;
layout(location = 1) out vec4 weightOut;
layout(location = 2) out vec4 rayOriginOut;
layout(location = 3) out vec4 rayDirOut;
layout(location = 4) out vec4 pathStateOut;
#endif

// The sample's features: the surface pass has recorded them (pathScatter only closes them).
void recordFeatures(vec3 a, vec3 n) {}

#include "integrators/hooks.glsl"
#include "common/integrators/path.h"

// The path's next ray from its hit (common/integrators/path.h pathScatter), after the light that
// next-event estimation gathered there; false when it ends here.
bool nextRay(vec4 s, inout PathState st) {
    vec4 nm = readStream(surfaceNormal);
    vec4 view = readStream(surfaceView);
    vec4 shading = readStream(surfaceShading);
    SurfaceHit hit;
    vec3 v0, e1, e2;
    int material;
    fetchTriangle(int(s.w), v0, e1, e2, material);
    hit.p = s.xyz;
    hit.n = nm.xyz;
    hit.ns = shading.xyz;
    hit.front = frontFace(e1, e2, view.xyz);
    hit.m = materialFacing(fetchMaterialRecord(int(nm.w), int(s.w), vec2(view.w, shading.w), view.xyz), hit.front);
    st.d = view.xyz;
    vec4 local4 = readStream(localColor);
    vec3 local = local4.xyz;
    pathCross(st, hit, local4.w);  // the surface pass applied it to its own copy of the throughput
#ifdef SCENE_EMITTERS  // SceneTextures::bind: compiled out without emitters
    vec4 q = readStream(lightSample);
    if (q.w >= 0.0f && readStream(hitState).w < 0.0f) {  // the emitter point is not in shadow
        vec3 qv0, qe1, qe2;
        int emitterMaterial;
        fetchTriangle(int(q.w), qv0, qe1, qe2, emitterMaterial);
        local = local + pathEmitterContribution(hit.m, hit.p, hit.ns, st.d, q.xyz, qe1, qe2, fetchEmission(emitterMaterial),
                                                emitterArea);
    }
#endif
    pathAdd(st, local, depth);
    return pathScatter(st, hit, depth);
}

void main() {
    vec4 w = readStream(weightState);
#ifdef PACK
    lives = vec4(0.0f);
#else
    colorOut = readStream(colorState);
    weightOut = vec4(w.xyz, 0.0f);
    rayOriginOut = vec4(0.0f);
    rayDirOut = vec4(0.0f, 0.0f, 0.0f, GPURT_NO_RAY);
    pathStateOut = vec4(0.0f);
#endif
    if (w.w == 0.0f) return;  // no path in this element
    vec4 s = readStream(surfacePoint);
    vec4 ps = readStream(pathStateIn);
    ivec2 pixel = pathPixel(ps, depth);
    samplePixel = uvec2(pixel);
    PathState st;
    vec4 c = readStream(colorState);
    st.color = c.xyz;
    st.weight = w.xyz;
    st.open = ps.w == 0.0f;
    st.dispersed = c.w > 0.0f;
    // A path that missed in this round (its background added by the surface pass) ends.
    if (s.w < 0.0f || !nextRay(s, st)) {
        imageStore(pixelColor, pixel - ivec2(0, tileRow), vec4(st.color, 0.0f));  // the stream element of the pixel
        return;
    }
    vec4 origin = vec4(st.o, GPURT_FAR);
    vec4 direction = vec4(st.d, GPURT_A_RAY);
    vec4 state = vec4(st.prevPdf, float(pixel.x), float(pixel.y), st.open ? 0.0f : 1.0f);
#ifdef PACK
    uint k = imageAtomicAdd(pathCount, ivec2(0), 1u);
    int width = textureSize(colorState, 0).x;
    ivec2 at = ivec2(int(k) % width, int(k) / width);
    imageStore(nextOrigin, at, origin);
    imageStore(nextDir, at, direction);
    imageStore(nextWeight, at, vec4(st.weight, 1.0f));
    imageStore(nextState, at, state);
    imageStore(nextColor, at, vec4(st.color, st.dispersed ? 1.0f : 0.0f));
    lives = vec4(1.0f, 0.0f, 0.0f, 0.0f);
#else
    colorOut = vec4(st.color, st.dispersed ? 1.0f : 0.0f);
    weightOut = vec4(st.weight, 1.0f);
    rayOriginOut = origin;
    rayDirOut = direction;
    pathStateOut = state;
#endif
}
