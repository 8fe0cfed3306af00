#include "raytrace/integrators/whitted/WhittedMegakernelGl.h"

#include "raytrace/integrators/SharedPasses.h"
#include "stream/StreamErrors.h"

namespace gpurt {

WhittedMegakernelGl::WhittedMegakernelGl(GpuPipeline& pipeline, const SceneTextures& textures, int stackSlots,
                                         size_t maxLights, MegakernelAovs* aovs)
    : p_(pipeline),
      inputs_(maxLights),
      colour_(p_.width, p_.height, 4, "whittedColour"),
      aovs_(aovs),
      samples_("whittedMegakernel", "integrators/whitted/megakernel.frag"),
      centres_("whittedMegakernel", "integrators/whitted/megakernel.frag", passDefines(kPixelCentre)),
      centresAovs_("whittedMegakernel", "integrators/whitted/megakernel.frag", passDefines(kPixelCentre | kAovPass)),
      accumulate_("whittedMegakernelAccumulate", "integrators/accumulate.frag") {
    for (GPUKernel* k : {&samples_, &centres_, &centresAovs_}) {
        inputs_.declare(*k, textures, p_.accel);
        k->addOutput(colour_).setUniform("stackSlots", stackSlots);
    }
    if (aovs_) centresAovs_.addOutput(p_.hit).addOutput(aovs_->normals()).addOutput(aovs_->steps());
    declareAccumulatePass(accumulate_, p_, colour_);
}

std::vector<GPUKernel*> WhittedMegakernelGl::kernels() { return {&samples_, &centres_, &centresAovs_, &accumulate_}; }

void WhittedMegakernelGl::setSample(uint32_t s, uint32_t n, uint32_t seed) {
    for (GPUKernel* k : {&samples_, &centres_, &centresAovs_})
        k->setUniform("sampleIndex", unsigned(s)).setUniform("sampleCount", unsigned(n)).setUniform("seed", unsigned(seed));
    sampleCount_ = n;
}

// One pass: every pixel's tree (maxBounces >= 0; the AOVs' pixel-centre pass of a render with
// several samples, maxBounces -1, is the wavefront chain's).
void WhittedMegakernelGl::sample(const std::vector<PointLight>& lights, int maxBounces, RenderOutput* aovs,
                                 RenderStats& stats) {
    const std::vector<GPUKernel*> passes = {&samples_, &centres_, &centresAovs_};
    inputs_.setLights(lights, passes);
    if (aovs && !aovs_) throw UsageError("WhittedMegakernelGl: AOVs asked of a pipeline made without them");
    GPUKernel& k = aovs ? centresAovs_ : sampleCount_ == 1 ? centres_ : samples_;
    k.setUniform("maxBounces", std::max(0, maxBounces));
    inputs_.run(k, 0, false, stats);
    if (aovs) {
        p_.readHitAovs(*aovs, &aovs_->steps(), false);
        p_.readNormalAov(*aovs, &aovs_->normals());
    }
}

}  // namespace gpurt
