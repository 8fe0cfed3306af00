// The denoiser on the cpu backend: the passes of glsl/denoise/ (demodulate, the a-trous
// iterations, remodulate) in C++ over the same common/denoise.h.
#include "raytrace/denoise/Denoise.h"

#include "base/Parallel.h"
#include "raytrace/common/RayMath.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace gpurt {

namespace {

using namespace raymath;

// What an iteration reads: the last signal and the guides (common/denoise.h's hooks).
struct DenoiseTexels {
    const std::vector<vec4>* signal;
    const std::vector<vec3>* albedo;
    const std::vector<vec4>* normal;
    const std::vector<vec3>* color;
    int width;
    size_t at(ivec2 q) const { return size_t(q.y) * size_t(width) + size_t(q.x); }
};

#define GPURT_DENOISE_PARAMS const DenoiseTexels &texels,
#define GPURT_DENOISE_SIGNAL(q) (*texels.signal)[texels.at(q)]
#define GPURT_DENOISE_ALBEDO(q) (*texels.albedo)[texels.at(q)]
#define GPURT_DENOISE_NORMAL(q) (*texels.normal)[texels.at(q)]
#define GPURT_DENOISE_COLOR(q) (*texels.color)[texels.at(q)]
#include "../../../glsl/common/denoise.h"

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

int denoiseIterations(int width, int height) { return denoiseIterations(std::min(width, height)); }

DenoiseImages denoiseImages(const RenderOutput& out) {
    DenoiseImages in;
    in.width = out.width;
    in.height = out.height;
    in.color = out.color;
    in.variance = out.variance;
    in.albedo = out.albedo;
    in.normal = out.shadingNormal;
    in.depth = out.depth;
    return in;
}

void checkDenoiseImages(const DenoiseImages& in) {
    const size_t n = size_t(in.width) * size_t(in.height);
    if (in.width <= 0 || in.height <= 0) throw std::invalid_argument("color: an empty image");
    auto check = [&](size_t size, const char* name, bool optional) {
        if (optional && size == 0) return;
        if (size != n)
            throw std::invalid_argument(std::string(name) + (size == 0 ? ": missing" : ": not the colour image's size"));
    };
    check(in.color.size(), "color", false);
    check(in.albedo.size(), "albedo", false);
    check(in.normal.size(), "normal", false);
    check(in.variance.size(), "variance", true);
    check(in.depth.size(), "depth", true);
}

uint64_t refusedPixels(const DenoiseImages& in) {
    uint64_t refused = 0;
    for (size_t p = 0; p < in.color.size(); ++p) {
        bool ok = finite(in.color[p]) && finite(in.albedo[p]) && finite(in.normal[p]);
        if (!in.variance.empty()) ok = ok && finite(in.variance[p]);
        if (!in.depth.empty()) ok = ok && !std::isnan(in.depth[p]) && in.depth[p] != -std::numeric_limits<float>::infinity();
        refused += ok ? 0 : 1;
    }
    return refused;
}

std::vector<glm::vec3> denoiseVariance(const DenoiseImages& in) {
    std::vector<glm::vec3> out = in.variance;
    out.resize(in.color.size(), glm::vec3(0.0f));
    const DenoiseTexels texels{nullptr, nullptr, nullptr, &in.color, in.width};
    for (int y = 0; y < in.height; ++y)
        for (int x = 0; x < in.width; ++x)
            if (glm::vec3& v = out[texels.at(ivec2(x, y))]; v == glm::vec3(0.0f))
                v = denoiseVarianceEstimate(texels, ivec2(x, y), ivec2(in.width, in.height));
    return out;
}

std::vector<glm::vec3> denoiseCpu(const DenoiseImages& in, int threads, DenoiseStats* stats) {
    checkDenoiseImages(in);
    const auto start = std::chrono::steady_clock::now();
    const size_t n = size_t(in.width) * size_t(in.height);
    const std::vector<glm::vec3> variance = denoiseVariance(in);
    // Step 1: the signal and the guides (demodulate.frag).
    std::vector<vec4> signal(n), next(n), normal(n);
    for (size_t p = 0; p < n; ++p) {
        normal[p] = vec4(in.normal[p], in.depth.empty() ? 0.0f : in.depth[p]);
        signal[p] = denoiseDemodulate(in.color[p], variance[p], in.albedo[p]);
    }
    // Step 2: the iterations (atrous.frag), rows in parallel.
    const ivec2 size(in.width, in.height);
    const int iterations = denoiseIterations(in.width, in.height);
    for (int i = 0; i < iterations; ++i) {
        const DenoiseTexels texels{&signal, &in.albedo, &normal, nullptr, in.width};
        parallelChunks(size_t(in.height), 1, threads, [&](size_t row, size_t, size_t) {
            for (int x = 0; x < in.width; ++x)
                next[row * size_t(in.width) + size_t(x)] = denoiseIteration(texels, ivec2(x, int(row)), size, 1 << i);
        });
        signal.swap(next);
    }
    // Step 3 (the last iteration's REMODULATE).
    std::vector<glm::vec3> out(n);
    for (size_t p = 0; p < n; ++p) out[p] = denoiseRemodulate(signal[p], in.albedo[p]);
    if (stats) {
        stats->refused = refusedPixels(in);
        stats->ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    return out;
}

}  // namespace gpurt
