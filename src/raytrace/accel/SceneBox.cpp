#include "raytrace/accel/SceneBox.h"

#include <algorithm>
#include <cmath>

#include "image/InputError.h"

namespace gpurt {

std::pair<glm::vec3, glm::vec3> sceneBox(const Scene& scene) {
    const Bounds bounds = scene.bounds();
    glm::vec3 lo(-1.0f), hi(1.0f);
    if (!bounds.empty()) {
        for (int a = 0; a < 3; ++a)
            if (!std::isfinite(bounds.min[a]) || !std::isfinite(bounds.max[a]))
                throw InputError("scene: vertex coordinates are not finite");
        const glm::vec3 extent = bounds.max - bounds.min;
        const float largest = std::max(extent.x, std::max(extent.y, extent.z));
        float pad = 1e-4f * largest;
        if (!(pad > 0.0f)) {
            // A point: pad by a fixed amount, large enough to survive the coordinates' rounding.
            const glm::vec3 magnitude = glm::max(glm::abs(bounds.min), glm::abs(bounds.max));
            pad =
                std::max(1e-3f, 1e-4f * std::max(magnitude.x, std::max(magnitude.y, magnitude.z)));
        }
        lo = bounds.min - glm::vec3(pad);
        hi = bounds.max + glm::vec3(pad);
        for (int a = 0; a < 3; ++a) {
            // A flat axis far from the origin can swallow the pad in rounding.
            if (!(hi[a] > lo[a])) {
                lo[a] = std::nextafter(lo[a], -INFINITY);
                hi[a] = std::nextafter(hi[a], INFINITY);
            }
        }
    }
    return {lo, hi};
}

float sceneRayOffset(glm::vec3 boxMin, glm::vec3 boxMax) {
    const glm::vec3 extent = boxMax - boxMin;
    return 1e-4f * std::max(extent.x, std::max(extent.y, extent.z));
}

}  // namespace gpurt
