// The path integrator in the registry (integrators/Registry.h).
#include "raytrace/integrators/Registry.h"
#include "raytrace/integrators/path/PathCpu.h"

#include <algorithm>

namespace gpurt {

namespace {

glm::vec3 cpuSample(const CpuScene& tracer, const PixelSample& px, glm::vec3 eye, glm::vec3 d,
                    const PunctualLights& lights, const RenderSettings& settings, PixelAovs aovs,
                    RenderStats& stats, SampleFeatures* features) {
    return pathSample(tracer, px, eye, d, lights, std::max(0, settings.maxBounces),
                      {settings.clampDirect, settings.clampIndirect}, aovs, stats, features);
}

}  // namespace

const IntegratorInfo& pathIntegrator() {
    static const IntegratorInfo info = [] {
        IntegratorInfo i{Integrator::Path, "path (path tracing with next-event estimation; --bounces is then the "
                                           "longest path, default 8)"};
        i.pathStreams = true;
        i.adaptive = true;
        i.features = true;
        i.clamps = true;
        i.defaultBounces = kDefaultPathBounces;
        i.cpuSample = cpuSample;
        i.hasWavefront = true;
        return i;
    }();
    return info;
}

}  // namespace gpurt
