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

uniform sampler2D surfacePoint;
uniform sampler2D surfaceNormal;
uniform sampler2D surfaceView;
uniform sampler2D surfaceShading;
uniform sampler2D localColor;
uniform sampler2D colorState;   // the path's colour so far
uniform sampler2D weightState;  // (throughput, alive)
uniform sampler2D pathStateIn;  // (pdf of the ray's direction, pixel x, pixel y, 0)
uniform sampler2D hitState;     // the emitter shadow rays' hits
uniform sampler2D lightSample;  // (q, emitting triangle | -1): the emitter point of the hit
uniform uint sampleIndex;
uniform uint sampleCount;
uniform uint seed;
uniform uint samplerKind;
uniform int depth;  // the hits' depth (0: the camera rays' hits)
uniform float clampDirect;    // --clamp-direct (common/path.h clampContribution)
uniform float clampIndirect;  // --clamp-indirect
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

// The path's next ray from its hit; false when it ends here.
bool nextRay(vec4 s, vec3 w, ivec2 pixel, inout vec3 color, out vec3 throughput, out vec3 o, out vec3 dir,
             out float pdf) {
    vec4 nm = readStream(surfaceNormal);
    vec4 view = readStream(surfaceView);
    vec4 shading = readStream(surfaceShading);
    vec3 d = view.xyz;
    vec3 v0, e1, e2;
    int material;
    fetchTriangle(int(s.w), v0, e1, e2, material);
    MaterialRecord m = materialFacing(fetchMaterialRecord(int(nm.w), int(s.w), vec2(view.w, shading.w)), frontFace(e1, e2, d));
    vec3 n = shading.xyz;
    vec3 local = readStream(localColor).xyz;
#ifdef SCENE_EMITTERS  // SceneTextures::bind: compiled out without emitters
    vec4 q = readStream(lightSample);
    if (q.w >= 0.0f && readStream(hitState).w < 0.0f) {  // the emitter point is not in shadow
        vec3 qv0, qe1, qe2;
        int emitterMaterial;
        fetchTriangle(int(q.w), qv0, qe1, qe2, emitterMaterial);
        local = local + pathLightContribution(m, s.xyz, n, d, q.xyz, fetchEmission(emitterMaterial),
                                              emitterIntensity(s.xyz, q.xyz, qe1, qe2, emitterArea)) *
                            emitterSampleWeight(m, s.xyz, q.xyz, qe1, qe2, emitterArea, n, d);
    }
#endif
    color = color + clampContribution(w * local, depth, clampDirect, clampIndirect);

    uint dim = GPURT_DIM_SCATTER + 2u * uint(depth);
    vec2 u = sample2D(samplerKind, uint(pixel.x), uint(pixel.y), sampleIndex, sampleCount, seed, dim);
    vec2 choice = sampleChoice(samplerKind, uint(pixel.x), uint(pixel.y), sampleIndex, sampleCount, seed, dim + 1u);
    vec3 factor;
    float side;
    if (!materialSample(m, d, nm.xyz, n, frontFace(e1, e2, d), u, choice.x, dir, factor, pdf, side))
        return false;
    throughput = w * factor;
    if (!russianRoulette(depth, throughput, choice.y)) return false;
    o = offsetOrigin(s.xyz, side * nm.xyz, rayOffset);
    return true;
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
    vec3 color = readStream(colorState).xyz;
    vec3 throughput, o, dir;
    float pdf;
    // A path that missed in this round (its background added by the surface pass) ends.
    if (s.w < 0.0f || !nextRay(s, w.xyz, pixel, color, throughput, o, dir, pdf)) {
        imageStore(pixelColor, pixel - ivec2(0, tileRow), vec4(color, 0.0f));  // the stream element of the pixel
        return;
    }
    vec4 origin = vec4(o, GPURT_FAR);
    vec4 direction = vec4(dir, GPURT_A_RAY);
    vec4 state = vec4(pdf, float(pixel.x), float(pixel.y), featuresOpenAfter(ps.w == 0.0f, pdf) ? 0.0f : 1.0f);
#ifdef PACK
    uint k = imageAtomicAdd(pathCount, ivec2(0), 1u);
    int width = textureSize(colorState, 0).x;
    ivec2 at = ivec2(int(k) % width, int(k) / width);
    imageStore(nextOrigin, at, origin);
    imageStore(nextDir, at, direction);
    imageStore(nextWeight, at, vec4(throughput, 1.0f));
    imageStore(nextState, at, state);
    imageStore(nextColor, at, vec4(color, 0.0f));
    lives = vec4(1.0f, 0.0f, 0.0f, 0.0f);
#else
    colorOut = vec4(color, 0.0f);
    weightOut = vec4(throughput, 1.0f);
    rayOriginOut = origin;
    rayDirOut = direction;
    pathStateOut = state;
#endif
}
