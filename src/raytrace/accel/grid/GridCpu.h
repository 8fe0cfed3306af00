// The uniform grid as the cpu backend's accelerator: the per-ray loop that the grid's kernels
// (glsl/accel/grid/) run as passes, with the same float operations (glsl/common/raymath.h).
#pragma once

#include <memory>
#include <vector>

#include "raytrace/materials/AlphaCoverage.h"
#include "raytrace/accel/CpuAccelerator.h"
#include "raytrace/accel/grid/UniformGrid.h"
#include "scene/Scene.h"

namespace gpurt {

class GridCpu final : public CpuAccelerator {
  public:
    // Keeps a reference to the grid: it must outlive the accelerator.
    GridCpu(const Scene& scene, const UniformGrid& grid);

    TraceHit closestHit(glm::vec3 o, glm::vec3 d, float tLimit, uint32_t coverageKey) const override {
        return traceRay<false>(o, d, tLimit, coverageKey);
    }
    TraceHit anyHit(glm::vec3 o, glm::vec3 d, float tLimit, uint32_t coverageKey) const override {
        return traceRay<true>(o, d, tLimit, coverageKey);
    }

    struct PreparedTriangle {
        glm::vec3 v0, v1, v2;  // the vertices, as the GL side's cell lists hold them
    };

  private:
    template <bool AnyHit>
    TraceHit traceRay(glm::vec3 o, glm::vec3 d, float tLimit, uint32_t coverageKey) const;

    const UniformGrid& grid_;
    std::vector<PreparedTriangle> triangles_;
    float hitTolerance_;
    int maxSteps_;
    std::unique_ptr<const AlphaCoverage> coverage_;  // null: the scene has no alpha
};

}  // namespace gpurt
