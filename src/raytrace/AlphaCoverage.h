// Alpha coverage on the cpu backend: whether a candidate hit of a traversal counts (glTF alphaMode
// MASK / BLEND, MTL d / map_d), as glsl/scene/alpha.glsl decides it in the accelerators' kernels,
// with the decision of glsl/common/alpha.h shared word for word.
#pragma once

#include <cstdint>
#include <memory>

#include "scene/Scene.h"

namespace gpurt {

// Whether a triangle of the scene has a material with alpha (a library's unused materials do not
// count): only then do the traversals test coverage (SCENE_ALPHA in the kernels).
bool sceneUsesAlpha(const Scene& scene);

class AlphaCoverage {
  public:
    // Null when no material of the scene has alpha (every hit counts). Keeps a reference to the
    // scene: it must outlive the coverage.
    static std::unique_ptr<const AlphaCoverage> of(const Scene& scene);

    explicit AlphaCoverage(const Scene& scene) : scene_(scene) {}

    // Whether triangle `prim` covers the ray of coverage key `key` (common/alpha.h coverageKey)
    // at barycentrics (u, v).
    bool covers(int prim, float u, float v, uint32_t key) const;

  private:
    const Scene& scene_;
};

// Whether a hit counts: always without coverage.
inline bool hitCovered(const AlphaCoverage* coverage, int prim, float u, float v, uint32_t key) {
    return coverage == nullptr || coverage->covers(prim, u, v, key);
}

}  // namespace gpurt
