// Ambient occlusion (--integrator ao), written once for the cpu backend
// (integrators/ao/AoIntegrator.cpp) and the kernel (glsl/integrators/ao/megakernel.frag): the clay
// render people use to judge geometry, as pbrt-v4's AOIntegrator. A camera ray that hits a surface
// sends one ray in a cosine-weighted direction about the geometric normal facing it; the sample
// is 1 when nothing blocks that ray within aoDistance (--ao-distance; GPURT_FAR: unlimited), else
// 0, so that a pixel's mean is the unoccluded fraction of the cosine-weighted hemisphere (1 where
// nothing is near). A camera ray that leaves the scene is 0, as in pbrt. Materials play no part:
// every surface occludes (alpha coverage still cuts holes).
// Hooks (common/integrators/README.md): rayOffset, aoDistance, pixelSample2D, integratorTrace,
// surfaceAt, recordPrimary, unblockedRay.
#ifndef GPURT_INTEGRATOR_AO_H
#define GPURT_INTEGRATOR_AO_H

#ifndef GPURT_PATH_H
#error "include common/path.h (the sample dimensions) before common/integrators/ao.h"
#endif

// The ambient occlusion sample of the camera ray o + t d.
GPURT_FN vec3 aoTrace(vec3 o, vec3 d) {
    vec4 h = integratorTrace(o, d, 0);
    if (h.w < 0.0f) return vec3(0.0f);
    SurfaceHit s = surfaceAt(h, o, d);
    recordPrimary(h, s.n);
    vec2 u = pixelSample2D(GPURT_DIM_SCATTER);
    vec3 l = directionAbout(s.n, sqrt(1.0f - u.x), u.y);
    return unblockedRay(offsetOrigin(s.p, s.n, rayOffset), l, aoDistance) ? vec3(1.0f) : vec3(0.0f);
}

#endif
