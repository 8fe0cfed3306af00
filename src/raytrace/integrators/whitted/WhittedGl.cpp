#include "raytrace/integrators/whitted/WhittedGl.h"

#include "raytrace/common/RayMath.h"
#include "raytrace/integrators/GlRegistry.h"
#include "raytrace/integrators/Megakernel.h"
#include "raytrace/integrators/SharedPasses.h"

#include <algorithm>
#include <cstdint>
#include <span>

namespace gpurt {

namespace {

// The ray tree's last pass of a sample (whitted/bounce.frag LAST_ROUND), where no ray can follow:
// colour += weight * local colour.
//   reads surfacePoint, weight, localColor (and the hit's record for a volume's absorption,
//   surface_streams.glsl crossedWeight: surfaceNormal, surfaceView, surfaceShading); in place color.
void declareLastBouncePass(GPUKernel& k, GpuPipeline& p) {
    k.addInput(p.surfacePoint, "surfacePoint").addInput(p.weight, "weightState");
    k.addInput(p.localColor, "localColor").addInOut(p.color, "colorState");
    k.addInput(p.surfaceNormal, "surfaceNormal").addInput(p.surfaceView, "surfaceView");
    k.addInput(p.surfaceShading, "surfaceShading");
}

// The bounce pass (whitted/bounce.frag): colour += weight * local colour, then the pixel's next
// ray: the hit's first child, or the top of its stack (common/raytree.h).
//   reads surfacePoint, surfaceNormal, surfaceView, surfaceShading, localColor; in place color,
//   weight, pathState (the tree's depth, stack height and rays); writes rayOrigin, rayDir; its
//   stack images, and the box of the elements with a ray next round (rayBounds).
void declareBouncePass(GPUKernel& k, GpuPipeline& p, GPUFloatArray& stackOrigin, GPUFloatArray& stackDir,
                       GPUFloatArray& stackWeight, GPUFloatArray& rayBounds, int slots) {
    k.addInput(p.surfacePoint, "surfacePoint").addInput(p.surfaceNormal, "surfaceNormal");
    k.addInput(p.surfaceView, "surfaceView").addInput(p.localColor, "localColor");
    k.addInput(p.surfaceShading, "surfaceShading");
    k.addInOut(p.color, "colorState").addInOut(p.weight, "weightState");
    k.addOutput(p.rayOrigin).addOutput(p.rayDir);
    if (p.needs.pathState) k.addInOut(p.pathState, "pathStateIn");
    k.addImage(stackOrigin, "stackOrigin").addImage(stackDir, "stackDir").addImage(stackWeight, "stackWeight");
    k.setUniform("stackSlots", slots);
    k.addImage(rayBounds, "rayBounds");
}
}  // namespace

WhittedGl::WhittedGl(GpuPipeline& pipeline, const SceneTextures& textures, int stackSlots, bool spawns)
    : p_(pipeline),
      emitters_(pipeline.needs.emitters),
      spawns_(spawns),
      stackOrigin_(stackSlots > 0 ? p_.width : 1, stackSlots > 0 ? p_.height * stackSlots : 1, 4, "stackOrigin"),
      stackDir_(stackSlots > 0 ? p_.width : 1, stackSlots > 0 ? p_.height * stackSlots : 1, 4, "stackDir"),
      stackWeight_(stackSlots > 0 ? p_.width : 1, stackSlots > 0 ? p_.height * stackSlots : 1, 4, "stackWeight"),
      rayBounds_(4, 1, GPUFormat::R32UI, "rayBounds"),
      surface_("surface", "integrators/surface.frag"),
      shadowgen_("shadowgen", "integrators/shadowgen.frag"),
      light_("light", "integrators/light.frag"),
      emitterShadowgen_("emitterShadowgen", "integrators/shadowgen.frag", passDefines(kEmitterPass)),
      emitterLight_("emitterLight", "integrators/light.frag", passDefines(kEmitterPass)),
      bounce_("bounce", "integrators/whitted/bounce.frag"),
      lastBounce_("lastBounce", "integrators/whitted/bounce.frag", passDefines(kLastRound)),
      accumulate_("accumulate", "integrators/accumulate.frag") {
    for (GPUKernel* k : kernels()) textures.bind(*k);
    declareSurfacePass(surface_, p_, false);
    declareShadowgenPass(shadowgen_, p_, false, false);
    declareLightPass(light_, p_, false);
    declareShadowgenPass(emitterShadowgen_, p_, false, true);
    declareLightPass(emitterLight_, p_, true);
    declareBouncePass(bounce_, p_, stackOrigin_, stackDir_, stackWeight_, rayBounds_, stackSlots);
    declareLastBouncePass(lastBounce_, p_);
    declareAccumulatePass(accumulate_, p_, p_.color);
}

std::vector<GPUKernel*> WhittedGl::kernels() {
    return {&surface_, &shadowgen_, &light_, &emitterShadowgen_, &emitterLight_, &bounce_, &lastBounce_, &accumulate_};
}

void WhittedGl::setSample(uint32_t s, uint32_t n, uint32_t seed) {
    emitterShadowgen_.setUniform("sampleIndex", unsigned(s)).setUniform("sampleCount", unsigned(n)).setUniform("seed", unsigned(seed));
}

// One sample of every pixel into p.color, from the rays of the pipeline's current sample, with up
// to maxBounces mirror and glass levels. Each round traces one ray of each pixel's tree (a tree
// has at most GPURT_TREE_RAYS rays); the trace's count ends the loop when every tree is done.
void WhittedGl::sample(const std::vector<Light>& lights, int maxBounces, RenderOutput* aovs, RenderStats& stats) {
    startTrees(maxBounces);
    // The rounds after the first cover the box of the elements with rays (bounce.frag); only for
    // a one-pass trace, whose passes need no mask over the whole image.
    const bool boxed = !p_.accel.needsRayStates();
    for (int round = 0; round < GPURT_TREE_RAYS; ++round) {
        const uint64_t rays = traceRays();
        (round == 0 ? stats.primaryRays : stats.secondaryRays) += rays;
        if (round > 0 && rays == 0) break;  // every tree is done (the count ends the loop)
        if (round == 0 && aovs) p_.readHitAovs(*aovs);  // before shadow rays reuse the ray streams
        shadeSurfaces();
        if (round == 0 && aovs) p_.readNormalAov(*aovs);
        if (maxBounces < 0) return;
        lightPointLights(lights, stats);
        lightEmitters(round, stats);
        if (maxBounces == 0 || !spawns_) {  // no ray spawns: the next round would trace none
            finishTrees();
            break;
        }
        if (!spawnRays(boxed)) break;  // no ray left: every tree is done
    }
    setRoundRect(std::nullopt);
}

// Every pixel starts a tree with one ray of weight 1: the camera ray of its sample.
//   writes color, weight, pathState; raygen writes rayOrigin, rayDir.
void WhittedGl::startTrees(int maxBounces) {
    p_.color.fill(0.0f);
    p_.weight.fill(1.0f);
    p_.pathState.fill(0.0f);
    p_.primaryRays().dispatch();
    bounce_.setUniform("maxBounces", std::max(0, maxBounces));
    setRoundRect(std::nullopt);
}

// The round's rays into hits (the accelerator); returns the rays traced.
uint64_t WhittedGl::traceRays() { return p_.accel.trace(false); }

// The hits into surface records, emission into the colour, the ambient term into localColor.
void WhittedGl::shadeSurfaces() { surface_.dispatch(); }

// Per point light: a shadow ray from each surface point it is in front of, traced for any hit,
// then its term where unblocked.
void WhittedGl::lightPointLights(const std::vector<Light>& lights, RenderStats& stats) {
    for (const Light& l : lights) {
        setLightUniforms(shadowgen_, l);
        shadowgen_.dispatch();
        stats.shadowRays += p_.accel.trace(true);
        setLightUniforms(light_, l);
        light_.dispatch();
    }
}

// The emitters (area lights): one point of them per surface point and sample, in the round's
// sample dimension, its shadow ray, its term.
void WhittedGl::lightEmitters(int round, RenderStats& stats) {
    if (!emitters_) return;
    emitterShadowgen_.setUniform("bounce", unsigned(round)).dispatch();
    stats.shadowRays += p_.accel.trace(true);
    emitterLight_.dispatch();
}

// The round after which no ray can follow: the local colours into the colour, one output.
void WhittedGl::finishTrees() { lastBounce_.dispatch(); }

// The local colours into the colour and each pixel's next ray; with `boxed`, the next round runs
// over the box of the elements that have one. False when no element has a ray.
bool WhittedGl::spawnRays(bool boxed) {
    const uint32_t emptyBox[4] = {UINT32_MAX, UINT32_MAX, 0, 0};
    if (boxed) rayBounds_.upload(std::span<const uint32_t>(emptyBox));
    bounce_.dispatch();
    if (!boxed) return true;
    const std::vector<uint32_t> box = rayBounds_.downloadUint();
    if (box[2] < box[0]) return false;
    setRoundRect(StreamRect{int(box[0]), int(box[1]), int(box[2] - box[0] + 1), int(box[3] - box[1] + 1)});
    return true;
}

// The round's passes over `rect` only (the box of the elements with rays), or all.
void WhittedGl::setRoundRect(std::optional<StreamRect> rect) {
    for (GPUKernel* k : {&surface_, &shadowgen_, &light_, &emitterShadowgen_, &emitterLight_, &bounce_, &lastBounce_})
        k->setRect(rect);
    p_.accel.setRect(rect);
}

// Whitted's gl form (integrators/GlRegistry.h).
std::unique_ptr<GlIntegrator> makeWhittedGl(const GlIntegratorSetup& s) {
    if (s.megakernel) {  // glsl/integrators/whitted/megakernel.frag: each pixel's tree in one pass
        auto k = std::make_unique<OnePassMegakernelGl>(s.pipeline, s.textures, "whittedMegakernel",
                                                       "integrators/whitted/megakernel.frag", s.maxLights, s.aovs);
        for (GPUKernel* pass : k->kernels()) pass->setUniform("stackSlots", s.stackSlots);
        return k;
    }
    return std::make_unique<WhittedGl>(s.pipeline, s.textures, s.stackSlots, s.spawns);
}

}  // namespace gpurt
