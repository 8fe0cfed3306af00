// Power-of-two rescaling of scenes for rendering (SceneScale.h).
#include "raytrace/scene/SceneScale.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace gpurt {
namespace {

// Scenes whose largest coordinate is within these bounds render as they are. Above 2^28 the
// cubic numerator of the triangle test's t can overflow for rays from a camera a few scene sizes
// away; below 2^-28 the quadratic determinant of typical triangles approaches the denormals,
// which llvmpipe flushes to zero. (Tiny triangles in a scene of ordinary size are not a reason
// to rescale: it would push the rest of the scene, lights included, towards overflow; their
// normals are computed safely anyway, shading.h facingNormal.)
constexpr double kLargestCoordinate = 0x1p28;
constexpr double kSmallestLargestCoordinate = 0x1p-28;

}  // namespace

int renderScaleExponent(const Scene& scene) {
    double largest = 0.0;
    for (const Triangle& t : scene.triangles)
        for (const glm::vec3& v : {t.v0, t.v1, t.v2})
            largest = std::max(
                {largest, double(std::fabs(v.x)), double(std::fabs(v.y)), double(std::fabs(v.z))});
    if (!(largest > 0.0) || !std::isfinite(largest)) return 0;
    if (largest >= kSmallestLargestCoordinate && largest <= kLargestCoordinate) return 0;
    int exponent = 0;
    std::frexp(largest, &exponent);  // largest = m 2^exponent, 0.5 <= m < 1
    return exponent - 1;             // the largest coordinate becomes m 2 in [1, 2)
}

void rescaleCamera(CameraSpec& camera, int exponent) {
    camera.eye = rescalePoint(camera.eye, exponent);
    camera.target = rescalePoint(camera.target, exponent);
    camera.lensRadius = std::ldexp(camera.lensRadius, -exponent);
    camera.focusDistance = std::ldexp(camera.focusDistance, -exponent);
    camera.metre = std::ldexp(camera.metre, -exponent);
}

void rescaleScene(Scene& scene, int exponent) {
    if (exponent == 0) return;
    for (Triangle& t : scene.triangles) {
        t.v0 = rescalePoint(t.v0, exponent);
        t.v1 = rescalePoint(t.v1, exponent);
        t.v2 = rescalePoint(t.v2, exponent);
    }
    for (Material& m : scene.materials)  // KHR_materials_volume's distance (infinite stays so)
        m.attenuationDistance = std::ldexp(m.attenuationDistance, -exponent);
    for (Light& light : scene.lights) {
        light.position = rescalePoint(light.position, exponent);
        light.range = std::ldexp(light.range, -exponent);
        // A light far brighter than its distance warrants saturates rather than overflows. (A
        // directional light's intensity is the same at every distance.)
        if (light.kind != LightKind::Directional)
            light.intensity = std::min(std::ldexp(light.intensity, -2 * exponent), FLT_MAX);
    }
    if (scene.camera) rescaleCamera(*scene.camera, exponent);
    if (scene.animation)
        for (CameraKey& key : scene.animation->keys) rescaleCamera(key.camera, exponent);
}

void unscaleDepth(std::vector<float>& depth, int exponent) {
    if (exponent == 0) return;
    // A hit farther away than the largest float (in a scene that spans nearly the float range)
    // keeps the largest float as its depth: +inf means a miss.
    for (float& t : depth)
        if (std::isfinite(t)) t = std::min(std::ldexp(t, exponent), FLT_MAX);
}

}  // namespace gpurt
