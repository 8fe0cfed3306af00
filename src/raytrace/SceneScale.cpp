// Power-of-two rescaling of scenes for rendering (SceneScale.h).
#include "raytrace/SceneScale.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace gpurt {
namespace {

// Scenes within these bounds render as they are: with coordinates below 2^28 the quartic normal
// length stays below 2^126, with edges from 2^-28 on it stays above 2^-126 (llvmpipe flushes
// denormals to zero).
constexpr double kLargestCoordinate = 0x1p28;
constexpr double kShortestEdge = 0x1p-28;

// Largest coordinate difference along one axis (double: float could overflow).
double edgeLength(glm::vec3 a, glm::vec3 b) {
    const glm::dvec3 e = glm::abs(glm::dvec3(b) - glm::dvec3(a));
    return std::max(e.x, std::max(e.y, e.z));
}

}  // namespace

int renderScaleExponent(const Scene& scene) {
    double largest = 0.0, shortest = INFINITY;
    for (const Triangle& t : scene.triangles) {
        for (const glm::vec3& v : {t.v0, t.v1, t.v2})
            largest = std::max(
                {largest, double(std::fabs(v.x)), double(std::fabs(v.y)), double(std::fabs(v.z))});
        for (double e : {edgeLength(t.v0, t.v1), edgeLength(t.v1, t.v2), edgeLength(t.v2, t.v0)})
            if (e > 0.0) shortest = std::min(shortest, e);
    }
    if (!(largest > 0.0) || !std::isfinite(largest)) return 0;
    if (!std::isfinite(shortest)) shortest = largest;  // only zero-area triangles: no edge
    if (largest <= kLargestCoordinate && shortest >= kShortestEdge) return 0;
    // Centre both ends: 2 * largest (the longest possible edge) and the shortest edge end up
    // equally far from 1. Where they are too far apart for both to fit, overflow is the worse
    // failure (no camera, no hits anywhere): the largest coordinate is brought within range, and
    // the shortest edges may then be too short to be hit.
    const int centred = int(std::lround((std::log2(2.0 * largest) + std::log2(shortest)) / 2.0));
    const int fitLargest = int(std::ceil(std::log2(largest / kLargestCoordinate)));
    return std::max(centred, fitLargest);
}

glm::vec3 rescalePoint(glm::vec3 p, int exponent) {
    return {std::ldexp(p.x, -exponent), std::ldexp(p.y, -exponent), std::ldexp(p.z, -exponent)};
}

void rescaleScene(Scene& scene, int exponent) {
    if (exponent == 0) return;
    for (Triangle& t : scene.triangles) {
        t.v0 = rescalePoint(t.v0, exponent);
        t.v1 = rescalePoint(t.v1, exponent);
        t.v2 = rescalePoint(t.v2, exponent);
    }
    for (PointLight& light : scene.lights) {
        light.position = rescalePoint(light.position, exponent);
        // A light far brighter than its distance warrants saturates rather than overflows.
        light.intensity = std::min(std::ldexp(light.intensity, -2 * exponent), FLT_MAX);
    }
    if (scene.camera) {
        scene.camera->eye = rescalePoint(scene.camera->eye, exponent);
        scene.camera->target = rescalePoint(scene.camera->target, exponent);
    }
}

void rescaleGrid(UniformGrid& grid, int exponent) {
    grid.min = rescalePoint(grid.min, exponent);
    grid.max = rescalePoint(grid.max, exponent);
    grid.cellSize = rescalePoint(grid.cellSize, exponent);
}

void unscaleDepth(std::vector<float>& depth, int exponent) {
    if (exponent == 0) return;
    // A hit farther away than the largest float (in a scene that spans nearly the float range)
    // keeps the largest float as its depth: +inf means a miss.
    for (float& t : depth)
        if (std::isfinite(t)) t = std::min(std::ldexp(t, exponent), FLT_MAX);
}

}  // namespace gpurt
