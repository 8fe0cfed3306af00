// The denoiser as stream kernels (glsl/denoise/): a demodulate pass, then the a-trous iterations
// as passes over ping-pong streams, the last one remodulating into the output stream. Needs a
// current GL context; the same filter as denoiseCpu (Denoise.h).
#pragma once

#include "raytrace/common/RenderTypes.h"
#include "raytrace/denoise/Denoise.h"
#include "stream/GPUFloatArray.h"
#include "stream/GPUKernel.h"

#include <glm/glm.hpp>

#include <vector>

namespace gpurt {

class DenoiserGl {
  public:
    DenoiserGl(int width, int height);

    int width() const { return width_; }
    int height() const { return height_; }

    // Uploads the images (checkDenoiseImages; the variance estimated where none is given), runs
    // the passes and returns the denoised colour.
    std::vector<glm::vec3> denoise(const DenoiseImages& in, DenoiseStats* stats = nullptr);

    // The viewer: the passes read a progressive render's running sums (of the samples, their
    // squares, albedos and shading normals; each (sum, count) in sampleSum) and its pixel-centre
    // hits for the depth, bound once.
    void bindSums(const GPUFloatArray& sampleSum, const GPUFloatArray& squareSum, const GPUFloatArray& albedoSum,
                  const GPUFloatArray& normalSum, const GPUFloatArray& aovHit);
    // Runs the passes from the sums bound (does not wait for them).
    void denoiseSums();
    // The last denoise's colour: (colour, 1), element (x, y) = pixel x of row y from the top.
    const GPUFloatArray& output() const { return output_; }

  private:
    void iterate();

    int width_, height_;
    GPUFloatArray colorIn_, varianceIn_, albedoIn_, normalIn_;
    GPUPingPongArray signal_;
    GPUFloatArray albedo_, normal_, output_;
    GPUKernel demodulate_, demodulateSums_, atrous_, remodulate_;
    bool sumsBound_ = false;
};

// The denoised colour on the backend's filter (gl: on the current context; cpu: on `threads`
// workers, 0: all cores).
std::vector<glm::vec3> denoise(Backend backend, const DenoiseImages& in, int threads = 0, DenoiseStats* stats = nullptr);

}  // namespace gpurt
