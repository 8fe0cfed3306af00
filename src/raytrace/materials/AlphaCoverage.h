// Alpha coverage and back-face culling on the cpu backend: whether a candidate hit of a traversal
// counts (glTF alphaMode MASK / BLEND, MTL d / map_d; glTF doubleSided false), as
// glsl/scene/alpha.glsl decides it in the accelerators' kernels, with the decisions of
// glsl/common/alpha.h and raymath.h backFacing shared word for word.
#pragma once

#include <cstdint>
#include <memory>

#include "scene/Scene.h"

namespace gpurt {

// Whether a triangle of the scene has a material with alpha (a library's unused materials do not
// count): only then do the traversals test coverage (SCENE_ALPHA in the kernels).
bool sceneUsesAlpha(const Scene& scene);
// Whether a triangle of the scene has a material that culls its back faces
// (Material::cullsBackFaces): only then do the traversals test facing (SCENE_CULL_BACK).
bool sceneCullsBackFaces(const Scene& scene);
// Whether a triangle of the scene has a material that shadow rays pass (Material::castsNoShadow:
// KHR_materials_unlit): only then do the traversals ask (SCENE_SHADOWLESS).
bool sceneHasShadowless(const Scene& scene);

class AlphaCoverage {
  public:
    // Null when no material in use has alpha, culls its back faces or casts no shadow (every hit
    // counts). Keeps a
    // reference to the scene: it must outlive the coverage.
    static std::unique_ptr<const AlphaCoverage> of(const Scene& scene);

    explicit AlphaCoverage(const Scene& scene) : scene_(scene) {}

    // Whether triangle `prim` (edges e1, e2) covers the ray of coverage key `key`
    // (common/alpha.h coverageKey) and direction d at barycentrics (u, v), a shadow ray (an
    // any-hit traversal's: it passes a material that casts no shadow) or not.
    bool covers(int prim, float u, float v, uint32_t key, glm::vec3 d, glm::vec3 e1, glm::vec3 e2, bool shadowRay) const;

  private:
    const Scene& scene_;
};

// Whether a hit counts: always without coverage.
inline bool hitCovered(const AlphaCoverage* coverage, int prim, float u, float v, uint32_t key, glm::vec3 d,
                       glm::vec3 e1, glm::vec3 e2, bool shadowRay) {
    return coverage == nullptr || coverage->covers(prim, u, v, key, d, e1, e2, shadowRay);
}

}  // namespace gpurt
