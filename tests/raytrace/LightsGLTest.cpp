// Punctual lights (CONTRACT.md, "Lights"; glsl/common/shading.h punctualAsPoint) against closed
// forms on both backends and both integrators. A Lambert floor of albedo a, nothing else, a black
// background; each pixel's centre ray (one sample) meets the floor at a point p known from the
// camera convention, so every pixel's light is exact:
// - a directional light of intensity I (gpurt's units: a white surface facing it has radiance I)
//   at angle theta from the normal: a I cos(theta);
// - a spot light of intensity I at height h pointing down, with the specification's cone falloff
//   s = saturate((cos phi - cos outer) / (cos inner - cos outer))^2 at the angle phi off its axis:
//   a I s cos(phi) / r^2 with r = h / cos(phi), and its range window clamp(1 - (r / range)^4, 0, 1).
// Whitted adds the material's ambient term, the same with the light off, which is subtracted.
#include "../common/GLTest.h"
#include "TestScenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

namespace gpurt {
namespace {

using test::addMaterial;
using test::addPolygon;

constexpr float kAlbedo = 0.6f;
constexpr int kSize = 48;

class Lights : public test::GLTest {};

Scene floorScene(const Light& light) {
    Scene scene;
    scene.background = glm::vec3(0.0f);
    constexpr float L = 50.0f;
    addPolygon(scene, {{-L, 0, -L}, {-L, 0, L}, {L, 0, L}, {L, 0, -L}}, addMaterial(scene, glm::vec3(kAlbedo)));
    scene.lights.push_back(light);
    return scene;
}

// The light's radiance at each pixel (less the render with the light off), on both backends and
// both integrators, against expected(p) at the floor point p of the pixel's centre ray.
void expectLight(const Light& light, const std::function<double(glm::vec3)>& expected) {
    const CameraSpec spec{{0.3f, 3.0f, 0.2f}, {0.0f, 0.0f, 0.0f}, {0, 0, -1}, 70.0f};
    Light off = light;
    off.intensity = 0.0f;
    const CameraBasis camera = makeCamera(spec, kSize, kSize);
    double largest = 0.0;
    for (const Integrator integrator : {Integrator::Whitted, Integrator::Path}) {
        const test::Both lit = test::renderBoth(floorScene(light), spec, kSize, kSize, 1, 3, integrator);
        const test::Both dark = test::renderBoth(floorScene(off), spec, kSize, kSize, 1, 3, integrator);
        for (const auto& [on, ambient] : {std::pair{&lit.gl, &dark.gl}, std::pair{&lit.cpu, &dark.cpu}}) {
            SCOPED_TRACE(std::string(integrator == Integrator::Path ? "path, " : "whitted, ") + (on == &lit.gl ? "gl" : "cpu"));
            int wrong = 0;
            for (int j = 0; j < kSize; ++j)
                for (int i = 0; i < kSize; ++i) {
                    const glm::vec3 d = primaryDirection(camera, i, j);
                    const glm::vec3 p = camera.eye + d * (camera.eye.y / -d.y);
                    const double want = expected(p);
                    largest = std::max(largest, want);
                    const size_t k = size_t(j) * kSize + size_t(i);
                    const double got = double(on->color[k].x) - double(ambient->color[k].x);
                    if (std::abs(got - want) > 1e-4 * std::max(1.0, want) + 1e-6 && ++wrong <= 5)
                        ADD_FAILURE() << "pixel " << i << "," << j << " at " << p.x << "," << p.z << ": " << got
                                      << ", expected " << want;
                }
        }
    }
    EXPECT_GT(largest, 0.05) << "the light lights nothing in view";
}

TEST_F(Lights, ADirectionalLightGivesALambertPlaneAIrradianceCosTheta) {
    for (const float degrees : {0.0f, 35.0f, 70.0f}) {
        SCOPED_TRACE(degrees);
        const double theta = double(degrees) * std::numbers::pi / 180.0;
        Light sun;
        sun.kind = LightKind::Directional;
        sun.intensity = 1.5f;
        sun.direction = glm::vec3(float(std::sin(theta)), float(-std::cos(theta)), 0.0f);
        expectLight(sun, [&](glm::vec3) { return kAlbedo * 1.5 * std::cos(theta); });
    }
    // Below the horizon, nothing.
    Light under;
    under.kind = LightKind::Directional;
    under.direction = glm::vec3(0.0f, 1.0f, 0.0f);
    const test::Both both = test::renderBoth(floorScene(under), {{0, 3, 0.2f}, {0, 0, 0}, {0, 0, -1}, 70.0f}, 8, 8, 1, 3,
                                             Integrator::Path);
    for (const glm::vec3& c : both.gl.color) EXPECT_EQ(c, glm::vec3(0.0f));
    for (const glm::vec3& c : both.cpu.color) EXPECT_EQ(c, glm::vec3(0.0f));
}

TEST_F(Lights, ASpotsProfileAcrossAPlaneFollowsItsConeAndRange) {
    constexpr double kHeight = 2.0, kInner = 0.3, kOuter = 0.6;
    for (const float range : {0.0f, 3.0f}) {
        SCOPED_TRACE(range);
        Light spot;
        spot.kind = LightKind::Spot;
        spot.position = glm::vec3(0.2f, float(kHeight), -0.1f);
        spot.direction = glm::vec3(0.0f, -1.0f, 0.0f);
        spot.intensity = 2.0f;
        spot.innerCone = float(kInner);
        spot.outerCone = float(kOuter);
        spot.range = range;
        expectLight(spot, [&](glm::vec3 p) {
            const glm::dvec3 toP = glm::dvec3(p) - glm::dvec3(spot.position);
            const double r = glm::length(toP), cosPhi = -toP.y / r;
            const double s = std::clamp((cosPhi - std::cos(kOuter)) / (std::cos(kInner) - std::cos(kOuter)), 0.0, 1.0);
            const double window = range > 0.0f ? std::clamp(1.0 - std::pow(r / range, 4.0), 0.0, 1.0) : 1.0;
            return kAlbedo * 2.0 * s * s * window * cosPhi / (r * r);
        });
    }
}

}  // namespace
}  // namespace gpurt
