#include "raytrace/GpuTracer.h"

#include "raytrace/GpuPipeline.h"
#include "raytrace/RayMath.h"
#include "raytrace/accel/grid/GridGl.h"

#include "../../glsl/common/scene_layout.h"


#include "stream/GPUKernel.h"
#include "stream/KernelChain.h"
#include "stream/StreamErrors.h"

#include <chrono>

namespace gpurt {

GpuTracer::GpuTracer(const Scene& scene, const UniformGrid& grid, GpuTracerOptions options)
    : scene_(scene),
      options_(options),
      textures_(scene, grid.rayOffset()),
      accel_(std::make_unique<GridGl>(scene, grid, options)) {
    for (uint32_t m : scene.materialIds) {
        hasDielectric_ = hasDielectric_ || scene.materials[m].ior > 0.0f;
        hasSecondary_ = hasSecondary_ || scene.materials[m].ior > 0.0f || scene.materials[m].reflectivity != glm::vec3(0.0f);
    }
}

GpuTracer::~GpuTracer() = default;

const char* traceKernelName(TraceKernel kernel) { return kernel == TraceKernel::Split ? "split" : "fused"; }

bool parseTraceKernel(const std::string& text, TraceKernel& kernel) {
    if (text == "fused") kernel = TraceKernel::Fused;
    else if (text == "split") kernel = TraceKernel::Split;
    else return false;
    return true;
}

int GpuTracer::stackSlots(const RenderSettings& settings) const {
    if (!hasDielectric_ || settings.integrator == Integrator::Path) return 0;
    return std::min(std::max(0, settings.maxBounces), GPURT_STACK_SLOTS);
}

GpuPipeline& GpuTracer::pipeline(int width, int height, int stackSlots, bool paths, bool progressive, bool sums) {
    GpuPipeline::Needs needs;
    needs.emitters = !textures_.emitterTable().empty();
    needs.pathState = paths || hasSecondary_;
    needs.sums = sums || progressive;
    if (!pipeline_ || pipeline_->width != width || pipeline_->height != height ||
        pipeline_->stackSlots != stackSlots || pipeline_->paths != paths || pipeline_->progressive != progressive ||
        !(pipeline_->needs == needs)) {
        pipeline_.reset();
        const MaskMode mask = options_.mask == MaskMode::None ? defaultMaskMode() : options_.mask;
        pipeline_ = std::make_unique<GpuPipeline>(width, height, textures_, *accel_, mask, stackSlots, paths, progressive,
                                                  needs);
    }
    return *pipeline_;
}

namespace {
template <typename T>
std::vector<T> toVectors(const std::vector<float>& flat, int stride) {
    std::vector<T> out(flat.size() / size_t(stride));
    for (size_t i = 0; i < out.size(); ++i)
        for (int c = 0; c < T::length(); ++c) out[i][c] = flat[i * size_t(stride) + size_t(c)];
    return out;
}
}  // namespace

// The sample loop (--spp), each sample a run of the Whitted chain: raygen through the sample's
// point of each pixel, then per bounce the trace loop, the surface pass, a shadow trace and light
// pass per light, and the bounce pass that spawns the mirror rays; the accumulate pass adds the
// sample's colour to the pixels' sums. The AOVs come from the pixel-centre rays: the first and only
// sample's when spp = 1, else a primary trace and surface pass of their own before the samples.
RenderOutput GpuTracer::render(const CameraBasis& camera, const RenderSettings& settings) {
    const auto start = std::chrono::steady_clock::now();
    const bool paths = settings.integrator == Integrator::Path;
    const uint32_t samples = std::max(1u, settings.samples);
    GpuPipeline& p = pipeline(camera.width, camera.rows(), stackSlots(settings), paths, false, samples > 1);
    RenderOutput out;
    out.width = camera.width;
    out.height = camera.rows();

    const std::vector<PointLight> lights = lightsOrHeadlight(scene_, camera.eye, paths);
    p.surface.setUniform("background", scene_.background);
    p.pathSurface.setUniform("background", scene_.background);
    p.setCamera(camera);
    if (samples > 1) traceSample(p, lights, -1, true, out);  // pixel centres: the AOVs only
    if (samples == 1) {  // the sample is the image: no sum to accumulate into
        p.setSample(0, 1, settings.seed);
        traceIntegrator(p, lights, settings, true, out);
        out.color = toVectors<glm::vec3>((paths ? p.pixelColor : p.color).download(), 4);
    } else {
        p.sampleSum.fill(0.0f);
        for (uint32_t s = 0; s < samples; ++s) {
            p.setSample(s, samples, settings.seed);
            traceIntegrator(p, lights, settings, false, out);
            (paths ? p.pathAccumulate : p.accumulate).dispatch();
        }
        out.color = toVectors<glm::vec3>(p.sampleSum.download(), 4);
        for (glm::vec3& c : out.color) c /= float(samples);  // CpuTracer::render divides alike
    }
    out.stats.samples = uint64_t(camera.width) * uint64_t(camera.rows()) * samples;
    flushStats();
    out.stats.totalMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
}

void GpuTracer::readHitAovs(GpuPipeline& p, RenderOutput& out) {
    const size_t pixels = size_t(p.width) * size_t(p.height);
    const auto hits = p.hit.download();
    const auto cells = accel_->steps().downloadInt();
    out.depth.resize(pixels);
    out.prim.resize(pixels);
    out.steps.resize(pixels);
    for (size_t i = 0; i < pixels; ++i) {
        const bool isHit = hits[i * 4 + 3] >= 0.0f;
        out.depth[i] = isHit ? hits[i * 4] : std::numeric_limits<float>::infinity();
        out.prim[i] = isHit ? hits[i * 4 + 3] : -1.0f;
        out.steps[i] = float(cells[i * 4 + 3]);
        // Overflow, counted for primary rays (their cell counts are read back anyway): with the
        // accelerator's limit, reaching it is the only way to visit that many cells.
        if (cells[i * 4 + 3] >= accel_->stepLimit()) ++out.stats.overflowRays;
    }
}

void GpuTracer::readNormalAov(GpuPipeline& p, RenderOutput& out) {
    out.normal = toVectors<glm::vec3>(p.surfaceNormal.download(), 4);
    for (size_t i = 0; i < out.normal.size(); ++i)
        if (out.prim[i] < 0.0f) out.normal[i] = glm::vec3(0.0f);
}

void GpuTracer::traceIntegrator(GpuPipeline& p, const std::vector<PointLight>& lights,
                                const RenderSettings& settings, bool readAovs, RenderOutput& out) {
    const int bounces = std::max(0, settings.maxBounces);
    if (settings.integrator == Integrator::Path) tracePath(p, lights, bounces, readAovs, out);
    else traceSample(p, lights, bounces, readAovs, out);
}

// Round b traces the rays of the paths alive at depth b (round 0: the camera rays, one an element
// in image order), and its count ends the loop when no path is left; then, as
// CpuTracer::pathSample: the surface pass (emission weighed against next-event estimation, the
// background on a miss), below the last depth a shadow trace and light pass per point light and
// one for an emitter point, and the bounce pass, which samples each path's next direction and
// packs the paths that go on to the front of the streams (stream compaction, Purcell et al.
// 2002): the next round's passes cover only the rows they fill, so ended paths cost nothing. A
// path leaves its colour in its pixel's element of pixelColor when it ends (the deposit pass for
// those alive after the last round).
void GpuTracer::tracePath(GpuPipeline& p, const std::vector<PointLight>& lights, int maxDepth, bool readAovs,
                          RenderOutput& out) {
    RenderStats& stats = out.stats;
    // Masks need a mask pass (early-Z or stencil); the early-exit mode is what the kernels do anyway.
    const MaskMode mode = p.aliveMask.mode();
    const bool masked = options_.maskPaths && (mode == MaskMode::EarlyZ || mode == MaskMode::Stencil);
    // The rays of the round; masked: the one-pass trace under the mask of the live paths (their
    // rays), or of those with a hit (their shadow rays).
    auto traceRound = [&](bool anyHit) -> uint64_t {
        return accel_->trace(anyHit, masked ? (anyHit ? &p.surfaceMask : &p.aliveMask) : nullptr);
    };
    p.maskPaths(masked);
    p.color.fill(0.0f);
    p.weight.fill(1.0f);
    p.pathState.fill(0.0f);  // the camera rays: their emission counts in full
    p.pixelColor.fill(0.0f);
    p.primaryRays().dispatch();
    int rows = p.height;  // the rows that hold the live paths
    p.setPathRows(rows);
    for (int b = 0; b <= maxDepth; ++b) {
        if (masked) p.aliveMask.update();
        const uint64_t rays = traceRound(false);
        if (b > 0 && rays == 0) break;  // every path has ended
        stats.addLivePaths(size_t(b), rays);
        (b == 0 ? stats.primaryRays : stats.secondaryRays) += rays;
        if (b == 0 && readAovs) readHitAovs(p, out);
        if (masked) p.surfacePoint.fill(-1.0f);  // no surface for the paths the mask leaves out
        p.pathSurface.dispatch();
        if (b == 0 && readAovs) readNormalAov(p, out);
        if (b == maxDepth) {  // the last depth: its emission only
            p.pathDeposit.setUniform("depth", b).dispatch();
            break;
        }
        if (masked) p.surfaceMask.update();
        for (const PointLight& l : lights) {
            p.pathShadowgen.setUniform("lightPosition", l.position).dispatch();
            stats.shadowRays += traceRound(true);
            p.pathLight.setUniform("lightPosition", l.position)
                .setUniform("lightColor", l.color)
                .setUniform("lightIntensity", l.intensity)
                .dispatch();
        }
        if (!textures_.emitterTable().empty()) {
            p.pathEmitterShadowgen.setUniform("bounce", unsigned(b)).dispatch();
            stats.shadowRays += traceRound(true);  // lit in the bounce pass
        }
        // Packing costs (an atomic counter and five stores a path): only from the depth on which
        // Russian roulette ends many paths, or once the rows in use are half empty.
        if (b < GPURT_RR_DEPTH && 2 * rays > uint64_t(rows) * uint64_t(p.width)) {
            p.pathBounce.setUniform("depth", b).dispatch();
            continue;
        }
        // The packed streams start empty: no ray, no throughput beyond the paths written.
        p.nextWeight.fill(0.0f);
        p.nextDir.fill(GPURT_NO_RAY);
        p.pathCount.fill(0.0f);
        p.pathPack.setUniform("depth", b).dispatch();
        const uint64_t live = p.pathCount.downloadUint()[0];
        p.rayOrigin.copyFrom(p.nextOrigin);
        p.rayDir.copyFrom(p.nextDir);
        p.weight.copyFrom(p.nextWeight);
        p.pathState.copyFrom(p.nextState);
        p.color.copyFrom(p.nextColor);
        if (live == 0) break;
        rows = int((live + uint64_t(p.width) - 1) / uint64_t(p.width));
        p.setPathRows(rows);
    }
    p.setPathRows(std::nullopt);
}

// One sample of every pixel through the chain into p.color, from the rays of raygen's current
// sample, with up to maxBounces mirror bounces (< 0: only the primary trace and surface pass, for
// the AOVs). With readAovs, reads the primary AOVs into `out`; the rays traced count in out.stats.
void GpuTracer::traceSample(GpuPipeline& p, const std::vector<PointLight>& lights, int maxBounces,
                            bool readAovs, RenderOutput& out) {
    RenderStats& stats = out.stats;
    RenderOutput* aovs = readAovs ? &out : nullptr;
    p.color.fill(0.0f);
    p.weight.fill(1.0f);  // every pixel starts a tree with one ray of weight 1
    p.pathState.fill(0.0f);
    p.primaryRays().dispatch();
    p.bounce.setUniform("maxBounces", std::max(0, maxBounces));
    p.setRoundRect(std::nullopt);
    // The rounds after the first cover the box of the elements with rays (bounce.frag); only for
    // a one-pass trace, whose passes need no mask over the whole image.
    const bool boxed = !accel_->needsRayStates();
    const uint32_t emptyBox[4] = {UINT32_MAX, UINT32_MAX, 0, 0};
    // Each round traces one ray of each pixel's tree; a tree has at most GPURT_TREE_RAYS rays.
    for (int b = 0; b < GPURT_TREE_RAYS; ++b) {
        const uint64_t rays = accel_->trace(false);
        (b == 0 ? stats.primaryRays : stats.secondaryRays) += rays;
        if (b > 0 && rays == 0) break;  // every tree is done (the count ends the loop)
        if (b == 0 && aovs) readHitAovs(p, *aovs);  // before shadow rays reuse the ray streams
        p.surface.dispatch();
        if (b == 0 && aovs) readNormalAov(p, *aovs);
        if (maxBounces < 0) return;
        for (const PointLight& l : lights) {
            p.shadowgen.setUniform("lightPosition", l.position).dispatch();
            stats.shadowRays += accel_->trace(true);
            p.light.setUniform("lightPosition", l.position)
                .setUniform("lightColor", l.color)
                .setUniform("lightIntensity", l.intensity)
                .dispatch();
        }
        if (!textures_.emitterTable().empty()) {
            p.emitterShadowgen.setUniform("bounce", unsigned(b)).dispatch();  // the round's dimension
            stats.shadowRays += accel_->trace(true);
            p.emitterLight.dispatch();
        }
        if (maxBounces == 0 || !hasSecondary_) {  // no ray spawns: the next round would trace none
            p.lastBounce.dispatch();
            break;
        }
        if (boxed) p.rayBounds.upload(std::span<const uint32_t>(emptyBox));
        p.bounce.dispatch();
        if (boxed) {
            const std::vector<uint32_t> box = p.rayBounds.downloadUint();
            if (box[2] < box[0]) break;  // no ray left: every tree is done
            p.setRoundRect(StreamRect{int(box[0]), int(box[1]), int(box[2] - box[0] + 1), int(box[3] - box[1] + 1)});
        }
    }
    p.setRoundRect(std::nullopt);
}

void GpuTracer::beginProgressive(const CameraBasis& camera, const RenderSettings& settings) {
    const bool paths = settings.integrator == Integrator::Path;
    GpuPipeline& p = pipeline(camera.width, camera.rows(), stackSlots(settings), paths, true);
    progressive_.settings = settings;
    progressive_.lights = lightsOrHeadlight(scene_, camera.eye, paths);
    p.surface.setUniform("background", scene_.background);
    p.pathSurface.setUniform("background", scene_.background);
    p.setCamera(camera);
    traceSample(p, progressive_.lights, -1, false, progressive_.output);  // pixel centres
    p.aovHit.copyFrom(p.hit);
    p.aovCells.copyFrom(accel_->steps());
    p.aovNormal.copyFrom(p.surfaceNormal);
    p.sampleSum.fill(0.0f);
}

void GpuTracer::bindDisplay(GPUKernel& display) {
    if (!pipeline_) throw UsageError("GpuTracer::bindDisplay before beginProgressive");
    display.addInput(pipeline_->sampleSum, "sampleSum").addInput(pipeline_->aovHit, "aovHit");
    display.addInput(pipeline_->aovCells, "aovCells").addInput(pipeline_->aovNormal, "aovNormal");
}

std::set<std::string> GpuTracer::accelerationPasses() {
    std::set<std::string> names;
    for (GPUKernel* k : accel_->kernels()) names.insert(k->name());
    return names;
}

void GpuTracer::addSample(uint32_t s, uint32_t n) {
    GpuPipeline& p = *pipeline_;
    p.setSample(s, n, progressive_.settings.seed);
    traceIntegrator(p, progressive_.lights, progressive_.settings, false, progressive_.output);
    (p.paths ? p.pathAccumulate : p.accumulate).dispatch();
    progressive_.output.stats.samples += uint64_t(p.width) * uint64_t(p.height);
}

uint64_t GpuTracer::tracePrimary(const CameraBasis& camera) {
    GpuPipeline& p = pipeline(camera.width, camera.rows());
    p.setCamera(camera);
    std::optional<uint64_t> rays = accel_->traceCamera();
    if (!rays) {
        p.primaryRays().dispatch();
        rays = accel_->trace(false);
    }
    glFinish();
    return *rays;
}

void GpuTracer::setRays(const RayStream& rays) {
    GpuPipeline& p = pipeline(rays.width, rays.height);
    const size_t n = size_t(rays.width) * size_t(rays.height);
    std::vector<float> origin(4 * n), direction(4 * n);
    for (size_t i = 0; i < n; ++i) {
        const glm::vec3 o = rays.origin[i], d = rays.direction[i];
        const float tLimit = rays.tLimit[i];
        const float ray[8] = {o.x, o.y, o.z, tLimit, d.x, d.y, d.z, tLimit >= 0.0f ? GPURT_A_RAY : GPURT_NO_RAY};
        std::copy(ray, ray + 4, origin.begin() + std::ptrdiff_t(4 * i));
        std::copy(ray + 4, ray + 8, direction.begin() + std::ptrdiff_t(4 * i));
    }
    p.rayOrigin.upload(origin);
    p.rayDir.upload(direction);
}

uint64_t GpuTracer::traceRays(bool anyHit) {
    if (!pipeline_) throw UsageError("GpuTracer::traceRays before setRays");
    const uint64_t rays = accel_->trace(anyHit);
    glFinish();
    return rays;
}

void GpuTracer::flushStats() {
    if (pipeline_)
        for (GPUKernel* k : pipeline_->allKernels()) k->flushStats();
}

std::vector<glm::vec4> GpuTracer::hits() {
    if (!pipeline_) throw UsageError("GpuTracer::hits before a trace");
    return toVectors<glm::vec4>(pipeline_->hit.download(), 4);
}

}  // namespace gpurt
