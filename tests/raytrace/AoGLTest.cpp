// Ambient occlusion (--integrator ao, glsl/common/integrators/ao.h) against closed forms, on both
// backends: a point on a floor with nothing near sees its whole hemisphere (exactly 1); beside an
// infinite wall it sees half of the cosine-weighted hemisphere; with --ao-distance R the wall at
// distance x blocks the directions whose projection onto the floor's unit disk (Malley: cosine-
// weighted directions project uniformly onto it) lies beyond x / R towards the wall, a circular
// segment of area acos(a) - a sqrt(1 - a^2), a = x / R. A camera ray that leaves the scene is 0.
#include "../common/GLTest.h"
#include "TestScenes.h"
#include "raytrace/integrators/Registry.h"

#include <gtest/gtest.h>

#include <cmath>

namespace gpurt {
namespace {

using test::addMaterial;
using test::addPolygon;

constexpr float kL = 1000.0f;  // the floor's and the wall's extent: infinite as far as the point sees
constexpr float kX = 1.0f;     // the point's distance from the wall

// A floor y = 0 on z in [0, L] and, with `wall`, a wall z = 0 up to y = L.
Scene wallScene(bool wall) {
    Scene scene;
    const uint32_t grey = addMaterial(scene, glm::vec3(0.5f));
    addPolygon(scene, {{-kL, 0, 0}, {-kL, 0, kL}, {kL, 0, kL}, {kL, 0, 0}}, grey);
    if (wall) addPolygon(scene, {{-kL, 0, 0}, {kL, 0, 0}, {kL, kL, 0}, {-kL, kL, 0}}, grey);
    return scene;
}

class Ao : public test::GLTest {};

struct AoImages {
    RenderOutput gl, cpu;
};

// An 8 x 8 image of `samples` samples a pixel, straight down onto the floor at (0, 0, kX) through a
// field of view of 0.2 degrees (the pixels see it within 0.002 of that point).
AoImages renderAo(const Scene& scene, uint32_t samples, float distance, CameraSpec spec = {{0, 1, kX}, {0, 0, kX}, {0, 0, -1}, 0.2f}) {
    const UniformGrid grid = buildGrid(scene, GridOptions{});
    const CameraBasis camera = makeCamera(spec, 8, 8);
    RenderSettings settings;
    settings.width = settings.height = 8;
    settings.samples = samples;
    settings.integrator = Integrator("ao");
    if (distance > 0.0f) settings.integratorOptions["aoDistance"] = distance;
    AoImages ao;
    ao.cpu = CpuTracer(scene, grid).render(camera, settings);
    ao.gl = GpuTracer(scene, grid).render(camera, settings);
    return ao;
}

double mean(const RenderOutput& out) {
    double sum = 0.0;
    for (const glm::vec3& c : out.color) sum += c.x;
    return sum / double(out.color.size());
}

// The samples are 0 or 1 (each channel alike): the image mean estimates p within 4 binomial
// standard deviations of the 64 x samples draws (the Sobol points do better; this bounds them).
void expectFraction(const AoImages& ao, double p, uint32_t samples, const char* what) {
    const double tolerance = 4.0 * std::sqrt(p * (1.0 - p) / (64.0 * samples)) + 1e-6;
    for (const RenderOutput* out : {&ao.gl, &ao.cpu}) {
        SCOPED_TRACE(std::string(what) + (out == &ao.gl ? ", gl" : ", cpu"));
        EXPECT_NEAR(mean(*out), p, tolerance);
        for (const glm::vec3& c : out->color) EXPECT_TRUE(c.x == c.y && c.y == c.z) << c.x << " " << c.y;
    }
}

TEST_F(Ao, NothingNearSeesTheWholeHemisphere) {
    const AoImages ao = renderAo(wallScene(false), 16, 0.0f);
    for (const RenderOutput* out : {&ao.gl, &ao.cpu})
        for (const glm::vec3& c : out->color) EXPECT_EQ(c, glm::vec3(1.0f));
}

TEST_F(Ao, AnInfiniteWallHidesHalfTheCosineWeightedHemisphere) {
    expectFraction(renderAo(wallScene(true), 256, 0.0f), 0.5, 256, "unlimited");
}

TEST_F(Ao, TheDistanceLimitsTheOccludersToACircularSegment) {
    for (const float r : {2.0f, 1.25f}) {
        const double a = kX / r;
        const double blocked = (std::acos(a) - a * std::sqrt(1.0 - a * a)) / M_PI;
        expectFraction(renderAo(wallScene(true), 256, r), 1.0 - blocked, 256, r == 2.0f ? "R = 2" : "R = 1.25");
    }
    // Nearer than the wall: nothing occludes.
    const AoImages near = renderAo(wallScene(true), 16, 0.5f * kX);
    for (const RenderOutput* out : {&near.gl, &near.cpu})
        for (const glm::vec3& c : out->color) EXPECT_EQ(c, glm::vec3(1.0f));
}

TEST_F(Ao, BothBackendsTakeTheSameSamplesAndARayThatLeavesIsZero) {
    // Looking away from the wall, the upper half of the image is sky (0), the lower the floor.
    const AoImages ao = renderAo(wallScene(true), 8, 0.0f, {{0, 0.5f, 3}, {0, 0.5f, 4}, {0, 1, 0}, 60.0f});
    size_t sky = 0;
    ASSERT_EQ(ao.gl.color.size(), ao.cpu.color.size());
    for (size_t i = 0; i < ao.gl.color.size(); ++i) {
        EXPECT_EQ(ao.gl.color[i], ao.cpu.color[i]) << "pixel " << i;  // the same numbers and rays
        if (ao.cpu.prim[i] < 0.0f) {
            ++sky;
            EXPECT_EQ(ao.cpu.color[i], glm::vec3(0.0f));
        }
    }
    EXPECT_GT(sky, 0u);
}

TEST(AoRegistry, IsInTheRegistryWithItsOption) {
    const IntegratorInfo* ao = findIntegrator("ao");
    ASSERT_NE(ao, nullptr);
    ASSERT_EQ(ao->options.size(), 1u);
    EXPECT_EQ(ao->options[0].name, "ao-distance");
    RenderSettings settings;
    settings.integrator = ao->id;
    EXPECT_TRUE(std::isinf(integratorOption(settings, "aoDistance")));  // unlimited unless given
    settings.integratorOptions["aoDistance"] = 3.0f;
    EXPECT_EQ(integratorOption(settings, "aoDistance"), 3.0f);
}

}  // namespace
}  // namespace gpurt
