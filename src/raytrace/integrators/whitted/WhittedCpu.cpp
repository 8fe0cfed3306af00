#include "raytrace/integrators/whitted/WhittedCpu.h"

namespace gpurt {

using namespace raymath;

namespace {

// The local colour at a hit (light.frag, its EMITTER variant): the material's ambient term (under
// an environment: the diffuse reflection of its irradiance at the shading normal), each
// point light's term where it is visible, and the round's emitter point's.
glm::vec3 whittedLocal(const CpuTracer& t, const PixelSample& px, const CpuTracer::Surface& s, glm::vec3 d,
                       const std::vector<PointLight>& lights, int round, RenderStats& stats) {
    glm::vec3 local = t.environment().empty() ? materialAmbient(s.material)
                                              : materialEnvironmentAmbient(s.material, t.environment().irradiance(s.ns));
    for (const PointLight& light : lights)
        if (t.lightVisible(s.p, s.n, light.position, px.coverageKey(), stats))
            local += materialLight(s.material, s.p, s.ns, d, light.position, light.color, light.intensity);
    vec3 q;
    uint32_t id;
    if (t.emitterVisible(px, round, s.p, s.n, stats, q, id)) {
        const CpuTracer::PreparedTriangle& e = t.triangle(id);
        local += materialLight(s.material, s.p, s.ns, d, q, t.scene().materials[t.scene().materialIds[id]].emission,
                               emitterIntensity(s.p, q, e.e1, e.e2, t.emitters().totalArea));
    }
    return local;
}

}  // namespace

glm::vec3 whittedSample(const CpuTracer& t, const PixelSample& px, glm::vec3 eye, glm::vec3 d,
                        const std::vector<PointLight>& lights, int maxBounces, int stackSlots, PixelAovs aovs,
                        RenderStats& stats) {
    struct Pending {
        glm::vec3 o, d, weight;
        int depth;
    };
    Pending stack[GPURT_STACK_SLOTS];
    glm::vec3 o = eye, color(0.0f), weight(1.0f);
    int height = 0, depth = 0, rays = 1;
    for (int round = 0;; ++round) {  // the ray's place in the tree's order: its GL round
        const TraceHit hit = t.trace(o, d, GPURT_FAR, px.coverageKey());
        ++(round == 0 ? stats.primaryRays : stats.secondaryRays);
        if (round == 0 && aovs.out) aovs.out->steps[aovs.pixel] = static_cast<float>(hit.steps);
        if (hit.state == RAY_OVERFLOW) ++stats.overflowRays;
        int children = 0;
        vec3 dirA, weightA, dirB, weightB;
        float sideA = 1.0f;
        CpuTracer::Surface s{};
        if (hit.prim < 0) {
            color += weight * (t.environment().empty() ? t.scene().background : t.environment().radiance(d));
        } else {
            s = t.surfaceAt(hit, o, d);
            color += weight * materialEmitted(s.material, s.ns);
            if (round == 0 && aovs.out) aovs.write(hit.t, static_cast<float>(hit.prim), s.n);
            if (maxBounces < 0) break;
            color += weight * whittedLocal(t, px, s, d, lights, round, stats);
            if (rayTreeMaySpawn(depth, rays, maxBounces) && materialSpawns(s.material)) {
                const CpuTracer::PreparedTriangle& tri = t.triangle(uint32_t(hit.prim));
                children = materialChildren(s.material, d, s.n, s.ns, frontFace(tri.e1, tri.e2, d), weight, dirA,
                                            weightA, sideA, dirB, weightB);
            }
        }
        bool push;
        const int next = rayTreeNext(children, stackSlots, depth, height, rays, push);
        if (next == GPURT_TREE_DONE) break;
        if (next == GPURT_TREE_POP) {  // the pending ray on top of the stack
            const Pending& top = stack[height];
            o = top.o;
            d = top.d;
            weight = top.weight;
            depth = top.depth;
            continue;
        }
        if (push) stack[height - 1] = {offsetOrigin(s.p, s.n, t.rayOffset()), dirB, weightB, depth};
        o = offsetOrigin(s.p, sideA * s.n, t.rayOffset());
        d = dirA;
        weight = weightA;
    }
    return color;
}

}  // namespace gpurt
