// The integrator seam on the cpu backend: an integrator is one sample of one pixel, a function
// over the scene as a sample sees it (CpuScene: the accelerator, the triangles, material
// records, shadow rays, emitters); CpuTracer::render runs the pixels, their samples and sums.
// Each has a gl twin (integrators/*/…Gl) that takes the same decisions from the same numbers.
#pragma once

#include "raytrace/lights/PunctualLights.h"
#include "raytrace/integrators/CpuScene.h"

#include <cstddef>
#include <cstdint>

namespace gpurt {

// Where a sample writes its pixel's primary AOVs: element `pixel` of `out` (nullptr: nowhere).
struct PixelAovs {
    RenderOutput* out = nullptr;
    size_t pixel = 0;

    void write(float depth, float prim, glm::vec3 normal) const {
        out->depth[pixel] = depth;
        out->prim[pixel] = prim;
        out->normal[pixel] = normal;
    }
};

// The denoiser's features of a sample (common/path.h featuresOpenAfter).
struct SampleFeatures {
    glm::vec3 albedo{0.0f}, normal{0.0f};
};

}  // namespace gpurt
