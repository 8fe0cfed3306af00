// The integrator seam on the gl backend: an integrator takes one sample of every pixel as rounds
// of passes over the shared streams (GpuPipeline), tracing through the accelerator, into a colour
// stream; GpuTracer runs the sample loop, the sums and the AOVs around it. Each is
// made by its registry entry (integrators/Registry.h); docs/ARCHITECTURE.md says how to add one.
#pragma once

#include "raytrace/common/RenderTypes.h"
#include "scene/Scene.h"
#include "stream/GPUFloatArray.h"
#include "stream/GPUKernel.h"

#include <cstdint>
#include <vector>

namespace gpurt {

class GlIntegrator {
  public:
    virtual ~GlIntegrator() = default;
    // The sample the kernels that draw random numbers take: s of n, --seed.
    virtual void setSample(uint32_t s, uint32_t n, uint32_t seed) = 0;
    // One sample of every pixel from the primary rays of the pipeline's current sample, with up
    // to maxBounces bounces; with `aovs`, the primary AOVs are read into it on the way. The rays
    // traced count in `stats`.
    virtual void sample(const std::vector<Light>& lights, int maxBounces, RenderOutput* aovs,
                        RenderStats& stats) = 0;
    // The sample's colour of each pixel (RGBA32F, w unused).
    virtual const GPUFloatArray& colour() const = 0;
    // Adds the sample's colour to the pipeline's sums.
    virtual void accumulate() = 0;
    virtual std::vector<GPUKernel*> kernels() = 0;
};

}  // namespace gpurt
