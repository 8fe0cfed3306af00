// Camera set-up and primary rays, exactly as CONTRACT.md writes them.
#include "raytrace/camera/Camera.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "image/InputError.h"
#include "raytrace/common/RayMath.h"
#include "raytrace/common/Vec3.h"

namespace gpurt {
namespace {

std::string format(glm::vec3 v) {
    std::ostringstream s;
    s << v.x << "," << v.y << "," << v.z;
    return s.str();
}

// The contract's normalize, a / sqrt(dot(a, a)). Where dot(a, a) leaves the float range (|a|
// beyond about 1e19 or below 1e-19), a is first scaled by a power of two, which keeps its
// direction: a camera far from its target, or very close to it, still gets the frame the
// contract means. Elsewhere the result is the contract's formula, bit for bit.
glm::vec3 unitVector(glm::vec3 a) {
    const float length2 = glm::dot(a, a);
    if (length2 >= FLT_MIN && length2 <= FLT_MAX) return raymath::contractNormalize(a);
    int exponent = 0;
    std::frexp(std::max(std::fabs(a.x), std::max(std::fabs(a.y), std::fabs(a.z))), &exponent);
    return raymath::contractNormalize(glm::vec3(
        std::ldexp(a.x, -exponent), std::ldexp(a.y, -exponent), std::ldexp(a.z, -exponent)));
}

// tan(fovy * pi / 360) in double, rounded to float (the contract's t).
float tanHalfFovy(float fovy) {
    return static_cast<float>(std::tan(double(fovy) * std::numbers::pi / 360.0));
}

std::string number(float v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// The lens of spec in the basis (its forward and field of view set).
void setLens(CameraBasis& c, const CameraSpec& spec) {
    if (!(std::isfinite(spec.lensRadius) && spec.lensRadius >= 0.0f))
        throw InputError("--lens-radius: must be a finite number >= 0, got " + number(spec.lensRadius));
    if (!(std::isfinite(spec.fstop) && spec.fstop >= 0.0f))
        throw InputError("--fstop: must be a finite number > 0, got " + number(spec.fstop));
    if (!(std::isfinite(spec.focusDistance) && spec.focusDistance >= 0.0f))
        throw InputError("--focus-distance: must be a finite number > 0, got " + number(spec.focusDistance));
    if (spec.blades < 0 || spec.blades == 1 || spec.blades == 2 || spec.blades > 64)
        throw InputError("--blades: must be 0 (a disc) or 3 to 64, got " + std::to_string(spec.blades));
    if (!std::isfinite(spec.bladeRotation))
        throw InputError("--blade-rotation: must be a finite number of degrees");
    if (!spec.hasLens()) return;
    double radius = spec.lensRadius;
    if (spec.fstop > 0.0f) {
        // f = 0.018 / tan(fov / 2), fov across the larger side; in double, then rounded.
        const double tanHalf = std::tan(double(spec.fovy) * std::numbers::pi / 360.0) * std::max(1.0, double(c.aspect));
        radius = 0.018 / tanHalf / (2.0 * double(spec.fstop)) * double(spec.metre);
    }
    c.lensRadius = static_cast<float>(radius);
    const glm::vec3 view = spec.target - spec.eye;
    c.focusDistance = spec.focusDistance > 0.0f ? spec.focusDistance : std::sqrt(glm::dot(view, view));
    if (!(c.focusDistance > 0.0f && std::isfinite(c.focusDistance)))
        throw InputError("--focus-distance: the distance from --eye to --target is not a usable focus distance");
    c.blades = spec.blades;
    c.bladeRotation = static_cast<float>(double(spec.bladeRotation) * std::numbers::pi / 180.0);
}

}  // namespace

CameraBasis makeCamera(const CameraSpec& spec, int width, int height) {
    if (width < 1 || height < 1)
        throw InputError("--size: width and height must be at least 1, got " +
                         std::to_string(width) + "x" + std::to_string(height));
    if (!isFinite(spec.eye)) throw InputError("--eye: not a finite point: " + format(spec.eye));
    if (!isFinite(spec.target))
        throw InputError("--target: not a finite point: " + format(spec.target));
    if (!isFinite(spec.up)) throw InputError("--up: not a finite vector: " + format(spec.up));
    if (!(spec.fovy > 0.0f && spec.fovy < 180.0f))
        throw InputError("--fovy: must be between 0 and 180 degrees (exclusive), got " +
                         std::to_string(spec.fovy));

    CameraBasis c;
    c.eye = spec.eye;
    const glm::vec3 view = spec.target - spec.eye;
    if (view == glm::vec3(0.0f))
        throw InputError("--target: must differ from --eye (both are " + format(spec.eye) + ")");
    if (!isFinite(view))
        throw InputError("--target: too far from --eye (" + format(spec.target) + " from " +
                         format(spec.eye) + " overflows float)");
    c.forward = unitVector(view);
    const glm::vec3 side = glm::cross(c.forward, spec.up);
    if (side == glm::vec3(0.0f))
        throw InputError("--up: " + format(spec.up) +
                         " is parallel to the viewing direction (or zero)");
    c.right = unitVector(side);
    c.upOrtho = glm::cross(c.right, c.forward);
    if (!isFinite(c.forward) || !isFinite(c.right) || !isFinite(c.upOrtho))
        throw InputError("--eye: eye, target and up give no valid camera frame");
    c.tanHalf = tanHalfFovy(spec.fovy);
    c.aspect = static_cast<float>(width) / static_cast<float>(height);
    c.width = width;
    c.height = height;
    setLens(c, spec);
    return c;
}

CameraSpec defaultCamera(const Bounds& bounds, int width, int height, float fovy) {
    glm::vec3 center(0.0f), half(1.0f);
    if (!bounds.empty()) {
        center = bounds.center();
        half = bounds.halfExtent();
    }
    CameraSpec spec;  // up = 0,1,0
    spec.fovy = fovy;
    const float t = tanHalfFovy(spec.fovy);
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    float dist = 1.1f * std::max(half.y / t, half.x / (t * aspect)) + half.z;
    // A single point (or a speck too small for float to step back from, fuzz_gltf found one of
    // 1e-39) has no size to fit; stand back one unit rather than at the point itself, or more where
    // the point is so far out that one unit is below float's step there.
    if (!(dist > 0.0f) || center.z + dist == center.z)
        dist = std::max({1.0f, 1e-3f * std::abs(center.x), 1e-3f * std::abs(center.y), 1e-3f * std::abs(center.z)});
    spec.eye = center + glm::vec3(0.0f, 0.0f, dist);
    spec.target = center;
    return spec;
}

glm::vec3 primaryDirection(const CameraBasis& c, int i, int j) {
    return raymath::cameraRayDirection(c.forward, c.right, c.upOrtho, c.tanHalf, c.aspect,
                                       static_cast<float>(i), static_cast<float>(j),
                                       static_cast<float>(c.width), static_cast<float>(c.height));
}

glm::vec3 sampleDirection(const CameraBasis& c, int i, int j, uint32_t s, uint32_t n, uint32_t seed,
                          SamplerKind sampler) {
    const glm::vec2 offset = raymath::pixelSampleOffset(uint32_t(sampler), uint32_t(i), uint32_t(j), s, n, seed);
    return raymath::cameraRayThrough(c.forward, c.right, c.upOrtho, c.tanHalf, c.aspect,
                                     float(i) + offset.x, float(j) + offset.y, float(c.width),
                                     float(c.height));
}

CameraRay sampleRay(const CameraBasis& c, int i, int j, uint32_t s, uint32_t n, uint32_t seed, SamplerKind sampler) {
    CameraRay ray{c.eye, sampleDirection(c, i, j, s, n, seed, sampler)};
    if (!(c.lensRadius > 0.0f)) return ray;
    const glm::vec2 u = raymath::sample2D(uint32_t(sampler), uint32_t(i), uint32_t(j), s, n, seed, GPURT_DIM_LENS);
    raymath::thinLensRay(c.eye, c.forward, c.right, c.upOrtho, ray.direction, c.lensRadius, c.focusDistance,
                         raymath::aperturePoint(u, c.blades, c.bladeRotation), ray.origin, ray.direction);
    return ray;
}

}  // namespace gpurt
