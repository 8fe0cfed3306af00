// The integrator seam on the cpu backend: an integrator is one sample of one pixel, a function
// over the tracer's access to the scene (CpuTracer: the accelerator, the triangles, material
// records, shadow rays, emitters); CpuTracer::render runs the pixels, their samples and sums.
// Each has a gl twin (integrators/*/…Gl) that takes the same decisions from the same numbers.
#pragma once

#include "raytrace/CpuTracer.h"

#include <cstddef>
#include <cstdint>

namespace gpurt {

// Sample `index` of `count` of pixel (i, j) of the image (its random numbers: common/sampling.h).
struct PixelSample {
    int i, j;
    uint32_t index, count, seed;

    // The coverage key of its rays (common/alpha.h): the accelerators' alpha coverage.
    uint32_t coverageKey() const { return raymath::coverageKey(uint32_t(i), uint32_t(j), index, seed); }
};

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

}  // namespace gpurt
