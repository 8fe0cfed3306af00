// Whitted's integrator in the registry (integrators/Registry.h).
#include "raytrace/integrators/Registry.h"
#include "raytrace/integrators/whitted/WhittedCpu.h"
#include "raytrace/integrators/whitted/WhittedGl.h"
#include "raytrace/integrators/Megakernel.h"

#include <algorithm>

namespace gpurt {

namespace {

glm::vec3 cpuSample(const CpuTracer& tracer, const PixelSample& px, glm::vec3 eye, glm::vec3 d,
                    const std::vector<PointLight>& lights, const RenderSettings& settings, PixelAovs aovs,
                    RenderStats& stats, SampleFeatures*) {
    const int bounces = std::max(0, settings.maxBounces);
    return whittedSample(tracer, px, eye, d, lights, bounces, std::min(bounces, GPURT_STACK_SLOTS), aovs, stats);
}

std::unique_ptr<GlIntegrator> gl(const GlIntegratorSetup& s) {
    if (s.megakernel) {  // glsl/integrators/whitted/megakernel.frag: each pixel's tree in one pass
        auto k = std::make_unique<OnePassMegakernelGl>(s.pipeline, s.textures, "whittedMegakernel",
                                                       "integrators/whitted/megakernel.frag", s.maxLights, s.aovs);
        for (GPUKernel* pass : k->kernels()) pass->setUniform("stackSlots", s.stackSlots);
        return k;
    }
    return std::make_unique<WhittedGl>(s.pipeline, s.textures, s.stackSlots, s.spawns);
}

}  // namespace

const IntegratorInfo& whittedIntegrator() {
    static const IntegratorInfo info = [] {
        IntegratorInfo i{Integrator::Whitted,
                         "whitted (ray tree: shadows, mirror, glass; default)"};
        i.rayTree = true;
        i.cpuSample = cpuSample;
        i.gl = gl;
        i.hasWavefront = true;
        return i;
    }();
    return info;
}

}  // namespace gpurt
