// The CPU backend: the same accelerator, traversal and shading as the GL kernels, evaluated ray by
// ray in C++ with the shared code of glsl/common (what a sample asks: integrators/CpuScene). It is the reference the GL backend is tested
// against and the fallback with --backend cpu.
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "raytrace/accel/grid/UniformGrid.h"
#include "raytrace/camera/Camera.h"
#include "raytrace/integrators/CpuScene.h"

namespace gpurt {

// Adaptive sampling's convergence pass over a width x height image (glsl/integrators/converge.frag
// on the cpu): each active pixel (active[i] != 0) stays active while one of its 3 x 3
// neighbourhood's errors (common/adaptive.h, from the sums of all and of the odd samples and the
// counts) is at or above the threshold; on `threads` threads. Returns the pixels still active.
uint64_t convergencePass(int width, int height, const std::vector<glm::vec3>& sums,
                         const std::vector<glm::vec3>& oddSums, const std::vector<float>& counts, float threshold,
                         int threads, std::vector<uint8_t>& active);

// The cpu backend's render loop over a CpuScene: pixels, samples, sums, AOVs, adaptive rounds.
class CpuTracer : public CpuScene {
  public:
    using CpuScene::CpuScene;
    // Over the uniform grid; keeps references to both: they must outlive the tracer.
    CpuTracer(const Scene& scene, const UniformGrid& grid);

    // Traces every ray of `rays` (elements with tLimit < 0 are skipped) on `threads` threads
    // (0: all cores), closest or any hit, into hits[i] = (t, u, v, triangle | -1); returns the
    // rays traced (gpurt bench).
    uint64_t traceStream(const RayStream& rays, bool anyHit, int threads, std::vector<glm::vec4>& hits) const;

    // Renders the camera's image (its width x height) under settings.integrator with the AOVs, on
    // settings.threads threads (0: all cores), rows handed out dynamically.
    RenderOutput render(const CameraBasis& camera, const RenderSettings& settings) const;
};

}  // namespace gpurt
