// The denoiser (render --denoise, gpurt denoise, the viewer): an edge-avoiding a-trous filter over
// the albedo-demodulated colour, guided by the path integrator's features and the variance
// (glsl/common/denoise.h, shared by both backends). This is its input and the cpu backend;
// DenoiseGl.h runs the same passes as stream kernels.
#pragma once

#include "raytrace/common/RenderTypes.h"

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace gpurt {

// The images a denoise reads, all width x height, row 0 = the top row (RenderOutput's layout), as
// the contract's AOVs define them: color (the mean), variance (of the mean), albedo,
// shading_normal, depth (+inf on a miss). depth and variance may be empty: without a depth, depth
// does not guide; a pixel without a variance, or with 0 in every channel (one sample), gets an
// estimate from its 3 x 3 neighbourhood (common/denoise.h denoiseVarianceEstimate).
struct DenoiseImages {
    int width = 0, height = 0;
    std::vector<glm::vec3> color, variance, albedo, normal;
    std::vector<float> depth;
};

struct DenoiseStats {
    uint64_t refused = 0;  // pixels with a value that is not finite: they weigh nothing
    double ms = 0.0;       // the filter's wall time
};

// The a-trous iterations for a width x height image, the last of holes 2^(n-1) pixels
// (common/denoise.h denoiseIterations).
int denoiseIterations(int width, int height);

// The denoiser's input from a render with RenderSettings::features and variance (its depth AOV
// when it has one).
DenoiseImages denoiseImages(const RenderOutput& out);

// The pixels with a value in some image that is not finite (NaN or an infinity; depth's +inf is
// a miss and counts as finite).
uint64_t refusedPixels(const DenoiseImages& in);

// The variance the filter uses: the given one, or the estimate where none is given or a pixel's
// is 0.
std::vector<glm::vec3> denoiseVariance(const DenoiseImages& in);

// Throws std::invalid_argument naming the first image that is missing or of the wrong size.
void checkDenoiseImages(const DenoiseImages& in);

// The files of a denoise (gpurt denoise): color, albedo and normal required, depth and variance
// optional (empty).
struct DenoiseFiles {
    std::string color, albedo, normal, depth, variance;
};

// One image (EXR or PFM) of `channels` channels for `role` (color, albedo, normal, depth,
// variance), top row first. Throws InputError naming the file when it is unreadable, of another
// kind (a PNG), has other channels, or holds a value that is not finite (a depth may be +inf).
std::vector<float> readDenoiseImage(const std::string& file, const std::string& role, int channels, int& width,
                                    int& height);
// All of them; InputError naming the file whose size differs from the colour's.
DenoiseImages readDenoiseImages(const DenoiseFiles& files);

// The cpu backend: the denoised colour, on up to `threads` workers (0: all cores).
std::vector<glm::vec3> denoiseCpu(const DenoiseImages& in, int threads = 0, DenoiseStats* stats = nullptr);

}  // namespace gpurt
