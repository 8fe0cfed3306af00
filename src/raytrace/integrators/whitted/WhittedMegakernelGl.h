// Whitted's integrator on the gl backend as a megakernel (--kernel megakernel): one pass takes
// each pixel's whole ray tree (glsl/integrators/whitted/megakernel.frag: trace, shading, shadow
// rays and the tree's pending rays in registers, as WhittedCpu does per pixel). Same rays, same
// order and same sums as the wavefront chain (WhittedGl).
#pragma once

#include "raytrace/GpuPipeline.h"
#include "raytrace/integrators/GlIntegrator.h"
#include "raytrace/integrators/Megakernel.h"

namespace gpurt {

class WhittedMegakernelGl final : public GlIntegrator {
  public:
    // stackSlots: the pending rays a tree keeps (GpuTracer::stackSlots); maxLights: the most
    // point lights a sample is given; aovs: the streams the pass writes the
    // primary AOVs to when it takes them (none: renders without AOVs).
    WhittedMegakernelGl(GpuPipeline& pipeline, const SceneTextures& textures, int stackSlots, size_t maxLights,
                        MegakernelAovs* aovs);

    void setSample(uint32_t s, uint32_t n, uint32_t seed) override;
    void sample(const std::vector<PointLight>& lights, int maxBounces, RenderOutput* aovs, RenderStats& stats) override;
    const GPUFloatArray& colour() const override { return colour_; }
    void accumulate() override { accumulate_.dispatch(); }
    std::vector<GPUKernel*> kernels() override;

  private:
    GpuPipeline& p_;
    MegakernelInputs inputs_;
    GPUFloatArray colour_;
    MegakernelAovs* aovs_;  // its streams: the AOV variant's outputs (none: no AOVs)
    uint32_t sampleCount_ = 1;
    // Through the sample points, through the pixel centres, and the latter with the AOVs.
    GPUKernel samples_, centres_, centresAovs_, accumulate_;
};

}  // namespace gpurt
