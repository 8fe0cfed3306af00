#include "scene/SmoothNormals.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

namespace gpurt {

namespace {

struct PositionHash {
    size_t operator()(const glm::vec3& p) const {
        size_t h = 0;
        for (int i = 0; i < 3; ++i) {
            uint32_t bits;
            const float c = p[i] == 0.0f ? 0.0f : p[i];  // -0 and +0 are one position
            std::memcpy(&bits, &c, 4);
            h = h * 0x9e3779b97f4a7c15ull + bits;
        }
        return h;
    }
};

bool usable(const TriangleNormals& n) {
    for (const glm::vec3& v : {n.n0, n.n1, n.n2})
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z) || v == glm::vec3(0.0f)) return false;
    return true;
}

}  // namespace

void smoothNormals(Scene& scene, float creaseDegrees) {
    const size_t n = scene.triangles.size();
    if (creaseDegrees < 0.0f) {
        scene.normals.clear();
        return;
    }
    scene.normals.resize(n);
    std::vector<bool> fromFile(n);
    bool anyMissing = false;
    for (size_t t = 0; t < n; ++t) {
        fromFile[t] = usable(scene.normals[t]);
        if (!fromFile[t]) {
            scene.normals[t] = TriangleNormals{};
            anyMissing = true;
        }
    }
    if (!anyMissing) return;

    // Unit face normals and corner angles in double (zero for degenerate triangles).
    std::vector<glm::dvec3> face(n);
    std::vector<glm::dvec3> angle(n);
    for (size_t t = 0; t < n; ++t) {
        const Triangle& tri = scene.triangles[t];
        const glm::dvec3 p[3] = {tri.v0, tri.v1, tri.v2};
        const glm::dvec3 c = glm::cross(p[1] - p[0], p[2] - p[0]);
        const double len = glm::length(c);
        if (!(len > 0.0) || !std::isfinite(len)) continue;
        face[t] = c / len;
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
            const double la = glm::length(a), lb = glm::length(b);
            angle[t][k] = la > 0.0 && lb > 0.0 ? std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0, 1.0)) : 0.0;
        }
    }
    // The corners at each position.
    std::unordered_map<glm::vec3, std::vector<uint32_t>, PositionHash> corners;
    corners.reserve(n * 3 / 2);
    for (size_t t = 0; t < n; ++t) {
        if (face[t] == glm::dvec3(0.0)) continue;
        const Triangle& tri = scene.triangles[t];
        const glm::vec3 p[3] = {tri.v0, tri.v1, tri.v2};
        for (uint32_t k = 0; k < 3; ++k) corners[p[k]].push_back(uint32_t(3 * t + k));
    }
    const double cosCrease = std::cos(double(creaseDegrees) * M_PI / 180.0);
    for (size_t t = 0; t < n; ++t) {
        if (fromFile[t] || face[t] == glm::dvec3(0.0)) continue;  // degenerate: no normals, faceted
        const Triangle& tri = scene.triangles[t];
        const glm::vec3 p[3] = {tri.v0, tri.v1, tri.v2};
        glm::vec3 out[3];
        for (int k = 0; k < 3; ++k) {
            glm::dvec3 sum(0.0);
            for (uint32_t corner : corners[p[k]]) {
                const size_t other = corner / 3;
                // Faces within the crease angle, either winding (meshes are not always consistent).
                const double c = glm::dot(face[other], face[t]);
                if (std::fabs(c) < cosCrease && other != t) continue;
                sum += (c < 0.0 ? -1.0 : 1.0) * angle[other][corner % 3] * face[other];
            }
            const double len = glm::length(sum);
            out[k] = glm::vec3(len > 0.0 ? sum / len : face[t]);
        }
        scene.normals[t] = {out[0], out[1], out[2]};
    }
}

}  // namespace gpurt
