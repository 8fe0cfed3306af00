#include "raytrace/integrators/Megakernel.h"
#include "raytrace/lights/PunctualLights.h"

#include "raytrace/integrators/SharedPasses.h"
#include "stream/StreamErrors.h"

#include <algorithm>
#include <span>
#include <string>

namespace gpurt {

namespace {
// glsl/integrators/megakernel.glsl's counters: packed paths, shadow rays, then the paths whose last
// ray in the pass was at each depth (the last depth counted takes the deeper ones).
constexpr int kCountPacked = 0;
constexpr int kCountShadow = 1;
constexpr int kCountOverflow = 2;
constexpr int kCountDepth = 3;
constexpr int kCountedDepths = 256;
}  // namespace

MegakernelInputs::MegakernelInputs(size_t maxLights)
    : maxLights_(std::max<size_t>(1, maxLights)),
      counters_(kCountDepth + kCountedDepths, 1, GPUFormat::R32UI, "megakernelCounters"),
      punctualLights_(int(kTexelsPerLight * maxLights_), 1, 4, "punctualLights") {}

void MegakernelInputs::declare(GPUKernel& k, const SceneTextures& textures, const GlAccelerator& accel) {
    textures.bind(k);
    textures.bindCoverageDefines(k);
    if (textures.environmentTable().sampled) k.addDefine("ENVIRONMENT_LIGHT");
    accel.bindTrace(k);
    k.addInput(punctualLights_, "punctualLights").addImage(counters_, "counters");
}

void MegakernelInputs::setLights(const std::vector<Light>& lights, const std::vector<GPUKernel*>& kernels) {
    if (lights.size() > maxLights_)
        throw UsageError("megakernel: " + std::to_string(lights.size()) + " point lights, made for " +
                         std::to_string(maxLights_));
    for (GPUKernel* k : kernels) k->setUniform("punctualLightCount", int(lights.size()));
    const std::vector<float> texels = lightTexels(lights, maxLights_);
    if (texels == uploaded_) return;
    punctualLights_.upload(texels);
    uploaded_ = texels;
}

uint64_t MegakernelInputs::run(GPUKernel& k, int firstDepth, bool livePaths, RenderStats& stats) {
    const std::vector<uint32_t> zeros(size_t(counters_.width()), 0u);
    counters_.upload(std::span<const uint32_t>(zeros));
    k.dispatch();
    const std::vector<uint32_t> counts = counters_.downloadUint();
    // The paths whose last ray was at depth b or deeper traced a ray at depth b.
    uint64_t rays = 0;
    for (int b = kCountedDepths - 1; b >= firstDepth; --b) {
        rays += counts[size_t(kCountDepth + b)];
        if (rays == 0) continue;
        if (livePaths) stats.addLivePaths(size_t(b), rays);
        (b == 0 ? stats.primaryRays : stats.secondaryRays) += rays;
    }
    stats.shadowRays += counts[kCountShadow];
    stats.overflowRays += counts[kCountOverflow];
    return counts[kCountPacked];
}

MegakernelAovs::MegakernelAovs(GpuPipeline& pipeline, const SceneTextures& textures)
    : p_(pipeline),
      inputs_(0),
      steps_(p_.width, p_.height, GPUFormat::RGBA32I, "megakernelSteps"),
      normals_(p_.width, p_.height, 4, "megakernelNormals"),
      kernel_("aovs", "integrators/aovs.frag") {
    inputs_.declare(kernel_, textures, p_.accel);
    kernel_.addOutput(p_.hit).addOutput(normals_).addOutput(steps_);
}

void MegakernelAovs::trace(RenderOutput* out, RenderStats& stats) {
    inputs_.run(kernel_, 0, false, stats);
    if (!out) return;
    p_.readHitAovs(*out, &steps_, false);
    p_.readNormalAov(*out, &normals_);
}

OnePassMegakernelGl::OnePassMegakernelGl(GpuPipeline& pipeline, const SceneTextures& textures, const std::string& name,
                                         const std::string& kernel, size_t maxLights, MegakernelAovs* aovs)
    : p_(pipeline),
      inputs_(maxLights),
      colour_(p_.width, p_.height, 4, name + "Colour"),
      aovs_(aovs),
      samples_(name, kernel),
      centres_(name, kernel, passDefines(kPixelCentre)),
      centresAovs_(name, kernel, passDefines(kPixelCentre | kAovPass)),
      accumulate_(name + "Accumulate", "integrators/accumulate.frag") {
    for (GPUKernel* k : {&samples_, &centres_, &centresAovs_}) {
        inputs_.declare(*k, textures, p_.accel);
        k->addOutput(colour_);
    }
    if (aovs_) centresAovs_.addOutput(p_.hit).addOutput(aovs_->normals()).addOutput(aovs_->steps());
    declareAccumulatePass(accumulate_, p_, colour_);
}

std::vector<GPUKernel*> OnePassMegakernelGl::kernels() { return {&samples_, &centres_, &centresAovs_, &accumulate_}; }

void OnePassMegakernelGl::setSample(uint32_t s, uint32_t n, uint32_t seed) {
    for (GPUKernel* k : {&samples_, &centres_, &centresAovs_})
        k->setUniform("sampleIndex", unsigned(s)).setUniform("sampleCount", unsigned(n)).setUniform("seed", unsigned(seed));
    sampleCount_ = n;
}

// One pass: every pixel's sample (maxBounces >= 0; the AOVs' pixel-centre pass of a render with
// several samples is MegakernelAovs').
void OnePassMegakernelGl::sample(const std::vector<Light>& lights, int maxBounces, RenderOutput* aovs,
                                 RenderStats& stats) {
    const std::vector<GPUKernel*> passes = {&samples_, &centres_, &centresAovs_};
    inputs_.setLights(lights, passes);
    if (aovs && !aovs_) throw UsageError(samples_.name() + ": AOVs asked of a pipeline made without them");
    GPUKernel& k = aovs ? centresAovs_ : sampleCount_ == 1 ? centres_ : samples_;
    k.setUniform("maxBounces", std::max(0, maxBounces));
    inputs_.run(k, 0, false, stats);
    if (aovs) {
        p_.readHitAovs(*aovs, &aovs_->steps(), false);
        p_.readNormalAov(*aovs, &aovs_->normals());
    }
}

}  // namespace gpurt
