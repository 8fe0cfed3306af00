#include "raytrace/integrators/whitted/WhittedCpu.h"

#include "raytrace/integrators/CpuHooks.h"

namespace gpurt {

namespace raymath {
namespace {

// One pixel's ray tree on the cpu: glsl/common/integrators/whitted.h over the cpu's hooks.
struct WhittedHooks : CpuHooks {
    WhittedHooks(const CpuScene& tracer, const PixelSample& px, const PunctualLights& lights,
                 PixelAovs aovs, RenderStats& stats, int maxBounces, int stackSlots)
        : CpuHooks(tracer, px, lights, aovs, stats), maxBounces(maxBounces), stackSlots(stackSlots) {}

    int maxBounces;
    int stackSlots;

    vec4 integratorTrace(vec3 o, vec3 d, int round) { return traceClosest(o, d, round); }

#include "../../../../glsl/common/integrators/whitted.h"
};

}  // namespace
}  // namespace raymath

glm::vec3 whittedSample(const CpuScene& t, const PixelSample& px, glm::vec3 eye, glm::vec3 d,
                        const PunctualLights& lights, int maxBounces, int stackSlots, PixelAovs aovs,
                        RenderStats& stats) {
    raymath::WhittedHooks hooks(t, px, lights, aovs, stats, maxBounces, stackSlots);
    int rounds;
    return hooks.whittedTrace(eye, d, rounds);
}

}  // namespace gpurt
