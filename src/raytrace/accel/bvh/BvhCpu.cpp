#include "raytrace/accel/bvh/BvhCpu.h"

#include <cstring>
#include <limits>

#include "raytrace/common/RayMath.h"
#include "raytrace/textures/SceneTextureLayout.h"
#include "raytrace/accel/bvh/BvhTexels.h"

namespace gpurt {

namespace {

using namespace glm;
using namespace raymath;

struct BvhTexels {
    const uvec4* nodes;
    const vec4* triangles;
    vec3 boxMin, boxStep;
    const AlphaCoverage* coverage;
    uint32_t coverageKey;
};

#define GPURT_BVH_PARAMS const BvhTexels &bvh,
#define GPURT_BVH_ARGS bvh,
#define GPURT_BVH_NODE(i) bvh.nodes[i]
#define GPURT_BVH_TRI(i) bvh.triangles[i]
#define GPURT_BVH_BOX_MIN bvh.boxMin
#define GPURT_BVH_BOX_STEP bvh.boxStep
#define GPURT_BVH_COVERED(id, flags, u, v, d, e1, e2, anyHit) \
    ((flags) == 0.0f || hitCovered(bvh.coverage, id, u, v, bvh.coverageKey, d, e1, e2, anyHit))
#include "../../../../glsl/common/bvh.h"

std::vector<vec4> asVectors(const TextureTexels& texels) {
    std::vector<vec4> v(texels.floats.size() / 4);
    std::memcpy(v.data(), texels.floats.data(), v.size() * sizeof(vec4));
    return v;
}

std::vector<uvec4> asUintVectors(const TextureTexels& texels) {
    std::vector<uvec4> v(texels.uints.size() / 4);
    std::memcpy(v.data(), texels.uints.data(), v.size() * sizeof(uvec4));
    return v;
}

}  // namespace

BvhCpu::BvhCpu(const Scene& scene, const Bvh& bvh)
    : coverage_(AlphaCoverage::of(scene)),
      nodes_(asUintVectors(bvhNodeTexels(bvh))),
      triangles_(asVectors(bvhTriangleTexels(scene, bvh))),
      maxSteps_(bvh.maxNodeSteps()) {
    bvh.quantisation(boxMin_, boxStep_);
}

template <bool AnyHit>
TraceHit BvhCpu::trace(glm::vec3 o, glm::vec3 d, float tLimit, uint32_t coverageKey) const {
    const BvhTexels texels{nodes_.data(), triangles_.data(), boxMin_, boxStep_, coverage_.get(), coverageKey};
    TraceHit hit{};
    hit.prim = bvhTrace(texels, o, d, tLimit, AnyHit, maxSteps_, hit.t, hit.u, hit.v, hit.steps, hit.tests, hit.state);
    if (hit.prim < 0) hit.t = std::numeric_limits<float>::infinity();
    return hit;
}

template TraceHit BvhCpu::trace<false>(glm::vec3, glm::vec3, float, uint32_t) const;
template TraceHit BvhCpu::trace<true>(glm::vec3, glm::vec3, float, uint32_t) const;

}  // namespace gpurt
