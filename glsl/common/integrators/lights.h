// Whether a light sample reaches a hit, for the integrators that trace their own shadow rays (the
// cpu backend, the megakernels; the wavefront chain's shadowgen and light passes take the same
// steps as passes), written once. Hooks (common/integrators/README.md): rayOffset,
// sceneHasEmitters, environmentSampled, pixelSample2D, unblockedRay, sampleEnvironment,
// emitterPointAt.
#ifndef GPURT_INTEGRATOR_LIGHTS_H
#define GPURT_INTEGRATOR_LIGHTS_H

// Whether light L lights the hit p (facing normal n): within its cone and range, in front of p,
// and its shadow ray unblocked; with the point light that stands for it at p (shading.h
// punctualAsPoint: its position and intensity).
GPURT_FN bool lightVisible(PunctualLight L, vec3 p, vec3 n, GPURT_OUT(vec3) position, GPURT_OUT(float) intensity) {
    if (!punctualAsPoint(L, p, position, intensity) || !lightInFront(p, n, position)) return false;
    vec3 o;
    vec3 d;
    float limit;
    punctualShadowRay(L, p, n, rayOffset, position, o, d, limit);
    return unblockedRay(o, d, limit);
}

// The environment direction l (solid-angle pdf) that the pixel's sample draws at hit depth b
// (sampling.h GPURT_DIM_ENVIRONMENT + b), and whether it lights p: above the surface and
// unblocked. False when the environment is not sampled (--env-sampling bsdf, or none).
GPURT_FN bool environmentVisible(int b, vec3 p, vec3 n, GPURT_OUT(vec3) l, GPURT_OUT(float) pdf) {
    if (!environmentSampled) return false;
    vec2 u = pixelSample2D(GPURT_DIM_ENVIRONMENT + uint(b));
    if (!sampleEnvironment(u, l, pdf) || !(dot(n, l) > 0.0f)) return false;
    return unblockedRay(offsetOrigin(p, n, rayOffset), l, GPURT_FAR);
}

// The emitter point q (on a triangle of edges e1, e2 and the given emission) that the pixel's
// sample draws at hit depth b (GPURT_DIM_EMITTER + b; uniform by area), and whether it lights p:
// in front of it and unblocked. False without emitters.
GPURT_FN bool emitterVisible(int b, vec3 p, vec3 n, GPURT_OUT(vec3) q, GPURT_OUT(vec3) e1, GPURT_OUT(vec3) e2,
                             GPURT_OUT(vec3) emission) {
    if (!sceneHasEmitters) return false;
    emitterPointAt(pixelSample2D(GPURT_DIM_EMITTER + uint(b)), q, e1, e2, emission);
    if (!lightInFront(p, n, q)) return false;
    vec3 o;
    vec3 d;
    float limit;
    emitterShadowRay(p, n, rayOffset, q, o, d, limit);
    return unblockedRay(o, d, limit);
}

#endif
