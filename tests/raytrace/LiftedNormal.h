// The normal Cycles' ensure_valid_reflection makes of a normal whose mirror falls below the
// surface, found by bisection: independent of glsl/common/shading.h validReflectionNormal (which
// takes the half vector of the view and a lifted mirror), for its tests.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace gpurt::test {

// The normal n (unit, facing as ng) turned in the plane of n and ng towards ng by the least
// angle for which the mirror of wo (unit, in front of ng) about it rises t = min(0.9 ng.wo, 0.01)
// above the surface; n itself where its mirror already does. The mirror's height over the normals
// cos(phi) ng + sin(phi) x (x: n's part across ng) is ng.wo cos(2 phi) + x.wo sin(2 phi), a
// cosine in 2 phi, so between phi = 0 (the height ng.wo >= t) and n's angle (below t) it falls
// through t once: bisection finds that phi.
inline glm::dvec3 liftedNormalByBisection(glm::dvec3 n, glm::dvec3 ng, glm::dvec3 wo) {
    const double t = std::min(0.9 * glm::dot(ng, wo), 0.01);
    const auto height = [&](glm::dvec3 m) { return glm::dot(2.0 * glm::dot(m, wo) * m - wo, ng); };
    if (height(n) >= t) return n;
    const glm::dvec3 x = glm::normalize(n - ng * glm::dot(n, ng));
    const auto at = [&](double phi) { return std::cos(phi) * ng + std::sin(phi) * x; };
    double lo = 0.0, hi = std::atan2(glm::dot(n, x), glm::dot(n, ng));
    for (int i = 0; i < 100; ++i) {
        const double mid = 0.5 * (lo + hi);
        (height(at(mid)) >= t ? lo : hi) = mid;
    }
    return at(lo);
}

}  // namespace gpurt::test
