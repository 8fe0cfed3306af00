// The CPU backend: the integrators' per-sample code (Whitted's ray tree, the path integrator) over
// a CpuAccelerator, with the shared shading, material and path code of glsl/common.
#include "raytrace/render/CpuTracer.h"
#include "raytrace/lights/PunctualLights.h"

#include "raytrace/materials/SurfaceTexture.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>

#include "raytrace/materials/MaterialRecord.h"
#include "raytrace/accel/grid/GridCpu.h"
#include "raytrace/integrators/Registry.h"
#include "raytrace/integrators/whitted/WhittedCpu.h"
#include "base/Parallel.h"
#include "raytrace/common/RayMath.h"

namespace gpurt {

using namespace raymath;

CpuTracer::CpuTracer(const Scene& scene, const UniformGrid& grid)
    : CpuScene(scene, std::make_unique<GridCpu>(scene, grid), grid.rayOffset()) {}

uint64_t CpuTracer::traceStream(const RayStream& rays, bool anyHit, int threads,
                               std::vector<glm::vec4>& hits) const {
    const size_t n = rays.tLimit.size();
    hits.assign(n, glm::vec4(std::numeric_limits<float>::infinity(), 0.0f, 0.0f, -1.0f));
    parallelChunks(n, std::max<size_t>(8, size_t(rays.width)), threads, [&](size_t begin, size_t end, size_t) {
        for (size_t i = begin; i < end; ++i) {
            if (rays.tLimit[i] < 0.0f) continue;
            // Element (x, y) as pixel (x, y) of sample 0, seed 0 (the gl trace kernels' default uniforms).
            const uint32_t key = coverageKey(uint32_t(i % size_t(rays.width)), uint32_t(i / size_t(rays.width)), 0u, 0u);
            const TraceHit h = anyHit ? traceAny(rays.origin[i], rays.direction[i], rays.tLimit[i], key)
                                      : trace(rays.origin[i], rays.direction[i], rays.tLimit[i], key);
            if (h.prim >= 0) hits[i] = glm::vec4(h.t, h.u, h.v, float(h.prim));
        }
    });
    return rays.rays();
}

namespace {

// The output image (the camera's width x its rows) with its AOVs cleared to a miss.
RenderOutput emptyOutput(const CameraBasis& camera, const RenderSettings& settings) {
    RenderOutput out;
    out.width = camera.width;
    out.height = camera.rows();  // image rows camera.rowBegin on (pixel (i, j) of the camera is
                                 // element (i, j - rowBegin) of the output)
    const size_t pixels = size_t(camera.width) * size_t(out.height);
    out.color.assign(pixels, glm::vec3(0.0f));
    if (settings.aovs) {
        out.depth.assign(pixels, std::numeric_limits<float>::infinity());
        out.prim.assign(pixels, -1.0f);
        out.normal.assign(pixels, glm::vec3(0.0f));
        out.steps.assign(pixels, 0.0f);
    }
    return out;
}

// Each pixel's sums as the gl backend's accumulate pass keeps them: of all its samples (and
// their count), of its odd-numbered ones (adaptive), of their squares (the variance AOV), of
// their features (the denoiser's albedo and normal); and whether it is still active.
struct PixelSums {
    PixelSums(size_t pixels, bool adaptive, bool variance, bool features)
        : sums(pixels, glm::vec3(0.0f)), oddSums(adaptive ? pixels : 0, glm::vec3(0.0f)), counts(pixels, 0.0f),
          squares(variance ? pixels : 0, glm::vec3(0.0f)), albedo(features ? pixels : 0, glm::vec3(0.0f)),
          normal(albedo), active(pixels, 1) {}

    void add(size_t pixel, uint32_t sample, glm::vec3 c, const SampleFeatures* f) {
        if (f) {
            albedo[pixel] += f->albedo;
            normal[pixel] += f->normal;
        }
        sums[pixel] += c;
        counts[pixel] += 1.0f;
        if (!oddSums.empty() && (sample & 1u) != 0u) oddSums[pixel] += c;
        if (!squares.empty()) squares[pixel] += c * c;
    }

    // The means into the output: colour, samples taken (adaptive), features, variance.
    void finish(RenderOutput& out) const {
        const size_t pixels = sums.size();
        for (size_t p = 0; p < pixels; ++p) out.color[p] = sums[p] / counts[p];
        if (!oddSums.empty()) out.spp = counts;
        if (!albedo.empty()) {
            out.albedo.resize(pixels);
            out.shadingNormal.resize(pixels);
            for (size_t p = 0; p < pixels; ++p) {
                out.albedo[p] = albedo[p] / counts[p];
                out.shadingNormal[p] = normal[p] / counts[p];
            }
        }
        if (!squares.empty()) {
            out.variance.resize(pixels);
            for (size_t p = 0; p < pixels; ++p) out.variance[p] = gpurt::varianceOfMean(sums[p], squares[p], counts[p]);
        }
        for (float c : counts) out.stats.samples += uint64_t(c);
    }

    std::vector<glm::vec3> sums, oddSums;
    std::vector<float> counts;
    std::vector<glm::vec3> squares, albedo, normal;
    std::vector<uint8_t> active;
};

// The workers' counts into the output's.
void addStats(const std::vector<RenderStats>& threadStats, RenderStats& total) {
    for (const RenderStats& s : threadStats) {
        total.primaryRays += s.primaryRays;
        total.shadowRays += s.shadowRays;
        total.secondaryRays += s.secondaryRays;
        total.overflowRays += s.overflowRays;
        for (size_t b = 0; b < s.livePaths.size(); ++b) total.addLivePaths(b, s.livePaths[b]);
    }
}

// The last sample of the round that starts at `taken`: up to the next convergence pass, or the
// last sample.
uint32_t roundEnd(uint32_t taken, uint32_t samples, bool adaptive, const RenderSettings& settings) {
    if (!adaptive) return samples;
    uint32_t next = taken + 1;
    while (next < samples && !adaptiveCheckAfter(next, settings)) ++next;
    return next;
}

}  // namespace

// The pixel-centre ray for the AOVs when there are several samples, then the samples of the
// integrator (integrators/whitted/WhittedCpu, integrators/path/PathCpu), summed in order and
// divided by their number (as the GL accumulate pass sums). Rows are handed out one at a time:
// cost varies strongly across the image. Adaptive sampling (settings.adaptive()) takes the samples
// in rounds over the whole image, as the gl backend's passes do, with a convergence pass between
// them (common/adaptive.h) that stops pixels; the rounds and decisions are the gl backend's.
RenderOutput CpuTracer::render(const CameraBasis& camera, const RenderSettings& settings) const {
    const auto start = std::chrono::steady_clock::now();
    RenderOutput out = emptyOutput(camera, settings);
    const IntegratorInfo& info = integratorInfo(settings.integrator);
    // The integrator's own options, each resolved once (its default where none is given; an
    // unlimited one as GPURT_FAR, as the kernels' uniforms hold it), not once a sample.
    RenderSettings sampleSettings = settings;
    for (const IntegratorOption& option : info.options)
        sampleSettings.integratorOptions[option.uniform] = std::min(integratorOption(settings, option.uniform), GPURT_FAR);
    const PunctualLights lights = punctualLights(lightsOrHeadlight(scene(), camera.eye, info.pathStreams));
    const int stackSlots = std::min(std::max(0, settings.maxBounces), GPURT_STACK_SLOTS);
    const uint32_t samples = std::max(1u, settings.samples);
    const bool adaptive = settings.adaptive() && samples > 1;
    const bool features = settings.features && info.features;
    PixelSums pixels(out.color.size(), adaptive, settings.variance, features);
    // Samples [first, last) of pixel (i, j), and its AOVs with the first.
    auto shadePixel = [&](int i, int j, uint32_t first, uint32_t last, RenderStats& stats) {
        const size_t pixel = size_t(j - camera.rowBegin) * size_t(camera.width) + size_t(i);
        if (!pixels.active[pixel]) return;
        if (first == 0 && samples > 1 && settings.aovs)
            whittedSample(*this, {i, j, 0, 1, settings.seed, settings.sampler}, camera.eye,
                          primaryDirection(camera, i, j), lights, -1, stackSlots, {&out, pixel}, stats);
        const PixelAovs aovs = samples == 1 && settings.aovs ? PixelAovs{&out, pixel} : PixelAovs{};
        for (uint32_t s = first; s < last; ++s) {
            const CameraRay ray = sampleRay(camera, i, j, s, samples, settings.seed, settings.sampler);
            SampleFeatures f;
            const glm::vec3 c = info.cpuSample(*this, {i, j, s, samples, settings.seed, settings.sampler}, ray.origin,
                                               ray.direction, lights, sampleSettings, aovs, stats,
                                               features ? &f : nullptr);
            pixels.add(pixel, s, c, features ? &f : nullptr);
        }
    };

    const int threads = std::min(resolveThreads(settings.threads), std::max(1, out.height));
    std::vector<RenderStats> threadStats(static_cast<size_t>(threads));
    std::mutex progressMutex;
    size_t rowsDone = 0;
    for (uint32_t taken = 0; taken < samples;) {
        const auto roundStart = std::chrono::steady_clock::now();
        const uint32_t next = roundEnd(taken, samples, adaptive, settings);
        parallelChunks(size_t(out.height), 1, threads, [&](size_t row, size_t, size_t worker) {
            for (int i = 0; i < camera.width; ++i)
                shadePixel(i, camera.rowBegin + int(row), taken, next, threadStats[worker]);
            if (settings.progress && !adaptive) {
                const std::lock_guard<std::mutex> lock(progressMutex);
                if (++rowsDone < size_t(out.height)) settings.progress(double(rowsDone) / double(out.height));
            }
        });
        taken = next;
        if (!adaptive || taken >= samples) break;
        if (settings.progress) settings.progress(double(taken) / double(samples));
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - roundStart).count();
        const uint64_t left = convergencePass(camera.width, out.height, pixels.sums, pixels.oddSums, pixels.counts,
                                              settings.noiseThreshold, threads, pixels.active);
        out.stats.adaptive.push_back({taken, left, ms});
        if (settings.adaptiveProgress) settings.adaptiveProgress(taken, left);
        if (left == 0) break;
    }
    pixels.finish(out);
    if (settings.progress) settings.progress(1.0);
    addStats(threadStats, out.stats);
    out.stats.totalMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
}

// The convergence pass of integrators/converge.frag over a width x height image of sums: each
// active pixel stays active while an error of its 3 x 3 neighbourhood is at or above the
// threshold. Returns the pixels still active.
uint64_t convergencePass(int width, int height, const std::vector<glm::vec3>& sums,
                         const std::vector<glm::vec3>& oddSums, const std::vector<float>& counts, float threshold,
                         int threads, std::vector<uint8_t>& active) {
    std::vector<uint8_t> next(active.size(), 0);
    parallelChunks(size_t(height), 1, threads, [&](size_t row, size_t, size_t) {
        for (int x = 0; x < width; ++x) {
            const size_t at = row * size_t(width) + size_t(x);
            if (!active[at]) continue;
            float error = 0.0f;
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    const int qx = x + dx, qy = int(row) + dy;
                    if (qx < 0 || qy < 0 || qx >= width || qy >= height) continue;
                    const size_t q = size_t(qy) * size_t(width) + size_t(qx);
                    error = std::max(error, pixelError(sums[q], oddSums[q], counts[q]));
                }
            }
            next[at] = pixelConverged(error, threshold) ? 0 : 1;
        }
    });
    active.swap(next);
    uint64_t left = 0;
    for (uint8_t a : active) left += a;
    return left;
}

}  // namespace gpurt
