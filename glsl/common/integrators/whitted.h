// Whitted's integrator's control flow (--integrator whitted), written once: the cpu backend
// (integrators/whitted/WhittedCpu.cpp) and the megakernel (glsl/integrators/whitted/megakernel.frag)
// run it; the wavefront chain takes the same steps one round a pass (surface, shadowgen, light and
// bounce passes, the stacks in images). A pixel's ray tree (Whitted 1980): at each hit the
// emission, the ambient term, each visible point light and the round's emitter point, then up to
// two children (mirror, glass: materialChildren), the tree walked depth first with its pending
// rays on a stack (common/raytree.h).
//
// The includer defines the hooks first (common/integrators/README.md): rayOffset, emitterArea,
// background, sceneHasEnvironment, punctualLightCount, maxBounces, stackSlots; environmentRadiance,
// environmentAmbient; integratorTrace, surfaceAt, recordPrimary, punctualLight, lightVisible,
// emitterVisible.
#ifndef GPURT_INTEGRATOR_WHITTED_H
#define GPURT_INTEGRATOR_WHITTED_H

#ifndef GPURT_RAYTREE_H
#error "include common/material.h (and with it common/raytree.h) before common/integrators/whitted.h"
#endif

// The local colour at surface s hit along d in round `round`: the material's ambient term (under
// an environment: the diffuse reflection of its irradiance at the shading normal), each visible
// punctual light's term, and the round's emitter point's.
GPURT_FN vec3 whittedLocal(SurfaceHit s, vec3 d, int round) {
    vec3 local = sceneHasEnvironment ? materialEnvironmentAmbient(s.m, environmentAmbient(s.ns)) : materialAmbient(s.m);
    for (int k = 0; k < punctualLightCount; ++k) {
        PunctualLight light = punctualLight(k);
        vec3 position;
        float intensity;
        if (lightVisible(light, s.p, s.n, position, intensity))
            local = local + materialLight(s.m, s.p, s.ns, d, position, light.color, intensity);
    }
    vec3 q;
    vec3 e1;
    vec3 e2;
    vec3 emission;
    if (emitterVisible(round, s.p, s.n, q, e1, e2, emission))
        local = local + materialLight(s.m, s.p, s.ns, d, q, emission, emitterIntensity(s.p, q, e1, e2, emitterArea));
    return local;
}

// The colour of the ray tree of the camera ray o + t d; rounds: the round of its last ray (the
// rays traced, less one). maxBounces < 0: the camera ray's emission only (the AOVs' pass).
GPURT_FN vec3 whittedTrace(vec3 o, vec3 d, GPURT_OUT(int) rounds) {
    vec3 color = vec3(0.0f);
    vec3 weight = vec3(1.0f);
    vec3 stackOrigin[GPURT_STACK_SLOTS];
    vec3 stackDir[GPURT_STACK_SLOTS];
    vec3 stackWeight[GPURT_STACK_SLOTS];
    int stackDepth[GPURT_STACK_SLOTS];
    int height = 0;
    int depth = 0;
    int rays = 1;
    int round = 0;
    for (;; ++round) {  // the ray's place in the tree's order: its wavefront round
        vec4 h = integratorTrace(o, d, round);
        int children = 0;
        vec3 dirA;
        vec3 weightA;
        vec3 dirB;
        vec3 weightB;
        float sideA = 1.0f;
        vec3 p = vec3(0.0f);
        vec3 n = vec3(0.0f);
        if (h.w < 0.0f) {
            color = color + weight * (sceneHasEnvironment ? environmentRadiance(d) : background);
        } else {
            SurfaceHit s = surfaceAt(h, o, d);
            if (round == 0) recordPrimary(h, s.n);
            p = s.p;
            n = s.n;
            weight = weight * materialTransmittance(s.m, h.x);  // the medium the ray crossed
            color = color + weight * materialEmitted(s.m, s.ns, d);
            if (maxBounces < 0) break;
            color = color + weight * whittedLocal(s, d, round);
            if (rayTreeMaySpawn(depth, rays, maxBounces) && materialSpawns(s.m))
                children = materialChildren(s.m, d, s.n, s.ns, s.front, weight, dirA, weightA, sideA, dirB, weightB);
        }
        bool push;
        int next = rayTreeNext(children, stackSlots, depth, height, rays, push);
        if (next == GPURT_TREE_DONE) break;
        if (next == GPURT_TREE_POP) {  // the pending ray on top of the stack
            o = stackOrigin[height];
            d = stackDir[height];
            weight = stackWeight[height];
            depth = stackDepth[height];
            continue;
        }
        if (push) {
            stackOrigin[height - 1] = offsetOrigin(p, n, rayOffset);
            stackDir[height - 1] = dirB;
            stackWeight[height - 1] = weightB;
            stackDepth[height - 1] = depth;
        }
        o = offsetOrigin(p, sideA * n, rayOffset);
        d = dirA;
        weight = weightA;
    }
    rounds = round;
    return color;
}

#endif
