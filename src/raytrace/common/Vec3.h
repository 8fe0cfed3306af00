// Two small vector helpers that the camera, the accelerators, the packed format and the scene's
// rescaling share.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace gpurt {

// Whether every component is finite.
inline bool isFinite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// p * 2^-exponent, component by component (exact unless it over- or underflows; SceneScale.h).
inline glm::vec3 rescalePoint(glm::vec3 p, int exponent) {
    return {std::ldexp(p.x, -exponent), std::ldexp(p.y, -exponent), std::ldexp(p.z, -exponent)};
}

}  // namespace gpurt
