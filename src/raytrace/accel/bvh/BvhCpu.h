// The BVH as the cpu backend's accelerator: the traversal of glsl/common/bvh.h over the same
// texels the kernel reads (SceneTextureLayout's bvhNodeTexels and bvhTriangleTexels).
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "raytrace/materials/AlphaCoverage.h"
#include "raytrace/accel/CpuAccelerator.h"
#include "raytrace/accel/bvh/Bvh.h"
#include "scene/Scene.h"

namespace gpurt {

class BvhCpu final : public CpuAccelerator {
  public:
    BvhCpu(const Scene& scene, const Bvh& bvh);

    TraceHit closestHit(glm::vec3 o, glm::vec3 d, float tLimit, uint32_t coverageKey) const override {
        return trace<false>(o, d, tLimit, coverageKey);
    }
    TraceHit anyHit(glm::vec3 o, glm::vec3 d, float tLimit, uint32_t coverageKey) const override {
        return trace<true>(o, d, tLimit, coverageKey);
    }

  private:
    template <bool AnyHit>  // one copy of the traversal each, with anyHit a constant
    TraceHit trace(glm::vec3 o, glm::vec3 d, float tLimit, uint32_t coverageKey) const;

    std::unique_ptr<const AlphaCoverage> coverage_;  // null: the scene has no alpha

    std::vector<glm::uvec4> nodes_;
    std::vector<glm::vec4> triangles_;
    glm::vec3 boxMin_, boxStep_;  // Bvh::quantisation
    int maxSteps_;
};

}  // namespace gpurt
