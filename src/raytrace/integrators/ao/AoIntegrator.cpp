// Ambient occlusion (--integrator ao; glsl/common/integrators/ao.h) in the registry
// (integrators/Registry.h): its cpu sample over the cpu's hooks (its gl form: AoGl.cpp).
#include "raytrace/integrators/CpuHooks.h"
#include "raytrace/integrators/Registry.h"

#include <limits>

namespace gpurt {

namespace raymath {
namespace {

struct AoHooks : CpuHooks {
    AoHooks(const CpuScene& tracer, const PixelSample& px, const PunctualLights& lights, PixelAovs aovs,
            RenderStats& stats, float aoDistance)
        : CpuHooks(tracer, px, lights, aovs, stats), aoDistance(aoDistance) {}

    float aoDistance;

    vec4 integratorTrace(vec3 o, vec3 d, int b) { return traceClosest(o, d, b); }

#include "../../../../glsl/common/integrators/ao.h"
};

}  // namespace
}  // namespace raymath

namespace {

glm::vec3 cpuSample(const CpuScene& tracer, const PixelSample& px, glm::vec3 eye, glm::vec3 d,
                    const PunctualLights& lights, const RenderSettings& settings, PixelAovs aovs,
                    RenderStats& stats, SampleFeatures*) {
    raymath::AoHooks hooks(tracer, px, lights, aovs, stats, settings.integratorOptions.at("aoDistance"));
    return hooks.aoTrace(eye, d);
}

}  // namespace

const IntegratorInfo& aoIntegrator() {
    static const IntegratorInfo info = [] {
        IntegratorInfo i{Integrator("ao"), "ao (ambient occlusion, as pbrt's: the unoccluded fraction of the "
                                           "cosine-weighted hemisphere within --ao-distance; the clay render; one megakernel pass "
                                           "under any --kernel)"};
        i.options.push_back({"ao-distance", "aoDistance",
                             "Ambient occlusion: only what lies within this distance of a point occludes it (scene "
                             "units, > 0; default 'unlimited')",
                             std::numeric_limits<float>::infinity(), 0.0f, true});
        i.cpuSample = cpuSample;
        return i;
    }();
    return info;
}

}  // namespace gpurt
