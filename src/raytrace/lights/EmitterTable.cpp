#include "raytrace/lights/EmitterTable.h"

#include <algorithm>
#include <cmath>

namespace gpurt {

size_t EmitterTable::pick(float u) const {
    const auto at = std::upper_bound(cdf.begin(), cdf.end(), u);
    return std::min(size_t(at - cdf.begin()), cdf.size() - 1);
}

EmitterTable buildEmitterTable(const Scene& scene) {
    EmitterTable table;
    std::vector<double> areas;
    double total = 0.0;
    for (size_t t = 0; t < scene.triangles.size(); ++t) {
        const Material& m = scene.materials[scene.materialIds[t]];
        if (!m.emits() || m.emissiveTexture >= 0) continue;  // textured emission: found by rays only
        const Triangle& tri = scene.triangles[t];
        const glm::dvec3 c = glm::cross(glm::dvec3(tri.v1) - glm::dvec3(tri.v0), glm::dvec3(tri.v2) - glm::dvec3(tri.v0));
        const double area = 0.5 * glm::length(c);
        if (!(area > 0.0) || !std::isfinite(area)) continue;  // no point of it can be sampled
        table.triangles.push_back(uint32_t(t));
        areas.push_back(area);
        total += area;
    }
    double sum = 0.0;
    for (double a : areas) {
        sum += a;
        table.cdf.push_back(float(sum / total));
    }
    if (!table.cdf.empty()) table.cdf.back() = 1.0f;
    table.totalArea = float(total);
    return table;
}

}  // namespace gpurt
