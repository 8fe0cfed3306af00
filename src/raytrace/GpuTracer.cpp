#include "raytrace/GpuTracer.h"

#include "raytrace/GpuPipeline.h"
#include "raytrace/RayMath.h"
#include "raytrace/MaterialRecord.h"
#include "raytrace/accel/grid/GridGl.h"
#include "raytrace/integrators/path/PathGl.h"
#include "raytrace/integrators/path/PathMegakernelGl.h"
#include "raytrace/integrators/whitted/WhittedGl.h"
#include "raytrace/integrators/whitted/WhittedMegakernelGl.h"

#include "../../glsl/common/scene_layout.h"


#include "stream/GPUKernel.h"
#include "stream/KernelChain.h"
#include "stream/StreamErrors.h"

#include <chrono>
#include <cstdlib>

namespace gpurt {

GpuTracer::GpuTracer(const Scene& scene, const UniformGrid& grid, GpuTracerOptions options)
    : GpuTracer(scene, std::make_unique<GridGl>(scene, grid, options), grid.rayOffset(), options) {}

GpuTracer::GpuTracer(const Scene& scene, std::unique_ptr<GlAccelerator> accel, float rayOffset, GpuTracerOptions options)
    : scene_(scene),
      options_(options),
      textures_(scene, rayOffset),
      accel_(std::move(accel)),
      kernel_(options.integratorKernel == IntegratorKernel::Auto ? defaultIntegratorKernel() : options.integratorKernel) {
    // Whether rays can spawn, and split in two: a question for each material the triangles use
    // (once each, not once a triangle: the dragon has 871k).
    std::vector<bool> used(scene.materials.size(), false);
    for (uint32_t m : scene.materialIds) used[m] = true;
    for (size_t m = 0; m < used.size(); ++m) {
        if (!used[m]) continue;
        const raymath::MaterialRecord r = materialRecord(scene.materials[m]);
        splits_ = splits_ || raymath::materialSplits(r);
        spawns_ = spawns_ || raymath::materialSpawns(r);
    }
}

GpuTracer::~GpuTracer() = default;

const char* traceKernelName(TraceKernel kernel) { return kernel == TraceKernel::Split ? "split" : "fused"; }

const char* integratorKernelName(IntegratorKernel kernel) {
    switch (kernel) {
        case IntegratorKernel::Wavefront: return "wavefront";
        case IntegratorKernel::Megakernel: return "megakernel";
        default: return "auto";
    }
}

IntegratorKernel defaultIntegratorKernel() {
    if (const char* chosen = std::getenv("GPURT_KERNEL")) {
        const std::string name = chosen;
        if (name == "wavefront") return IntegratorKernel::Wavefront;
        if (name == "megakernel") return IntegratorKernel::Megakernel;
        throw EnvironmentError("GPURT_KERNEL=" + name + ": expected wavefront or megakernel");
    }
    return IntegratorKernel::Wavefront;
}

bool parseTraceKernel(const std::string& text, TraceKernel& kernel) {
    if (text == "fused") kernel = TraceKernel::Fused;
    else if (text == "split") kernel = TraceKernel::Split;
    else return false;
    return true;
}

int GpuTracer::stackSlots(const RenderSettings& settings) const {
    if (!splits_ || settings.integrator == Integrator::Path) return 0;
    return std::min(std::max(0, settings.maxBounces), GPURT_STACK_SLOTS);
}

GpuPipeline& GpuTracer::pipeline(int width, int height, int stackSlots, bool paths, bool progressive, bool sums) {
    GpuPipeline::Needs needs;
    needs.emitters = !textures_.emitterTable().empty();
    needs.environment = paths && textures_.environmentTable().sampled;
    needs.pathState = paths || spawns_;
    needs.sums = sums || progressive;
    if (!pipeline_ || pipeline_->width != width || pipeline_->height != height || whitted_->stackSlots() != stackSlots ||
        path_->paths() != paths || pipeline_->progressive != progressive || !(pipeline_->needs == needs)) {
        pathMegakernel_.reset();
        whittedMegakernel_.reset();
        path_.reset();
        whitted_.reset();
        pipeline_.reset();
        const MaskMode mask = options_.mask == MaskMode::None ? defaultMaskMode() : options_.mask;
        pipeline_ = std::make_unique<GpuPipeline>(width, height, textures_, *accel_, mask, paths, progressive, needs);
        whitted_ = std::make_unique<WhittedGl>(*pipeline_, textures_, stackSlots, spawns_);
        path_ = std::make_unique<PathGl>(*pipeline_, textures_, mask, paths, options_.maskPaths);
        if (kernel_ == IntegratorKernel::Megakernel && paths) {
            pathMegakernel_ = std::make_unique<PathMegakernelGl>(*pipeline_, textures_, paths, scene_.lights.size() + 1);
            pathMegakernel_->setBouncesPerPass(options_.megakernelBounces);
        }
        if (kernel_ == IntegratorKernel::Megakernel && !paths)
            whittedMegakernel_ = std::make_unique<WhittedMegakernelGl>(*pipeline_, textures_, stackSlots, scene_.lights.size() + 1);
        for (GPUKernel* k : accel_->kernels()) {
            textures_.bindCoverage(*k);
            if (textures_.hasAlpha())  // the packed paths' pixels (scene/alpha.glsl coveragePixels)
                k->addInput(pipeline_->pathState, "coveragePixels");
        }
    }
    return *pipeline_;
}

GlIntegrator& GpuTracer::integrator(const RenderSettings& settings) {
    if (settings.integrator == Integrator::Path) {
        if (pathMegakernel_) return *pathMegakernel_;
        return *path_;
    }
    if (whittedMegakernel_) return *whittedMegakernel_;
    return *whitted_;
}

std::vector<GlIntegrator*> GpuTracer::megakernels() {
    std::vector<GlIntegrator*> all;
    if (pathMegakernel_) all.push_back(pathMegakernel_.get());
    if (whittedMegakernel_) all.push_back(whittedMegakernel_.get());
    return all;
}

std::vector<GPUKernel*> GpuTracer::allKernels() {
    std::vector<GPUKernel*> all;
    if (!pipeline_) return all;
    for (const std::vector<GPUKernel*>& ks : {pipeline_->kernels(), accel_->kernels(), whitted_->kernels(), path_->kernels()})
        all.insert(all.end(), ks.begin(), ks.end());
    for (GlIntegrator* megakernel : megakernels())
        for (GPUKernel* k : megakernel->kernels()) all.push_back(k);
    return all;
}

void GpuTracer::setCamera(const CameraBasis& camera) {
    std::vector<GPUKernel*> integrators = whitted_->kernels();
    for (GPUKernel* k : path_->kernels()) integrators.push_back(k);
    for (GlIntegrator* megakernel : megakernels())
        for (GPUKernel* k : megakernel->kernels()) integrators.push_back(k);
    pipeline_->setCamera(camera, integrators);
}

void GpuTracer::setCoverageSample(uint32_t s, uint32_t seed) {
    if (!textures_.hasAlpha()) return;
    std::vector<GPUKernel*> tracing = accel_->kernels();
    for (GlIntegrator* megakernel : megakernels())
        for (GPUKernel* k : megakernel->kernels()) tracing.push_back(k);
    for (GPUKernel* k : tracing)
        k->setUniform("coverageSample", s).setUniform("coverageSeed", seed).setUniform("coverageFromStream", 0);
}

void GpuTracer::setSample(uint32_t s, uint32_t n, uint32_t seed) {
    setCoverageSample(s, seed);
    pipeline_->setSample(s, n, seed);
    whitted_->setSample(s, n, seed);
    path_->setSample(s, n, seed);
    for (GlIntegrator* megakernel : megakernels()) megakernel->setSample(s, n, seed);
}

// The sample loop (--spp), each sample one of the integrator's (integrators/): its rounds of
// passes from raygen's rays through the sample's point of each pixel; the accumulate pass adds
// the sample's colour to the pixels' sums. The AOVs come from the pixel-centre rays: the first
// and only sample's when spp = 1, else a primary trace and surface pass of their own (Whitted's
// first round) before the samples.
RenderOutput GpuTracer::render(const CameraBasis& camera, const RenderSettings& settings) {
    const auto start = std::chrono::steady_clock::now();
    const bool paths = settings.integrator == Integrator::Path;
    const uint32_t samples = std::max(1u, settings.samples);
    GpuPipeline& p = pipeline(camera.width, camera.rows(), stackSlots(settings), paths, false, samples > 1);
    GlIntegrator& chosen = integrator(settings);
    RenderOutput out;
    out.width = camera.width;
    out.height = camera.rows();

    const std::vector<PointLight> lights = lightsOrHeadlight(scene_, camera.eye, paths);
    for (GPUKernel* k : allKernels()) k->setUniform("background", scene_.background);
    setCamera(camera);
    setCoverageSample(0, settings.seed);  // the pixel-centre rays are sample 0's (CpuTracer::render)
    if (samples > 1) whitted_->sample(lights, -1, &out, out.stats);  // pixel centres: the AOVs only
    const int bounces = std::max(0, settings.maxBounces);
    if (samples == 1) {  // the sample is the image: no sum to accumulate into
        setSample(0, 1, settings.seed);
        chosen.sample(lights, bounces, &out, out.stats);
        out.color = downloadVectors<glm::vec3>(chosen.colour());
    } else {
        p.sampleSum.fill(0.0f);
        for (uint32_t s = 0; s < samples; ++s) {
            setSample(s, samples, settings.seed);
            chosen.sample(lights, bounces, nullptr, out.stats);
            chosen.accumulate();
            // The rounds' occlusion counts already wait for the passes; glFinish makes the
            // fraction a finished one (a few microseconds a sample, only when asked for).
            if (settings.progress && s + 1 < samples) {
                glFinish();
                settings.progress(double(s + 1) / double(samples));
            }
        }
        out.color = downloadVectors<glm::vec3>(p.sampleSum);
        for (glm::vec3& c : out.color) c /= float(samples);  // CpuTracer::render divides alike
    }
    out.stats.samples = uint64_t(camera.width) * uint64_t(camera.rows()) * samples;
    flushStats();
    if (settings.progress) settings.progress(1.0);
    out.stats.totalMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
}

void GpuTracer::beginProgressive(const CameraBasis& camera, const RenderSettings& settings) {
    const bool paths = settings.integrator == Integrator::Path;
    GpuPipeline& p = pipeline(camera.width, camera.rows(), stackSlots(settings), paths, true);
    progressive_.settings = settings;
    progressive_.lights = lightsOrHeadlight(scene_, camera.eye, paths);
    for (GPUKernel* k : allKernels()) k->setUniform("background", scene_.background);
    setCamera(camera);
    setCoverageSample(0, settings.seed);
    whitted_->sample(progressive_.lights, -1, nullptr, progressive_.output.stats);  // pixel centres
    p.aovHit.copyFrom(p.hit);
    p.aovCells.copyFrom(accel_->steps());
    p.aovNormal.copyFrom(p.surfaceNormal);
    p.sampleSum.fill(0.0f);
}

void GpuTracer::addSample(uint32_t s, uint32_t n) {
    setSample(s, n, progressive_.settings.seed);
    GlIntegrator& chosen = integrator(progressive_.settings);
    chosen.sample(progressive_.lights, std::max(0, progressive_.settings.maxBounces), nullptr, progressive_.output.stats);
    chosen.accumulate();
    progressive_.output.stats.samples += uint64_t(pipeline_->width) * uint64_t(pipeline_->height);
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

uint64_t GpuTracer::tracePrimary(const CameraBasis& camera) {
    GpuPipeline& p = pipeline(camera.width, camera.rows());
    setCamera(camera);
    setCoverageSample(0, 0);  // as CpuTracer::traceStream
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
    setCoverageSample(0, 0);  // as CpuTracer::traceStream
    const uint64_t rays = accel_->trace(anyHit);
    glFinish();
    return rays;
}

void GpuTracer::flushStats() {
    for (GPUKernel* k : allKernels()) k->flushStats();
}

std::vector<glm::vec4> GpuTracer::hits() {
    if (!pipeline_) throw UsageError("GpuTracer::hits before a trace");
    return downloadVectors<glm::vec4>(pipeline_->hit);
}

}  // namespace gpurt
