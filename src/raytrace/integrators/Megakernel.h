// What the megakernel integrators (integrators/path/PathMegakernelGl, OnePassMegakernelGl below)
// share: a megakernel pass's scene, accelerator and light inputs, the point lights' texture, and
// the pass's counters (glsl/integrators/megakernel.glsl) read into RenderStats.
#pragma once

#include "raytrace/integrators/GpuPipeline.h"
#include "raytrace/common/RenderTypes.h"
#include "raytrace/textures/SceneTextures.h"
#include "raytrace/accel/GlAccelerator.h"
#include "raytrace/integrators/GlIntegrator.h"
#include "stream/GPUFloatArray.h"
#include "stream/GPUKernel.h"

#include <cstdint>
#include <vector>

namespace gpurt {

class MegakernelInputs {
  public:
    // maxLights: the most point lights a sample is given.
    explicit MegakernelInputs(size_t maxLights);

    // The scene's textures and defines, the accelerator traced inside, the point lights and the
    // counters as inputs of megakernel pass `k`.
    void declare(GPUKernel& k, const SceneTextures& textures, const GlAccelerator& accel);
    // The lights of the sample into the texture (when they changed) and their count into `kernels`.
    // Throws UsageError for more than maxLights.
    void setLights(const std::vector<Light>& lights, const std::vector<GPUKernel*>& kernels);
    // Runs pass `k` with the counters zeroed and reads them: the rays of each depth from
    // `firstDepth` on (primary at depth 0, secondary deeper; with livePaths, also per depth as the
    // path integrator's live paths) and the shadow rays into stats. Returns the paths it packed.
    uint64_t run(GPUKernel& k, int firstDepth, bool livePaths, RenderStats& stats);

  private:
    size_t maxLights_;
    GPUFloatArray counters_, punctualLights_;
    std::vector<float> uploaded_;  // the light texels last uploaded
};

// The pixel centres' primary AOVs in one pass (glsl/integrators/aovs.frag) for the renders whose
// integrators are megakernels, where no wavefront round traces and shades them: the hits into
// the pipeline's hit stream, the facing normals into normals(), the step counts into steps().
class MegakernelAovs {
  public:
    MegakernelAovs(GpuPipeline& pipeline, const SceneTextures& textures);
    // Traces them (counted as primary rays); with `out`, reads them into it as well.
    void trace(RenderOutput* out, RenderStats& stats);
    // The step counts (RGBA32I, w) and the facing normals, also the megakernels' AOV variants'
    // outputs.
    GPUFloatArray& steps() { return steps_; }
    GPUFloatArray& normals() { return normals_; }
    std::vector<GPUKernel*> kernels() { return {&kernel_}; }

  private:
    GpuPipeline& p_;
    MegakernelInputs inputs_;
    GPUFloatArray steps_, normals_;
    GPUKernel kernel_;
};

// An integrator whose megakernel takes each pixel's whole sample in one pass (Whitted's ray tree:
// glsl/integrators/whitted/megakernel.frag; ambient occlusion: ao/megakernel.frag): the kernel
// writes the sample's colour, and with AOVS the camera rays' AOVs (the variant run for one sample
// a pixel with AOVs). Its uniform maxBounces is the sample's bounces.
class OnePassMegakernelGl final : public GlIntegrator {
  public:
    // name: the passes' name; kernel: the megakernel's GLSL file; maxLights: the most point lights
    // a sample is given; aovs: the streams the pass writes the primary AOVs to when it takes them
    // (none: renders without AOVs).
    OnePassMegakernelGl(GpuPipeline& pipeline, const SceneTextures& textures, const std::string& name,
                        const std::string& kernel, size_t maxLights, MegakernelAovs* aovs);

    void setSample(uint32_t s, uint32_t n, uint32_t seed) override;
    void sample(const std::vector<Light>& lights, int maxBounces, RenderOutput* aovs, RenderStats& stats) override;
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
