#include "raytrace/integrators/GpuPipeline.h"

#include "raytrace/integrators/SharedPasses.h"

#include <limits>
#include <span>

namespace gpurt {

GpuPipeline::GpuPipeline(int w, int h, const SceneTextures& textures, GlAccelerator& accelerator, MaskMode mask,
                         bool paths, bool progressiveAovs, Needs needed)
    : width(w),
      height(h),
      needs(needed),
      // Without the stages: the path megakernel's live paths, and the AOVs' hits.
      rayOrigin(needed.stages || paths ? w : 1, needed.stages || paths ? h : 1, 4, "rayOrigin"),
      rayDir(needed.stages || paths ? w : 1, needed.stages || paths ? h : 1, 4, "rayDir"),
      hit(needed.stages || needed.aovs ? w : 1, needed.stages || needed.aovs ? h : 1, 4, "hit"),
      accel(accelerator),
      surfacePoint(needs.stages ? w : 1, needs.stages ? h : 1, 4, "surfacePoint"),
      surfaceNormal(needs.stages ? w : 1, needs.stages ? h : 1, 4, "surfaceNormal"),
      surfaceView(needs.stages ? w : 1, needs.stages ? h : 1, 4, "surfaceView"),
      surfaceShading(needs.stages ? w : 1, needs.stages ? h : 1, 4, "surfaceShading"),
      localColor(needs.stages ? w : 1, needs.stages ? h : 1, 4, "localColor"),
      color(needs.stages || paths ? w : 1, needs.stages || paths ? h : 1, 4, "color"),
      weight(needs.stages || paths ? w : 1, needs.stages || paths ? h : 1, 4, "weight"),
      sampleSum(needs.sums ? w : 1, needs.sums ? h : 1, 4, "sampleSum"),
      lightSample(needs.stages && (needs.emitters || needs.environment) ? w : 1,
                  needs.stages && (needs.emitters || needs.environment) ? h : 1, 4, "lightSample"),
      pathState(needs.pathState || paths ? w : 1, needs.pathState || paths ? h : 1, 4, "pathState"),
      progressive(progressiveAovs),
      aovHit(progressive ? w : 1, progressive ? h : 1, 4, "aovHit"),
      aovCells(progressive ? w : 1, progressive ? h : 1, GPUFormat::RGBA32I, "aovCells"),
      aovNormal(progressive ? w : 1, progressive ? h : 1, 4, "aovNormal"),
      raygen("raygen", "integrators/raygen.frag"),
      raygenCentre("raygen", "integrators/raygen.frag", passDefines(kPixelCentre)),  // a variant: the same pass in --stats
      oddSum(needs.adaptive ? w : 1, needs.adaptive ? h : 1, 4, "oddSum"),
      squareSum(needs.variance ? w : 1, needs.variance ? h : 1, 4, "squareSum"),
      pixelAlbedo(needs.features ? w : 1, needs.features ? h : 1, 4, "pixelAlbedo"),
      pixelNormal(needs.features ? w : 1, needs.features ? h : 1, 4, "pixelNormal"),
      albedoSum(needs.features ? w : 1, needs.features ? h : 1, 4, "albedoSum"),
      normalSum(needs.features ? w : 1, needs.features ? h : 1, 4, "normalSum"),
      activity(needs.adaptive ? w : 1, needs.adaptive ? h : 1, 4, "activity"),
      activePixels(needs.adaptive ? w : 1, needs.adaptive ? h : 1, 4, "activePixels"),
      activeCount(1, 1, GPUFormat::R32UI, "activeCount"),
      converge("converge", "integrators/converge.frag") {
    if (needs.stages) accel.attach(GlRayStreams{&rayOrigin, &rayDir, &hit}, mask);
    for (GPUKernel* k : kernels()) {
        textures.bind(*k);
        k->addOutput(rayOrigin).addOutput(rayDir);
    }
    if (needs.adaptive) {
        activeMask = std::make_unique<GPUMask>("active", mask, activity, 0, 0.5f, 1.5f);
        for (GPUKernel* k : kernels()) k->setMask(activeMask.get(), false);
        // Stopped pixels are masked out and keep the 0 the stream is cleared to.
        converge.addInput(sampleSum, "sampleSum").addInput(oddSum, "oddSum").addOutput(activity);
        converge.addImage(activePixels, "activePixels").addImage(activeCount, "activeCount").setUniform("packWidth", w);
        converge.setPreserveUnwritten(false).setMask(activeMask.get(), false);
    }
}

void GpuPipeline::beginAdaptive() {
    oddSum.fill(0.0f);
    activity.front().fill(1.0f);
    activeMask->update();
    packedActive.reset();
}

uint64_t GpuPipeline::convergeRound(float threshold) {
    activity.back().fill(0.0f);
    const uint32_t zero = 0;
    activeCount.upload(std::span<const uint32_t>(&zero, 1));
    converge.setUniform("threshold", threshold);
    const uint64_t active = converge.execute();  // the pass swaps activity: its front is the new one
    activeMask->update();
    packedActive = active;
    return active;
}

void GpuPipeline::setCamera(const CameraBasis& c, const std::vector<GPUKernel*>& others) {
    setSample(0, 1, 0);
    // The kernels that generate camera rays: raygen, the accelerator's camera trace, and the
    // integrators' megakernels among `others` (the others ignore the uniforms).
    std::vector<GPUKernel*> all = accel.kernels();
    all.insert(all.end(), {&raygen, &raygenCentre});
    all.insert(all.end(), others.begin(), others.end());
    for (GPUKernel* k : all)
        k->setUniform("eye", c.eye)
            .setUniform("forward", c.forward)
            .setUniform("right", c.right)
            .setUniform("upOrtho", c.upOrtho)
            .setUniform("tanHalf", c.tanHalf)
            .setUniform("aspect", c.aspect)
            .setUniform("imageSize", glm::vec2(float(c.width), float(c.height)))
            .setUniform("tileRow", c.rowBegin)
            .setUniform("lensRadius", c.lensRadius)
            .setUniform("focusDistance", c.focusDistance)
            .setUniform("blades", c.blades)
            .setUniform("bladeRotation", c.bladeRotation);
}

void GpuPipeline::setSample(uint32_t s, uint32_t n, uint32_t seed) {
    sampleCount_ = n;
    raygen.setUniform("sampleIndex", unsigned(s)).setUniform("sampleCount", unsigned(n)).setUniform("seed", unsigned(seed));
}

void GpuPipeline::readHitAovs(RenderOutput& out, const GPUFloatArray* stepStream, bool countOverflow) {
    const size_t pixels = size_t(width) * size_t(height);
    const auto hits = hit.download();
    const auto steps = (stepStream ? *stepStream : accel.steps()).downloadInt();
    out.depth.resize(pixels);
    out.prim.resize(pixels);
    out.steps.resize(pixels);
    for (size_t i = 0; i < pixels; ++i) {
        const bool isHit = hits[i * 4 + 3] >= 0.0f;
        out.depth[i] = isHit ? hits[i * 4] : std::numeric_limits<float>::infinity();
        out.prim[i] = isHit ? hits[i * 4 + 3] : -1.0f;
        out.steps[i] = float(steps[i * 4 + 3]);
        // Overflow, counted for primary rays (their step counts are read back anyway): with the
        // accelerator's limit, reaching it is the only way to visit that many cells.
        if (countOverflow && steps[i * 4 + 3] >= accel.stepLimit()) ++out.stats.overflowRays;
    }
}

void GpuPipeline::readNormalAov(RenderOutput& out, const GPUFloatArray* normals) {
    out.normal = downloadVectors<glm::vec3>(normals ? *normals : surfaceNormal);
    for (size_t i = 0; i < out.normal.size(); ++i)
        if (out.prim[i] < 0.0f) out.normal[i] = glm::vec3(0.0f);
}

}  // namespace gpurt
