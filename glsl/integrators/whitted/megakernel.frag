// Whitted's integrator as a megakernel (--kernel megakernel): each pixel's whole ray tree in this
// one pass, as WhittedCpu does per pixel (word for word: the same rays in the same order, its
// pending rays on a stack in registers): trace (the accelerator inside, accel/trace.glsl),
// emission, the ambient term, each point light and the round's emitter point with its shadow ray,
// then the tree's next ray (common/raytree.h). The wavefront chain (surface, shadowgen, light,
// bounce passes, one round a ray of each tree) writes each step to streams and the stacks to
// images. AOVS: the primary hit, facing normal and step count as well.
#include "integrators/megakernel.glsl"
#include "common/raytree.h"

uniform int maxBounces;  // mirror and glass levels (--bounces)
uniform int stackSlots;  // the pending rays a tree keeps (GpuTracer::stackSlots)

layout(location = 0) out vec4 colorOut;  // (the sample's colour, 0)
#ifdef AOVS
layout(location = 1) out vec4 hitOut;     // (t, u, v, triangle | -1) of the camera ray
layout(location = 2) out vec4 normalOut;  // (facing geometric normal, 0)
layout(location = 3) out ivec4 stepsOut;  // w: the cells or nodes its trace visited
#endif

// The local colour at surface s hit along d (WhittedCpu whittedLocal): the material's ambient term
// (under an environment: the diffuse reflection of its irradiance at the shading normal), each
// point light's term where it is visible, and the round's emitter point's.
vec3 whittedLocal(uvec2 pixel, SurfaceHit s, vec3 d, int round) {
#ifdef SCENE_ENVIRONMENT
    vec3 local = materialEnvironmentAmbient(s.m, environmentAmbient(s.ns));
#else
    vec3 local = materialAmbient(s.m);
#endif
    for (int k = 0; k < pointLightCount; ++k) {
        vec3 position, color;
        float intensity;
        pointLight(k, position, color, intensity);
        if (lightVisible(s.p, s.n, position)) local = local + materialLight(s.m, s.p, s.ns, d, position, color, intensity);
    }
#ifdef SCENE_EMITTERS
    vec3 q;
    int id;
    if (emitterVisible(pixel, round, s.p, s.n, q, id)) {
        vec3 v0, e1, e2;
        int material;
        fetchTriangle(id, v0, e1, e2, material);
        local = local + materialLight(s.m, s.p, s.ns, d, q, fetchEmission(material), emitterIntensity(s.p, q, e1, e2, emitterArea));
    }
#endif
    return local;
}

void main() {
    uvec2 pixel = imagePixel();
    setPixelCoverage(pixel);
#ifdef PIXEL_CENTRE
    vec3 d = primaryDirection();
#else
    vec3 d = sampleDirection();
#endif
    vec3 o = eye;
    vec3 color = vec3(0.0f);
    vec3 weight = vec3(1.0f);
    vec3 stackOrigin[GPURT_STACK_SLOTS];
    vec3 stackDir[GPURT_STACK_SLOTS];
    vec3 stackWeight[GPURT_STACK_SLOTS];
    int stackDepth[GPURT_STACK_SLOTS];
    int height = 0, depth = 0, rays = 1;
    int round = 0;
    for (;; ++round) {  // the ray's place in the tree's order: its wavefront round
        int steps;
        vec4 h = traceClosest(o, d, GPURT_FAR, round == 0, steps);
#ifdef AOVS
        if (round == 0) {
            hitOut = h;
            stepsOut = ivec4(0, 0, 0, steps);
            normalOut = vec4(0.0f);
        }
#endif
        int children = 0;
        vec3 dirA, weightA, dirB, weightB;
        float sideA = 1.0f;
        vec3 p = vec3(0.0f), n = vec3(0.0f);
        if (h.w < 0.0f) {
#ifdef SCENE_ENVIRONMENT
            color = color + weight * environmentRadiance(d);
#else
            color = color + weight * background;
#endif
        } else {
            SurfaceHit s = surfaceAt(h, o, d);
#ifdef AOVS
            if (round == 0) normalOut = vec4(s.n, 0.0f);
#endif
            p = s.p;
            n = s.n;
            color = color + weight * materialEmitted(s.m, s.ns);
            color = color + weight * whittedLocal(pixel, s, d, round);
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
    countRays(round);
    colorOut = vec4(color, 0.0f);
}
