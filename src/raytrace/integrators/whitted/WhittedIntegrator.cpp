// Whitted's integrator in the registry (integrators/Registry.h).
#include "raytrace/integrators/Registry.h"
#include "raytrace/integrators/whitted/WhittedCpu.h"

#include <algorithm>

namespace gpurt {

namespace {

glm::vec3 cpuSample(const CpuScene& tracer, const PixelSample& px, glm::vec3 eye, glm::vec3 d,
                    const PunctualLights& lights, const RenderSettings& settings, PixelAovs aovs,
                    RenderStats& stats, SampleFeatures*) {
    const int bounces = std::max(0, settings.maxBounces);
    return whittedSample(tracer, px, eye, d, lights, bounces, std::min(bounces, GPURT_STACK_SLOTS), aovs, stats);
}

}  // namespace

const IntegratorInfo& whittedIntegrator() {
    static const IntegratorInfo info = [] {
        IntegratorInfo i{Integrator::Whitted,
                         "whitted (ray tree: shadows, mirror, glass; default)"};
        i.rayTree = true;
        i.cpuSample = cpuSample;
        i.hasWavefront = true;
        return i;
    }();
    return info;
}

}  // namespace gpurt
