// The scene's emitting triangles (area lights) as one light sampled uniformly by area: the
// triangles whose material emits and whose area is not zero, with the cumulative distribution of
// their areas. Both backends sample it the same way (glsl/common/shading.h; the GL side reads it
// as the emitter table of SceneTextures).
#pragma once

#include <cstdint>
#include <vector>

#include "scene/Scene.h"

namespace gpurt {

struct EmitterTable {
    std::vector<uint32_t> triangles;  // ids of the emitting triangles, ascending
    // cdf[k]: the share of the total area of triangles 0..k (the last is exactly 1).
    std::vector<float> cdf;
    float totalArea = 0.0f;

    bool empty() const { return triangles.empty(); }
    // The entry k with cdf[k - 1] <= u < cdf[k] (cdf[-1] = 0) for u in [0, 1): the first k with
    // u < cdf[k], as the GLSL search finds it.
    size_t pick(float u) const;
    float lower(size_t k) const { return k == 0 ? 0.0f : cdf[k - 1]; }
};

EmitterTable buildEmitterTable(const Scene& scene);

}  // namespace gpurt
