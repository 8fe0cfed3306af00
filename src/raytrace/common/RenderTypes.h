// What a render is asked for and what it returns; shared by the CPU and GL backends so that tools
// and tests treat both alike.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace gpurt {

// The two backends (--backend).
enum class Backend {
    Gl,   // the stream kernels on the GL context (render/GpuTracer)
    Cpu,  // the same algorithm in C++ (render/CpuTracer)
};

// --integrator: an integrator of the registry (integrators/Registry.h, which says what each can
// do), by its name: Whitted's ray tree (shadows, mirror, glass; the default), path tracing with
// next-event estimation (glsl/common/integrators/path.h), ambient occlusion, ...
class Integrator {
  public:
    static const Integrator Whitted, Path;
    constexpr explicit Integrator(std::string_view name) : name_(name) {}
    constexpr std::string_view name() const { return name_; }
    constexpr bool operator==(const Integrator& o) const { return name_ == o.name_; }
    constexpr bool operator!=(const Integrator& o) const { return name_ != o.name_; }

  private:
    std::string_view name_;  // a registry entry's (static storage)
};
inline constexpr Integrator Integrator::Whitted{"whitted"};
inline constexpr Integrator Integrator::Path{"path"};

// --sampler: where each sample's random numbers come from (glsl/common/sampling.h; the values are
// its GPURT_SAMPLER_*).
enum class SamplerKind : uint32_t { Sobol = 0, Stratified = 1, Random = 2 };

// The path integrator's --bounces when none is given (pbrt's default maxdepth is 5, Cycles' 12).
constexpr int kDefaultPathBounces = 8;

struct RenderSettings {
    // The image size is the camera's (CameraBasis); these are kept for callers.
    int width = 512, height = 512;
    // Levels of the ray tree after the primary hit (mirror, glass; callers copy
    // Scene::maxBounces here).
    // Under the path integrator: the longest path in hits after which light is gathered (pbrt's
    // maxdepth: 1 is direct light only, 0 the emitters the camera sees).
    int maxBounces = 3;
    Integrator integrator = Integrator::Whitted;
    int threads = 0;  // CPU backend: 0 = all cores
    // --spp: samples per pixel (1: the pixel-centre ray) and --seed (glsl/common/sampling.h).
    uint32_t samples = 1;
    uint32_t seed = 0;
    SamplerKind sampler = SamplerKind::Sobol;
    // Adaptive sampling (--noise-threshold, path integrator; glsl/common/adaptive.h): 0 is off,
    // else each pixel takes at least minSamples (--min-spp) samples and stops once its
    // neighbourhood's error is below noiseThreshold; `samples` is then the most it takes.
    float noiseThreshold = 0.0f;
    uint32_t minSamples = 0;
    bool adaptive() const { return noiseThreshold > 0.0f; }
    // --clamp-direct, --clamp-indirect (path integrator; common/path.h clampContribution): 0 is
    // off. The library's default is off; the command's indirect default is Cycles' 10.
    float clampDirect = 0.0f, clampIndirect = 0.0f;
    // The integrator's own options (IntegratorInfo::options) by their uniform names; an option
    // not given takes its default.
    std::map<std::string, float> integratorOptions;
    // The variance AOV (RenderOutput::variance): the sums of the samples' squares as well.
    bool variance = false;
    // The denoiser's features (RenderOutput::albedo, shadingNormal; the path integrator only).
    bool features = false;
    // The primary AOVs (depth, prim, normal, steps) in RenderOutput, from the pixel centres' rays;
    // false: the colour alone (gpurt render without --aov), and no pixel-centre rays of their own
    // for several samples a pixel.
    bool aovs = true;
    // Called with the fraction of the render done (0..1, rising; 1 once it is done) after each
    // sample (gl) or image row (cpu), from the rendering thread or a worker (never two at once).
    // Nothing of the image depends on it.
    std::function<void(double)> progress;
    // Adaptive sampling: called after each convergence pass with the samples taken and the pixels
    // still active (both backends; the same thread rules as progress).
    std::function<void(uint32_t, uint64_t)> adaptiveProgress;
};

// Cycles' default --min-spp for a --noise-threshold (Integrator::get_adaptive_sampling: "threshold
// 0.1 -> 32, 0.01 -> 64, 0.001 -> 128"): max(4, ceil(16 / threshold^0.3)).
uint32_t defaultMinSamples(float noiseThreshold);

// Whether an adaptive render with these settings checks convergence once `taken` samples a pixel
// are summed: at minSamples, then at each multiple of GPURT_ADAPTIVE_STEP above it, before the
// last sample (both backends take the same rounds).
bool adaptiveCheckAfter(uint32_t taken, const RenderSettings& settings);

// The variance of a pixel's mean from the sum and the sum of squares of its n samples, per channel
// (both backends; the variance AOV).
glm::vec3 varianceOfMean(glm::vec3 sum, glm::vec3 squares, float n);

// One convergence pass of an adaptive render: the pixels still active after `samples` samples.
struct AdaptiveRound {
    uint32_t samples = 0;
    uint64_t active = 0;
    // Wall time of the round's samples (since the last convergence pass, or the first sample),
    // in milliseconds: the masked passes' cost against the pixels they ran for.
    double ms = 0.0;
};

struct RenderStats {
    uint64_t primaryRays = 0, shadowRays = 0, secondaryRays = 0;
    // Rays stopped by the traversal step limit (RAY_OVERFLOW): a bug if > 0. The GL backend
    // counts primary rays only (their cell counts are read back for the steps AOV).
    uint64_t overflowRays = 0;
    // The path integrator: livePaths[b] paths (over all samples) reached hit depth b, that is,
    // traced their ray of round b (round 0: the camera rays). Empty for Whitted.
    std::vector<uint64_t> livePaths;
    uint64_t samples = 0;  // pixel samples taken (width x height x spp; adaptive: the sum over the pixels)
    std::vector<AdaptiveRound> adaptive;  // adaptive sampling's convergence passes, in order
    double totalMs = 0;
    // The denoiser's (render --denoise): whether it ran, the pixels it refused (not finite), its time.
    bool denoised = false;
    uint64_t denoiseRefused = 0;
    double denoiseMs = 0.0;

    void addLivePaths(size_t round, uint64_t paths) {
        if (livePaths.size() <= round) livePaths.resize(round + 1, 0);
        livePaths[round] += paths;
    }
};

// The image and the contract's AOVs, all row-major with row 0 = the TOP row of the image.
struct RenderOutput {
    int width = 0, height = 0;
    std::vector<glm::vec3> color;  // linear RGB: the mean of the pixel's samples
    // t of the first hit along the normalised primary ray; +inf on a miss.
    std::vector<float> depth;
    std::vector<float> prim;        // triangle index of the first hit; -1 on a miss
    std::vector<glm::vec3> normal;  // geometric unit normal facing the eye; 0,0,0 on a miss
    std::vector<float> steps;       // grid cells visited by the primary ray
    // The samples each pixel took (adaptive sampling; empty otherwise: every pixel took --spp).
    std::vector<float> spp;
    // With RenderSettings::variance: per channel, the variance of each pixel's mean (the samples'
    // variance over their count: (sum of squares / n - mean^2) / (n - 1)); 0 for one sample.
    std::vector<glm::vec3> variance;
    // With RenderSettings::features (path integrator): the means over each pixel's samples of the
    // albedo and the shading normal of the first hit that is not a mirror or smooth glass
    // (common/path.h featuresOpenAfter; Open Image Denoise's feature images).
    std::vector<glm::vec3> albedo, shadingNormal;
    RenderStats stats;
};

// Rays to trace as a stream (gpurt bench), for every backend: one element per ray, laid out width x height.
struct RayStream {
    int width = 0, height = 0;
    std::vector<glm::vec3> origin, direction;  // direction normalised
    std::vector<float> tLimit;                 // < 0: no ray in this element

    // The elements that carry a ray.
    uint64_t rays() const {
        uint64_t n = 0;
        for (float t : tLimit) n += t >= 0.0f;
        return n;
    }
};

}  // namespace gpurt
