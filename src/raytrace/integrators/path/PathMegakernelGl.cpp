#include "raytrace/integrators/path/PathMegakernelGl.h"

#include "raytrace/integrators/SharedPasses.h"
#include "stream/StreamErrors.h"

#include "../../../../glsl/common/scene_layout.h"

#include <algorithm>

namespace gpurt {

PathMegakernelGl::PathMegakernelGl(GpuPipeline& pipeline, const SceneTextures& textures, size_t maxLights,
                                   MegakernelAovs* aovs)
    : p_(pipeline),
      inputs_(maxLights),
      origin_(p_.width, p_.height, 4, "megakernelOrigin"),
      dir_(p_.width, p_.height, 4, "megakernelDir"),
      weight_(p_.width, p_.height, 4, "megakernelWeight"),
      state_(p_.width, p_.height, 4, "megakernelState"),
      color_(p_.width, p_.height, 4, "megakernelColor"),
      pixelColor_(p_.width, p_.height, 4, "megakernelPixelColor"),
      lives_(p_.width, p_.height, 1, "megakernelLives"),
      aovs_(aovs),
      camera_("pathMegakernel", "integrators/path/megakernel.frag", passDefines(kCameraPass)),
      cameraCentre_("pathMegakernel", "integrators/path/megakernel.frag", passDefines(kCameraPass | kPixelCentre)),
      cameraAovs_("pathMegakernel", "integrators/path/megakernel.frag",
                  passDefines(kCameraPass | kPixelCentre | kAovPass)),
      fromPipeline_("pathMegakernel", "integrators/path/megakernel.frag"),
      fromOwn_("pathMegakernel", "integrators/path/megakernel.frag"),
      accumulate_("pathMegakernelAccumulate", "integrators/accumulate.frag"),
      cameraList_("pathMegakernel", "integrators/path/megakernel.frag", passDefines(kCameraPass)) {
    const PathStreams pipelineSet{&p_.rayOrigin, &p_.rayDir, &p_.weight, &p_.pathState, &p_.color};
    const PathStreams ownSet{&origin_, &dir_, &weight_, &state_, &color_};
    for (GPUKernel* k : {&camera_, &cameraCentre_, &cameraAovs_}) declarePass(*k, textures, nullptr, pipelineSet);
    declarePass(fromPipeline_, textures, &pipelineSet, ownSet);
    declarePass(fromOwn_, textures, &ownSet, pipelineSet);
    if (aovs_) cameraAovs_.addOutput(p_.hit).addOutput(aovs_->normals()).addOutput(aovs_->steps());
    declareAccumulatePass(accumulate_, p_, pixelColor_);
    // Adaptive sampling: the stopped pixels start no path: the first round's passes are masked,
    // the later ones run over the packed list of the pixels still active.
    if (p_.activeMask) {
        for (GPUKernel* k : {&camera_, &cameraCentre_}) k->setMask(p_.activeMask.get(), false);
        cameraList_.addDefine("PIXEL_LIST");
        declarePass(cameraList_, textures, nullptr, pipelineSet);
        cameraList_.addInput(p_.activePixels, "activePixels");
    }
}

// A pass's streams: the scene, its accelerator, the lights, the live paths it reads (none: the
// camera's) and those it packs, each pixel's colour and the counters.
void PathMegakernelGl::declarePass(GPUKernel& k, const SceneTextures& textures, const PathStreams* in,
                                   const PathStreams& out) {
    inputs_.declare(k, textures, p_.accel);
    if (in) {
        k.addInput(*in->origin, "rayOrigin").addInput(*in->dir, "rayDir").addInput(*in->weight, "weightState");
        k.addInput(*in->state, "pathStateIn").addInput(*in->color, "colorState");
    }
    k.addImage(*out.origin, "nextOrigin").addImage(*out.dir, "nextDir").addImage(*out.weight, "nextWeight");
    k.addImage(*out.state, "nextState").addImage(*out.color, "nextColor");
    k.addImage(pixelColor_, "pixelColor");
    if (p_.needs.features)
        k.addDefine("FEATURES").addImage(p_.pixelAlbedo, "pixelAlbedo").addImage(p_.pixelNormal, "pixelNormal");
    k.addOutput(lives_);
    k.setUniform("packWidth", p_.width);
}

std::vector<GPUKernel*> PathMegakernelGl::kernels() {
    return {&camera_, &cameraCentre_, &cameraAovs_, &fromPipeline_, &fromOwn_, &accumulate_, &cameraList_};
}

void PathMegakernelGl::setSample(uint32_t s, uint32_t n, uint32_t seed) {
    for (GPUKernel* k : {&camera_, &cameraCentre_, &cameraAovs_, &fromPipeline_, &fromOwn_, &cameraList_})
        k->setUniform("sampleIndex", unsigned(s)).setUniform("sampleCount", unsigned(n)).setUniform("seed", unsigned(seed));
    sampleCount_ = n;
}

// The first pass starts every pixel's path at its camera ray; each pass takes the live paths
// through bouncesPerPass depths (all of them when 0) and packs those still alive for the next,
// whose count ends the loop. Each path leaves its colour in its pixel's element when it ends.
void PathMegakernelGl::sample(const std::vector<Light>& lights, int maxDepth, RenderOutput* aovs,
                              RenderStats& stats) {
    const std::vector<GPUKernel*> passes = {&camera_, &cameraCentre_, &cameraAovs_, &fromPipeline_, &fromOwn_,
                                            &cameraList_};
    inputs_.setLights(lights, passes);
    const int perPass = bouncesPerPass_ > 0 ? bouncesPerPass_ : maxDepth + 1;
    for (GPUKernel* k : passes) k->setUniform("bounces", perPass).setUniform("maxDepth", maxDepth);
    if (aovs && !aovs_) throw UsageError("PathMegakernelGl: AOVs asked of a pipeline made without them");
    uint64_t live = 0;
    if (p_.packedActive && !aovs) {  // adaptive sampling, after a convergence pass
        const uint64_t pixels = *p_.packedActive;
        cameraList_.setUniform("listLength", unsigned(pixels));
        if (pixels > 0)  // (the viewer goes on sampling once every pixel has stopped)
            live = runPass(cameraList_, 0, int((pixels + uint64_t(p_.width) - 1) / uint64_t(p_.width)), stats);
    } else {
        GPUKernel& first = aovs ? cameraAovs_ : sampleCount_ == 1 ? cameraCentre_ : camera_;
        live = runPass(first, 0, p_.height, stats);
    }
    if (aovs) {
        p_.readHitAovs(*aovs, &aovs_->steps(), false);
        p_.readNormalAov(*aovs, &aovs_->normals());
    }
    bool fromPipeline = true;
    for (int depth = perPass; live > 0 && depth <= maxDepth; depth += perPass) {
        GPUKernel& k = fromPipeline ? fromPipeline_ : fromOwn_;
        k.setUniform("paths", unsigned(live));
        live = runPass(k, depth, int((live + uint64_t(p_.width) - 1) / uint64_t(p_.width)), stats);
        fromPipeline = !fromPipeline;
    }
}

uint64_t PathMegakernelGl::runPass(GPUKernel& k, int depth, int rows, RenderStats& stats) {
    k.setUniform("depth", depth).setRect(StreamRect{0, 0, p_.width, rows});
    return inputs_.run(k, depth, true, stats);
}

}  // namespace gpurt
