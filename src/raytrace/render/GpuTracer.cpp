#include "raytrace/render/GpuTracer.h"

#include "raytrace/integrators/GpuPipeline.h"
#include "raytrace/common/RayMath.h"
#include "raytrace/materials/MaterialRecord.h"
#include "raytrace/accel/grid/GridGl.h"
#include "raytrace/integrators/Megakernel.h"
#include "raytrace/integrators/GlRegistry.h"
#include "raytrace/integrators/whitted/WhittedGl.h"

#include "../../../glsl/common/scene_layout.h"


#include "stream/GLContext.h"
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

IntegratorKernel defaultIntegratorKernel() {
    if (const char* chosen = std::getenv("GPURT_KERNEL")) {
        const std::string name = chosen;
        if (name == "wavefront") return IntegratorKernel::Wavefront;
        if (name == "megakernel") return IntegratorKernel::Megakernel;
        throw EnvironmentError("GPURT_KERNEL=" + name + ": expected wavefront or megakernel");
    }
    // Measured on llvmpipe (docs/PERFORMANCE.md, issue 24): the megakernels are faster on every
    // render measured (Whitted 1.2-1.9x, path 1.3x), the wavefront chain's passes spending their
    // time in memory traffic and stream allocation. Not measured on a GPU yet: the wavefront chain
    // stays the default there until a run of scripts/bench-kernels.py on one decides.
    return isSoftwareRenderer() ? IntegratorKernel::Megakernel : IntegratorKernel::Wavefront;
}

bool parseTraceKernel(const std::string& text, TraceKernel& kernel) {
    if (text == "fused") kernel = TraceKernel::Fused;
    else if (text == "split") kernel = TraceKernel::Split;
    else return false;
    return true;
}

int GpuTracer::stackSlots(const RenderSettings& settings) const {
    if (!splits_ || !integratorInfo(settings.integrator).rayTree) return 0;
    return std::min(std::max(0, settings.maxBounces), GPURT_STACK_SLOTS);
}

GpuPipeline& GpuTracer::pipeline(int width, int height, int stackSlots, const IntegratorInfo* integrator,
                                 bool progressive, bool sums, bool aovs, bool adaptive, bool variance, bool features) {
    // The megakernels for the integrators' samples: the wavefront rounds' streams are then 1 x 1
    // (each full-size stream costs its allocation: llvmpipe zeroes it, page by page), and a
    // pass of their own takes the pixel centres' AOVs. An integrator without a wavefront chain
    // runs as its megakernel whatever the kernel asked for.
    const bool megakernel = integrator && (kernel_ == IntegratorKernel::Megakernel || !integrator->hasWavefront);
    const bool paths = integrator && integrator->pathStreams;
    GpuPipeline::Needs needs;
    needs.emitters = !textures_.emitterTable().empty();
    needs.environment = paths && textures_.environmentTable().sampled;
    needs.pathState = paths || (spawns_ && !megakernel);
    needs.sums = sums || progressive;
    needs.stages = !megakernel;
    needs.aovs = aovs || progressive;
    needs.adaptive = adaptive;
    needs.variance = variance;
    needs.features = features && integrator && integrator->features;
    if (!pipeline_ || pipeline_->width != width || pipeline_->height != height || stackSlots_ != stackSlots ||
        integrator_ != integrator || pipeline_->progressive != progressive || !(pipeline_->needs == needs)) {
        megakernelAovs_.reset();
        chosen_.reset();
        whittedAovs_.reset();
        centres_ = nullptr;
        pipeline_.reset();
        stackSlots_ = stackSlots;
        integrator_ = integrator;
        const MaskMode mask = options_.mask == MaskMode::None ? defaultMaskMode() : options_.mask;
        pipeline_ = std::make_unique<GpuPipeline>(width, height, textures_, *accel_, mask, paths, progressive, needs);
        ++pipelineGeneration_;
        if (megakernel && needs.aovs) megakernelAovs_ = std::make_unique<MegakernelAovs>(*pipeline_, textures_);
        if (integrator) {
            const size_t lights = scene_.lights.size() + 1;  // the scene's, or the headlight
            chosen_ = makeGlIntegrator(*integrator, {*pipeline_, textures_, megakernel, mask, options_.maskPaths, stackSlots, spawns_,
                                      lights, megakernelAovs_.get(), options_.megakernelBounces});
        }
        if (!megakernel) {  // the pixel centres' AOVs: Whitted's first round (pixelCentreAovs)
            centres_ = dynamic_cast<WhittedGl*>(chosen_.get());
            if (!centres_) {
                whittedAovs_ = std::make_unique<WhittedGl>(*pipeline_, textures_, stackSlots, spawns_);
                centres_ = whittedAovs_.get();
            }
        }
        for (GPUKernel* k : accel_->kernels()) {
            textures_.bindCoverage(*k);
            if (textures_.hasAlpha())  // the packed paths' pixels (scene/alpha.glsl coveragePixels)
                k->addInput(pipeline_->pathState, "coveragePixels");
        }
    }
    return *pipeline_;
}

// The AOVs of the pixel centres' rays (several samples a pixel, the viewer): Whitted's first round
// (its trace and surface passes), or with megakernels a pass of its own.
void GpuTracer::pixelCentreAovs(const std::vector<Light>& lights, RenderOutput* out, RenderStats& stats) {
    if (!pipeline_->needs.stages) megakernelAovs_->trace(out, stats);
    else centres_->sample(lights, -1, out, stats);
}

GlIntegrator& GpuTracer::integrator() {
    if (!chosen_) throw UsageError("GpuTracer: no integrator on a pipeline made for tracing alone");
    return *chosen_;
}

std::vector<GPUKernel*> GpuTracer::integratorKernels() {
    std::vector<GPUKernel*> all;
    if (megakernelAovs_) all = megakernelAovs_->kernels();
    for (GlIntegrator* integrator : {chosen_.get(), static_cast<GlIntegrator*>(whittedAovs_.get())})
        if (integrator)
            for (GPUKernel* k : integrator->kernels()) all.push_back(k);
    return all;
}

std::vector<GPUKernel*> GpuTracer::allKernels() {
    std::vector<GPUKernel*> all;
    if (!pipeline_) return all;
    for (const std::vector<GPUKernel*>& ks : {pipeline_->kernels(), accel_->kernels(), integratorKernels()})
        all.insert(all.end(), ks.begin(), ks.end());
    return all;
}

// The uniforms of a render's settings on every kernel: the background, the sampler, the clamps and
// the integrator's own options (GPURT_FAR for an unlimited one).
void GpuTracer::setRenderUniforms(const RenderSettings& settings) {
    std::vector<std::pair<std::string, float>> options;
    for (const IntegratorOption& option : integratorInfo(settings.integrator).options)
        options.emplace_back(option.uniform, std::min(integratorOption(settings, option.uniform), GPURT_FAR));
    for (GPUKernel* k : allKernels()) {
        k->setUniform("background", scene_.background)
            .setUniform("samplerKind", unsigned(settings.sampler))
            .setUniform("clampDirect", settings.clampDirect)
            .setUniform("clampIndirect", settings.clampIndirect);
        for (const auto& [uniform, value] : options) k->setUniform(uniform, value);
    }
}

void GpuTracer::setCamera(const CameraBasis& camera) {
    pipeline_->setCamera(camera, integratorKernels());
}

void GpuTracer::setCoverageSample(uint32_t s, uint32_t seed) {
    if (!textures_.hasAlpha()) return;
    std::vector<GPUKernel*> tracing = accel_->kernels();
    if (!pipeline_->needs.stages)
        for (GPUKernel* k : integratorKernels()) tracing.push_back(k);  // the megakernels trace
    for (GPUKernel* k : tracing)
        k->setUniform("coverageSample", s).setUniform("coverageSeed", seed).setUniform("coverageFromStream", 0);
}

void GpuTracer::setSample(uint32_t s, uint32_t n, uint32_t seed) {
    setCoverageSample(s, seed);
    pipeline_->setSample(s, n, seed);
    if (chosen_) chosen_->setSample(s, n, seed);
    if (whittedAovs_) whittedAovs_->setSample(s, n, seed);
}

void GpuTracer::sampleRounds(const std::vector<Light>& lights, const RenderSettings& settings, RenderOutput& out) {
    GpuPipeline& p = *pipeline_;
    const uint32_t samples = settings.samples;
    const bool adaptive = p.needs.adaptive;
    p.sampleSum.fill(0.0f);
    if (p.needs.variance) p.squareSum.fill(0.0f);
    if (p.needs.features) {
        p.albedoSum.fill(0.0f);
        p.normalSum.fill(0.0f);
    }
    if (adaptive) p.beginAdaptive();
    const std::vector<GPUKernel*> kernels = integratorKernels();
    auto roundStart = std::chrono::steady_clock::now();
    for (uint32_t s = 0; s < samples; ++s) {
        setSample(s, samples, settings.seed);
        if (adaptive)  // the accumulate pass sums the odd samples apart (common/adaptive.h)
            for (GPUKernel* k : kernels) k->setUniform("odd", float(s & 1u));
        chosen_->sample(lights, std::max(0, settings.maxBounces), nullptr, out.stats);
        chosen_->accumulate();
        // Adaptive sampling's convergence pass (CpuTracer::render takes the same rounds): the
        // render ends when its occlusion query counts no active pixel.
        if (adaptiveCheckAfter(s + 1, settings)) {
            glFinish();  // the round's passes, timed apart from the convergence pass
            const auto now = std::chrono::steady_clock::now();
            const double ms = std::chrono::duration<double, std::milli>(now - roundStart).count();
            const uint64_t active = p.convergeRound(settings.noiseThreshold);
            roundStart = std::chrono::steady_clock::now();
            out.stats.adaptive.push_back({s + 1, active, ms});
            if (settings.adaptiveProgress) settings.adaptiveProgress(s + 1, active);
            if (active == 0) break;
        }
        // The rounds' occlusion counts already wait for the passes; glFinish makes the
        // fraction a finished one (a few microseconds a sample, only when asked for).
        if (settings.progress && s + 1 < samples) {
            glFinish();
            settings.progress(double(s + 1) / double(samples));
        }
    }
}

void GpuTracer::readSums(RenderOutput& out) {
    GpuPipeline& p = *pipeline_;
    const std::vector<glm::vec4> sums = downloadVectors<glm::vec4>(p.sampleSum);
    out.color.resize(sums.size());
    for (size_t i = 0; i < sums.size(); ++i) {  // CpuTracer::render divides alike
        out.color[i] = glm::vec3(sums[i]) / sums[i].w;
        out.stats.samples += uint64_t(sums[i].w);
    }
    if (p.needs.features) {  // the means, as CpuTracer::render divides them
        out.albedo = downloadVectors<glm::vec3>(p.albedoSum);
        out.shadingNormal = downloadVectors<glm::vec3>(p.normalSum);
        for (size_t i = 0; i < sums.size(); ++i) {
            out.albedo[i] = out.albedo[i] / sums[i].w;
            out.shadingNormal[i] = out.shadingNormal[i] / sums[i].w;
        }
    }
    if (p.needs.adaptive) {
        out.spp.resize(sums.size());
        for (size_t i = 0; i < sums.size(); ++i) out.spp[i] = sums[i].w;
    }
    if (p.needs.variance) {
        const std::vector<glm::vec3> squares = downloadVectors<glm::vec3>(p.squareSum);
        out.variance.resize(sums.size());
        for (size_t i = 0; i < sums.size(); ++i) out.variance[i] = varianceOfMean(glm::vec3(sums[i]), squares[i], sums[i].w);
    }
}

// The sample loop (--spp), each sample one of the integrator's (integrators/): its rounds of
// passes from raygen's rays through the sample's point of each pixel; the accumulate pass adds
// the sample's colour to the pixels' sums. The AOVs come from the pixel-centre rays: the first
// and only sample's when spp = 1, else a primary trace and surface pass of their own (Whitted's
// first round) before the samples.
RenderOutput GpuTracer::render(const CameraBasis& camera, const RenderSettings& settings) {
    const auto start = std::chrono::steady_clock::now();
    const IntegratorInfo& info = integratorInfo(settings.integrator);
    const uint32_t samples = std::max(1u, settings.samples);
    const bool adaptive = settings.adaptive() && samples > 1;
    const bool variance = settings.variance && samples > 1;
    const bool features = settings.features && info.features;
    GpuPipeline& p = pipeline(camera.width, camera.rows(), stackSlots(settings), &info, false, samples > 1,
                              settings.aovs, adaptive, variance, features);
    GlIntegrator& chosen = integrator();
    RenderOutput out;
    out.width = camera.width;
    out.height = camera.rows();

    const std::vector<Light> lights = lightsOrHeadlight(scene_, camera.eye, info.pathStreams);
    setRenderUniforms(settings);
    setCamera(camera);
    setCoverageSample(0, settings.seed);  // the pixel-centre rays are sample 0's (CpuTracer::render)
    if (samples > 1 && settings.aovs) pixelCentreAovs(lights, &out, out.stats);
    const int bounces = std::max(0, settings.maxBounces);
    if (samples == 1) {  // the sample is the image: no sum to accumulate into
        setSample(0, 1, settings.seed);
        chosen.sample(lights, bounces, settings.aovs ? &out : nullptr, out.stats);
        out.color = downloadVectors<glm::vec3>(chosen.colour());
        if (features) {
            out.albedo = downloadVectors<glm::vec3>(p.pixelAlbedo);
            out.shadingNormal = downloadVectors<glm::vec3>(p.pixelNormal);
        }
    } else {
        sampleRounds(lights, settings, out);
        readSums(out);
    }
    if (settings.variance && samples == 1) out.variance.assign(out.color.size(), glm::vec3(0.0f));
    if (samples == 1) out.stats.samples = uint64_t(camera.width) * uint64_t(camera.rows());
    flushStats();
    if (settings.progress) settings.progress(1.0);
    out.stats.totalMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
}

void GpuTracer::beginProgressive(const CameraBasis& camera, const RenderSettings& settings) {
    const IntegratorInfo& info = integratorInfo(settings.integrator);
    GpuPipeline& p = pipeline(camera.width, camera.rows(), stackSlots(settings), &info, true, false, true,
                              settings.adaptive(), settings.variance, settings.features);
    progressive_.settings = settings;
    progressive_.lights = lightsOrHeadlight(scene_, camera.eye, info.pathStreams);
    setRenderUniforms(settings);
    setCamera(camera);
    setCoverageSample(0, settings.seed);
    pixelCentreAovs(progressive_.lights, nullptr, progressive_.output.stats);
    p.aovHit.copyFrom(p.hit);
    p.aovCells.copyFrom(megakernelAovs_ ? megakernelAovs_->steps() : accel_->steps());
    p.aovNormal.copyFrom(megakernelAovs_ ? megakernelAovs_->normals() : p.surfaceNormal);
    p.sampleSum.fill(0.0f);
    if (p.needs.variance) p.squareSum.fill(0.0f);
    if (p.needs.features) {
        p.albedoSum.fill(0.0f);
        p.normalSum.fill(0.0f);
        if (!denoiser_ || denoiserGeneration_ != pipelineGeneration_) {
            denoiser_ = std::make_unique<DenoiserGl>(p.width, p.height);
            denoiser_->bindSums(p.sampleSum, p.squareSum, p.albedoSum, p.normalSum, p.aovHit);
            denoiserGeneration_ = pipelineGeneration_;
        }
    }
    if (settings.adaptive()) p.beginAdaptive();
}

// Under adaptive sampling the viewer's sums stop refining converged pixels as render does (the
// same rounds, with n the most a pixel takes).
void GpuTracer::addSample(uint32_t s, uint32_t n) {
    const RenderSettings& settings = progressive_.settings;
    setSample(s, n, settings.seed);
    if (pipeline_->needs.adaptive)
        for (GPUKernel* k : integratorKernels()) k->setUniform("odd", float(s & 1u));
    GlIntegrator& chosen = integrator();
    chosen.sample(progressive_.lights, std::max(0, settings.maxBounces), nullptr, progressive_.output.stats);
    chosen.accumulate();
    progressive_.output.stats.samples += uint64_t(pipeline_->width) * uint64_t(pipeline_->height);
    RenderSettings rounds = settings;
    rounds.samples = n;
    if (pipeline_->needs.adaptive && adaptiveCheckAfter(s + 1, rounds))
        progressive_.output.stats.adaptive.push_back({s + 1, pipeline_->convergeRound(settings.noiseThreshold)});
}

void GpuTracer::bindDisplay(GPUKernel& display) {
    if (!pipeline_) throw UsageError("GpuTracer::bindDisplay before beginProgressive");
    display.addInput(pipeline_->sampleSum, "sampleSum").addInput(pipeline_->aovHit, "aovHit");
    display.addInput(pipeline_->aovCells, "aovCells").addInput(pipeline_->aovNormal, "aovNormal");
    display.addInput(denoiser_ && denoiserGeneration_ == pipelineGeneration_ ? denoiser_->output() : pipeline_->sampleSum,
                     "denoised");
}

void GpuTracer::denoiseProgressive() {
    if (!denoiser_ || denoiserGeneration_ != pipelineGeneration_)
        throw UsageError("GpuTracer::denoiseProgressive without the features (RenderSettings::features)");
    denoiser_->denoiseSums();
}

float GpuTracer::progressiveHitDistance(int x, int y) const {
    constexpr float kNone = std::numeric_limits<float>::infinity();
    if (!pipeline_ || x < 0 || y < 0 || x >= pipeline_->width || y >= pipeline_->height) return kNone;
    const std::vector<float> hits = pipeline_->aovHit.download();  // a key press's, not a frame's
    const size_t texel = (size_t(y) * size_t(pipeline_->width) + size_t(x)) * 4;
    return texel + 3 < hits.size() && hits[texel + 3] >= 0.0f ? hits[texel] : kNone;
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
