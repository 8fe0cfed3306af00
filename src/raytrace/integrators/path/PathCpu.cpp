#include "raytrace/integrators/path/PathCpu.h"

namespace gpurt {

using namespace raymath;

namespace {

// Next-event estimation at a hit (shadowgen.frag and light.frag PATH and ENVIRONMENT, the
// emitter's part of path/bounce.frag): each visible point light through the BSDF, the round's
// environment direction and emitter point, each weighed against the BSDF's sampling of it.
glm::vec3 directLight(const CpuTracer& t, const PixelSample& px, const CpuTracer::Surface& s, glm::vec3 d,
                      const std::vector<PointLight>& lights, int depth, RenderStats& stats) {
    glm::vec3 local(0.0f);
    for (const PointLight& light : lights)
        if (t.lightVisible(s.p, s.n, light.position, px.coverageKey(), stats))
            local += pathLightContribution(s.material, s.p, s.ns, d, light.position, light.color, light.intensity);
    vec3 l;
    float pdf;
    if (t.environmentVisible(px, depth, s.p, s.n, stats, l, pdf))
        local += pathEnvironmentContribution(s.material, s.ns, d, l, t.environment().radiance(l), pdf);
    vec3 q;
    uint32_t id;
    if (t.emitterVisible(px, depth, s.p, s.n, stats, q, id)) {
        const CpuTracer::PreparedTriangle& e = t.triangle(id);
        const float area = t.emitters().totalArea;
        local += pathLightContribution(s.material, s.p, s.ns, d, q, t.scene().materials[t.scene().materialIds[id]].emission,
                                       emitterIntensity(s.p, q, e.e1, e.e2, area)) *
                 emitterSampleWeight(s.material, s.p, q, e.e1, e.e2, area, s.ns, d);
    }
    return local;
}

}  // namespace

glm::vec3 pathSample(const CpuTracer& t, const PixelSample& px, glm::vec3 eye, glm::vec3 d,
                     const std::vector<PointLight>& lights, int maxDepth, PathClamp clamp, PixelAovs aovs,
                     RenderStats& stats, SampleFeatures* features) {
    glm::vec3 o = eye, color(0.0f), weight(1.0f);
    float prevPdf = 0.0f;  // the camera ray: its emission counts in full
    bool open = features != nullptr;  // the sample's features are still to be recorded
    for (int b = 0;; ++b) {
        const TraceHit hit = t.trace(o, d, GPURT_FAR, px.coverageKey());
        stats.addLivePaths(size_t(b), 1);
        ++(b == 0 ? stats.primaryRays : stats.secondaryRays);
        if (hit.state == RAY_OVERFLOW) ++stats.overflowRays;
        if (b == 0 && aovs.out) aovs.out->steps[aovs.pixel] = static_cast<float>(hit.steps);
        if (hit.prim < 0) {
            if (open) *features = {glm::vec3(GPURT_BACKGROUND_ALBEDO), glm::vec3(0.0f)};
            const glm::vec3 sky = t.environment().empty()
                                      ? t.scene().background
                                      : t.environment().radiance(d) * environmentHitWeight(prevPdf, t.environment().pdf(d));
            color += clampContribution(weight * sky, b, clamp.direct, clamp.indirect);
            break;
        }
        const CpuTracer::Surface s = t.surfaceAt(hit, o, d);
        if (open) *features = {materialAlbedo(s.material), s.ns};
        if (b == 0 && aovs.out) aovs.write(hit.t, static_cast<float>(hit.prim), s.n);
        const float mis = s.material.emitterLight ? emissionWeight(prevPdf, hit.t, s.n, d, t.emitters().totalArea) : 1.0f;
        color += clampContribution(weight * (materialEmitted(s.material, s.ns) * mis), b, clamp.direct, clamp.indirect);
        if (b == maxDepth) break;
        if (materialLit(s.material))
            color += clampContribution(weight * directLight(t, px, s, d, lights, b, stats), b, clamp.direct, clamp.indirect);

        // The next direction (path/bounce.frag).
        const uint32_t dim = GPURT_DIM_SCATTER + 2u * uint32_t(b);
        const vec2 u = px.sample2D(dim);
        const vec2 choice = px.sampleChoice(dim + 1u);
        const CpuTracer::PreparedTriangle& tri = t.triangle(uint32_t(hit.prim));
        vec3 dir, factor;
        float pdf, side;
        if (!materialSample(s.material, d, s.n, s.ns, frontFace(tri.e1, tri.e2, d), u, choice.x, dir, factor, pdf, side))
            break;
        weight *= factor;
        open = featuresOpenAfter(open, pdf);
        if (!russianRoulette(b, weight, choice.y)) break;
        prevPdf = pdf;
        o = offsetOrigin(s.p, side * s.n, t.rayOffset());
        d = dir;
    }
    return color;
}

}  // namespace gpurt
