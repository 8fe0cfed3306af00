// The path integrator's last step of a round (common/path.h): colour += throughput * the light
// that next-event estimation gathered at the hit (the point lights' in localColor, and the
// emitter point's, whose shadow ray the last trace answered, added here: the light pass of the
// emitters fused into this one), then the path's next ray: a direction from the
// BSDF (scatterPath, the sample's numbers of this depth), the throughput times f cos / pdf, and
// Russian roulette. A path that ends (missed, absorbed, below the surface, roulette) writes no ray,
// so the next round's trace and its count skip it (GpuTracer::tracePath).
#include "shading.glsl"
#include "../common/sampling.h"
#include "../common/path.h"

uniform sampler2D surfacePoint;
uniform sampler2D surfaceNormal;
uniform sampler2D surfaceView;
uniform sampler2D surfaceShading;
uniform sampler2D localColor;
uniform sampler2D colorState;   // in place
uniform sampler2D weightState;  // in place: (throughput, alive)
uniform sampler2D hitState;     // the emitter shadow rays' hits
uniform sampler2D lightSample;  // (q, emitting triangle | -1): the emitter point of the hit
uniform uint sampleIndex;
uniform uint sampleCount;
uniform uint seed;
uniform int depth;  // the hits' depth (0: the camera rays' hits)

layout(location = 0) out vec4 color;
layout(location = 1) out vec4 weight;
layout(location = 2) out vec4 rayOrigin;
layout(location = 3) out vec4 rayDir;
layout(location = 4) out vec4 pathState;  // (pdf of the new direction, 0, 0, 0)

void main() {
    vec4 s = readStream(surfacePoint);
    vec4 w = readStream(weightState);
    color = readStream(colorState);
    weight = vec4(w.xyz, 0.0f);
    rayOrigin = vec4(0.0f);
    rayDir = vec4(0.0f, 0.0f, 0.0f, GPURT_NO_RAY);
    pathState = vec4(0.0f);
    if (w.w == 0.0f || s.w < 0.0f) return;  // ended before, or missed in this round
    vec3 throughput = w.xyz;
    vec4 nm = readStream(surfaceNormal);
    vec3 kd, ks, reflectivity, tf, diffuse, glossy;
    float ns, ior;
    fetchMaterial(int(nm.w), kd, ks, ns, reflectivity);
    fetchDielectric(int(nm.w), tf, ior);
    pathLobes(kd, ks, reflectivity, ior, diffuse, glossy);
    vec3 d = readStream(surfaceView).xyz;
    vec3 n = readStream(surfaceShading).xyz;
    vec3 local = readStream(localColor).xyz;
    vec4 q = emitterCount > 0 ? readStream(lightSample) : vec4(-1.0f);
    if (q.w >= 0.0f && readStream(hitState).w < 0.0f) {  // the emitter point is not in shadow
        vec3 qv0, qe1, qe2;
        int emitterMaterial;
        fetchTriangle(int(q.w), qv0, qe1, qe2, emitterMaterial);
        vec3 probs = lobeProbabilities(diffuse, glossy, reflectivity, ior);
        local = local + pathLightContribution(s.xyz, n, d, diffuse, glossy, ns, q.xyz, fetchEmission(emitterMaterial),
                                              emitterIntensity(s.xyz, q.xyz, qe1, qe2, emitterArea)) *
                            emitterSampleWeight(s.xyz, q.xyz, qe1, qe2, emitterArea, probs, ns, n, d);
    }
    color = vec4(color.xyz + throughput * local, 0.0f);

    vec3 v0, e1, e2;
    int material;
    fetchTriangle(int(s.w), v0, e1, e2, material);
    uvec2 pixel = uvec2(gl_FragCoord.xy);
    uint dim = GPURT_DIM_SCATTER + 2u * uint(depth);
    vec2 u = cmjSample(sampleIndex, sampleCount, samplePattern(pixel.x, pixel.y, seed, dim));
    vec2 choice = randomPair(sampleIndex, samplePattern(pixel.x, pixel.y, seed, dim + 1u));
    vec3 dir, factor;
    float pdf, side;
    if (!scatterPath(d, nm.xyz, n, frontFace(e1, e2, d), diffuse, glossy, ns,
                     reflectivity, ior, tf, u, choice.x, dir, factor, pdf, side))
        return;
    throughput = throughput * factor;
    float survive = survival(depth, throughput, choice.y);
    if (survive == 0.0f) return;
    throughput = throughput / survive;
    vec3 o = offsetOrigin(s.xyz, side * nm.xyz, rayOffset);
    weight = vec4(throughput, 1.0f);
    rayOrigin = vec4(o, GPURT_FAR);
    rayDir = vec4(dir, gridEntry(o, dir, GPURT_FAR));
    pathState = vec4(pdf, 0.0f, 0.0f, 0.0f);
}
