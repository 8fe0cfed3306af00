#include "raytrace/integrators/path/PathGl.h"

#include "raytrace/common/RayMath.h"
#include "raytrace/integrators/GlRegistry.h"
#include "raytrace/integrators/path/PathMegakernelGl.h"
#include "raytrace/integrators/SharedPasses.h"

#include "../../../../glsl/common/scene_layout.h"

namespace gpurt {

namespace {

// The bounce pass (path/bounce.frag): the light next-event estimation gathered into the colour,
// then each path's next ray (a direction from the BSDF, Russian roulette); a path that ends
// leaves its colour in its pixel's element of pixelColor.
//   reads surfacePoint, surfaceNormal, surfaceView, surfaceShading, localColor, hit (the emitter
//   shadow rays'), lightSample; writes pixelColor (image).
//   In place (bounce): color, weight, pathState; writes rayOrigin, rayDir.
//   Packed (PACK): reads color, weight, pathState; writes the next* images, pathCount, pathLives.
void declareBouncePass(GPUKernel& k, GpuPipeline& p, GPUFloatArray& pixelColor) {
    k.addInput(p.surfacePoint, "surfacePoint").addInput(p.surfaceNormal, "surfaceNormal");
    k.addInput(p.surfaceView, "surfaceView").addInput(p.surfaceShading, "surfaceShading");
    k.addInput(p.localColor, "localColor").addInput(p.hit, "hitState").addInput(p.lightSample, "lightSample");
    k.addImage(pixelColor, "pixelColor");
}

// The end of the last round (path/deposit.frag): every path still alive leaves its colour.
//   reads color, weight, pathState; writes pixelColor (image), pathLives.
void declareDepositPass(GPUKernel& k, GpuPipeline& p, GPUFloatArray& pixelColor, GPUFloatArray& lives) {
    k.addInput(p.color, "colorState").addInput(p.weight, "weightState").addInput(p.pathState, "pathStateIn");
    k.addImage(pixelColor, "pixelColor").addOutput(lives);
}
}  // namespace

PathGl::PathGl(GpuPipeline& pipeline, const SceneTextures& textures, MaskMode mask, bool paths, bool maskPaths)
    : p_(pipeline),
      masked_(maskPaths && (mask == MaskMode::EarlyZ || mask == MaskMode::Stencil)),
      nextOrigin_(paths ? p_.width : 1, paths ? p_.height : 1, 4, "nextOrigin"),
      nextDir_(paths ? p_.width : 1, paths ? p_.height : 1, 4, "nextDir"),
      nextWeight_(paths ? p_.width : 1, paths ? p_.height : 1, 4, "nextWeight"),
      nextState_(paths ? p_.width : 1, paths ? p_.height : 1, 4, "nextState"),
      nextColor_(paths ? p_.width : 1, paths ? p_.height : 1, 4, "nextColor"),
      pathCount_(1, 1, GPUFormat::R32UI, "pathCount"),
      pixelColor_(paths ? p_.width : 1, paths ? p_.height : 1, 4, "pixelColor"),
      pathLives_(paths ? p_.width : 1, paths ? p_.height : 1, 1, "pathLives"),
      aliveMask_("alive", mask, p_.weight, 3, 1.0f, 1.0f),
      surfaceMask_("surface", mask, p_.surfacePoint, 3, 0.0f, 1e30f),
      surface_("pathSurface", "integrators/surface.frag", passDefines(kPathPass)),
      shadowgen_("pathShadowgen", "integrators/shadowgen.frag", passDefines(kPathPass)),
      light_("pathLight", "integrators/light.frag", passDefines(kPathPass)),
      emitterShadowgen_("pathEmitterShadowgen", "integrators/shadowgen.frag", passDefines(kEmitterPass | kPathPass)),
      bounce_("pathBounce", "integrators/path/bounce.frag"),
      pack_("pathPack", "integrators/path/bounce.frag", passDefines(kPackPass)),
      deposit_("pathDeposit", "integrators/path/deposit.frag"),
      accumulate_("pathAccumulate", "integrators/accumulate.frag"),
      emitters_(!textures.emitterTable().empty()),
      environment_(paths && textures.environmentTable().sampled),
      environmentShadowgen_("pathEnvironmentShadowgen", "integrators/shadowgen.frag",
                            passDefines(kEnvironmentPass | kPathPass)),
      environmentLight_("pathEnvironmentLight", "integrators/light.frag", passDefines(kEnvironmentPass | kPathPass)) {
    for (GPUKernel* k : kernels()) textures.bind(*k);
    if (environment_) {
        declareEnvironmentShadowgenPass(environmentShadowgen_, p_);
        declareLightPass(environmentLight_, p_, true);
    }
    declareSurfacePass(surface_, p_, true);
    if (p_.needs.features)
        surface_.addDefine("FEATURES").addImage(p_.pixelAlbedo, "pixelAlbedo").addImage(p_.pixelNormal, "pixelNormal");
    declareShadowgenPass(shadowgen_, p_, true, false);
    declareLightPass(light_, p_, false);
    declareShadowgenPass(emitterShadowgen_, p_, true, true);
    for (GPUKernel* k : {&bounce_, &pack_}) declareBouncePass(*k, p_, pixelColor_);
    bounce_.addInOut(p_.color, "colorState").addInOut(p_.weight, "weightState").addOutput(p_.rayOrigin).addOutput(p_.rayDir);
    if (paths) bounce_.addInOut(p_.pathState, "pathStateIn");
    pack_.addInput(p_.color, "colorState").addInput(p_.weight, "weightState").addInput(p_.pathState, "pathStateIn");
    pack_.addImage(nextOrigin_, "nextOrigin").addImage(nextDir_, "nextDir").addImage(nextWeight_, "nextWeight");
    pack_.addImage(nextState_, "nextState").addImage(nextColor_, "nextColor").addImage(pathCount_, "pathCount");
    pack_.addOutput(pathLives_);
    declareDepositPass(deposit_, p_, pixelColor_, pathLives_);
    declareAccumulatePass(accumulate_, p_, pixelColor_);
    maskPasses(masked_);
}

std::vector<GPUKernel*> PathGl::kernels() {
    std::vector<GPUKernel*> k = {&surface_, &shadowgen_, &light_, &emitterShadowgen_, &bounce_, &pack_, &deposit_, &accumulate_};
    if (environment_) k.insert(k.begin() + 4, {&environmentShadowgen_, &environmentLight_});
    return k;
}

void PathGl::setSample(uint32_t s, uint32_t n, uint32_t seed) {
    for (GPUKernel* k : {&emitterShadowgen_, &environmentShadowgen_, &bounce_, &pack_})
        k->setUniform("sampleIndex", unsigned(s)).setUniform("sampleCount", unsigned(n)).setUniform("seed", unsigned(seed));
}

// Round b traces the rays of the paths alive at depth b (round 0: the camera rays, one an element
// in image order), and its count ends the loop when no path is left; then, as PathCpu: the
// surface pass (emission weighed against next-event estimation, the background on a miss), below
// the last depth the point lights and an emitter point, each with shadow rays, and the bounce
// pass. The next round's passes cover only the rows the packed paths fill, so ended paths cost
// nothing. A path leaves its colour in its pixel's element of pixelColor when it ends (the deposit
// pass for those alive after the last round).
void PathGl::sample(const std::vector<Light>& lights, int maxDepth, RenderOutput* aovs, RenderStats& stats) {
    startPaths();
    for (int b = 0; b <= maxDepth; ++b) {
        if (masked_) aliveMask_.update();
        // From the second round on the paths are packed: the accelerators' alpha coverage reads
        // each ray's pixel from pathState (scene/alpha.glsl).
        for (GPUKernel* k : p_.accel.kernels()) k->setUniform("coverageFromStream", b > 0 ? 1 : 0);
        const uint64_t rays = traceRays(false);
        if (b > 0 && rays == 0) break;  // every path has ended
        stats.addLivePaths(size_t(b), rays);
        (b == 0 ? stats.primaryRays : stats.secondaryRays) += rays;
        if (b == 0 && aovs) p_.readHitAovs(*aovs);
        surface_.setUniform("depth", b);
        shadeSurfaces(masked_);
        if (b == 0 && aovs) p_.readNormalAov(*aovs);
        if (b == maxDepth) {  // the last depth: its emission only
            depositPaths(b);
            break;
        }
        if (masked_) surfaceMask_.update();
        lightPointLights(lights, stats);
        lightEnvironment(b, stats);
        sampleEmitters(b, stats);
        // Packing costs (an atomic counter and five stores a path): only from the depth on which
        // Russian roulette ends many paths, or once the rows in use are half empty.
        const int rows = rows_;
        if (b < GPURT_RR_DEPTH && 2 * rays > uint64_t(rows) * uint64_t(p_.width)) {
            continuePaths(b);
            continue;
        }
        if (packPaths(b) == 0) break;
    }
    setPathRows(std::nullopt);
}

// Every pixel starts a path of throughput 1 from its camera ray; no pixel has a colour yet.
//   writes color, weight, pathState (pdf 0: the camera ray's emission counts in full), pixelColor;
//   raygen writes rayOrigin, rayDir.
void PathGl::startPaths() {
    p_.color.fill(0.0f);
    p_.weight.fill(1.0f);
    p_.pathState.fill(0.0f);
    pixelColor_.fill(0.0f);
    // Adaptive sampling: raygen skips the stopped pixels, which then carry no ray.
    if (p_.activeMask) p_.rayDir.fill(GPURT_NO_RAY);
    p_.primaryRays().dispatch();
    setPathRows(p_.height);
}

// The rays of the round into hits (anyHit: the shadow rays); masked, only the live paths' (or
// those with a hit: their shadow rays).
uint64_t PathGl::traceRays(bool anyHit) {
    return p_.accel.trace(anyHit, masked_ ? (anyHit ? &surfaceMask_ : &aliveMask_) : nullptr);
}

void PathGl::shadeSurfaces(bool masked) {
    if (masked) p_.surfacePoint.fill(-1.0f);  // no surface for the paths the mask leaves out
    surface_.dispatch();
}

void PathGl::lightPointLights(const std::vector<Light>& lights, RenderStats& stats) {
    for (const Light& l : lights) {
        setLightUniforms(shadowgen_, l);
        shadowgen_.dispatch();
        stats.shadowRays += traceRays(true);
        setLightUniforms(light_, l);
        light_.dispatch();
    }
}

// The emitter point of each hit and its shadow ray; it is lit in the bounce pass.
void PathGl::sampleEmitters(int depth, RenderStats& stats) {
    if (!emitters_) return;
    emitterShadowgen_.setUniform("bounce", unsigned(depth)).dispatch();
    stats.shadowRays += traceRays(true);
}

// The environment direction of each hit, its shadow ray, and its light into the local colour
// (before sampleEmitters, which reuses lightSample).
void PathGl::lightEnvironment(int depth, RenderStats& stats) {
    if (!environment_) return;
    environmentShadowgen_.setUniform("bounce", unsigned(depth)).dispatch();
    stats.shadowRays += traceRays(true);
    environmentLight_.dispatch();
}

// The paths go on in their elements.
void PathGl::continuePaths(int depth) { bounce_.setUniform("depth", depth).dispatch(); }

// The paths that go on, packed to the front of the streams for the next round (Purcell's stream
// compaction: an atomic counter gives each its slot); returns how many.
uint64_t PathGl::packPaths(int depth) {
    // The packed streams start empty: no ray, no throughput beyond the paths written.
    nextWeight_.fill(0.0f);
    nextDir_.fill(GPURT_NO_RAY);
    pathCount_.fill(0.0f);
    pack_.setUniform("depth", depth).dispatch();
    const uint64_t live = pathCount_.downloadUint()[0];
    p_.rayOrigin.copyFrom(nextOrigin_);
    p_.rayDir.copyFrom(nextDir_);
    p_.weight.copyFrom(nextWeight_);
    p_.pathState.copyFrom(nextState_);
    p_.color.copyFrom(nextColor_);
    if (live > 0) setPathRows(int((live + uint64_t(p_.width) - 1) / uint64_t(p_.width)));
    return live;
}

void PathGl::depositPaths(int depth) { deposit_.setUniform("depth", depth).dispatch(); }

// The rounds' passes over the first `rows` rows only, where the live paths are packed
// (std::nullopt: all rows again).
void PathGl::setPathRows(std::optional<int> rows) {
    rows_ = rows.value_or(p_.height);
    const std::optional<StreamRect> rect = rows ? std::optional<StreamRect>(StreamRect{0, 0, p_.width, *rows}) : std::nullopt;
    for (GPUKernel* k : {&surface_, &shadowgen_, &light_, &emitterShadowgen_, &environmentShadowgen_, &environmentLight_,
                         &bounce_, &pack_, &deposit_})
        k->setRect(rect);
    p_.accel.setRect(rect);
}

// The rounds' shading passes under the masks, or not. The bounce pass ends the paths that missed:
// it runs for all paths alive in the round.
void PathGl::maskPasses(bool on) {
    surface_.setMask(on ? &aliveMask_ : nullptr, false);
    bounce_.setMask(on ? &aliveMask_ : nullptr, false);
    pack_.setMask(on ? &aliveMask_ : nullptr, false);
    for (GPUKernel* k : {&shadowgen_, &light_, &emitterShadowgen_, &environmentShadowgen_, &environmentLight_})
        k->setMask(on ? &surfaceMask_ : nullptr, false);
}

// The path integrator's gl form (integrators/GlRegistry.h).
std::unique_ptr<GlIntegrator> makePathGl(const GlIntegratorSetup& s) {
    if (s.megakernel) {
        auto k = std::make_unique<PathMegakernelGl>(s.pipeline, s.textures, s.maxLights, s.aovs);
        k->setBouncesPerPass(s.megakernelBounces);
        return k;
    }
    return std::make_unique<PathGl>(s.pipeline, s.textures, s.mask, true, s.maskPaths);
}

}  // namespace gpurt
