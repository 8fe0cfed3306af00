// Whitted shading of the CPU backend on tiny scenes whose colours are worked out by hand from the
// formulas of glsl/common/shading.h: diffuse + specular, inverse-square falloff, shadows, lights
// behind the surface, the headlight, and mirror bounces (Christen 2005, eq. 5.1).
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "raytrace/camera/Camera.h"
#include "raytrace/render/CpuTracer.h"
#include "raytrace/common/RayMath.h"
#include "raytrace/accel/grid/UniformGrid.h"
#include "LiftedNormal.h"

namespace gpurt::raymath {
#include "../../glsl/common/shading.h"
}  // namespace gpurt::raymath

namespace gpurt {
namespace {

// A large triangle in the plane z = 0 around the origin, facing +z, plus a camera at (0, 0, 2)
// whose single pixel looks straight down -z at the origin.
Scene floorScene(const Material& material) {
    Scene scene;
    scene.materials.push_back(material);
    scene.triangles.push_back({{-10, -10, 0}, {10, -10, 0}, {0, 10, 0}});
    scene.materialIds.push_back(0);
    scene.background = glm::vec3(0.25f, 0.5f, 0.75f);
    return scene;
}

Material material(glm::vec3 kd, glm::vec3 ks, float ns, glm::vec3 reflectivity = glm::vec3(0.0f)) {
    Material m;
    m.diffuse = kd;
    m.specular = ks;
    m.shininess = ns;
    m.reflectivity = reflectivity;
    return m;
}

RenderOutput renderCentre(const Scene& scene, int maxBounces = 3) {
    const UniformGrid grid = buildGrid(scene, {});
    const CpuTracer tracer(scene, grid);
    const CameraBasis camera = makeCamera({{0, 0, 2}, {0, 0, 0}, {0, 1, 0}, 45.0f}, 1, 1);
    RenderSettings settings;
    settings.maxBounces = maxBounces;
    settings.threads = 1;
    return tracer.render(camera, settings);
}

void expectColor(glm::vec3 actual, glm::dvec3 expected) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(actual[c], expected[c], 1e-5 * std::max(1.0, expected[c])) << "channel " << c;
}

const glm::dvec3 kd(0.5, 0.25, 1.0), ks(0.2, 0.3, 0.4);

// The normal's squared length is quartic in the edges: triangles 1e-15 or 1e15 across still get
// a unit normal facing the ray, and a triangle whose vertices are collinear in float (no normal
// at all) faces the ray instead of giving NaN.
// A light far brighter than white (colour and intensity near the float limit, or a surface point
// almost at the light) gives a large but finite contribution: infinity would turn into NaN when a
// later bounce weighs it by 0.
TEST(ShadingTest, LightContributionStaysFinite) {
    using namespace raymath;
    const glm::vec3 p(0), n(0, 0, 1), d(0, 0, -1);
    const glm::vec3 huge = lightContribution(p, n, d, glm::vec3(0.5f), glm::vec3(0.5f), 10.0f,
                                             glm::vec3(0, 0, 1), glm::vec3(1e30f, 3e38f, 1), 3e38f);
    const glm::vec3 close = lightContribution(p, n, d, glm::vec3(0.5f), glm::vec3(0), 10.0f,
                                              glm::vec3(0, 0, 1e-20f), glm::vec3(1), 1.0f);
    for (int c = 0; c < 3; ++c) {
        EXPECT_TRUE(std::isfinite(huge[c]) && huge[c] > 1e29f) << huge[c];
        EXPECT_TRUE(std::isfinite(close[c]) && close[c] > 1e29f) << close[c];
        EXPECT_EQ(0.0f * huge[c], 0.0f);
    }
}

TEST(ShadingTest, FacingNormalOfTinyHugeAndCollinearTriangles) {
    using namespace raymath;
    const glm::vec3 d = glm::normalize(glm::vec3(0.1f, -0.2f, -1.0f));
    for (float size : {1e-18f, 1e-15f, 1e-8f, 1.0f, 1e8f, 1e15f, 1e18f}) {
        SCOPED_TRACE(size);
        const glm::vec3 n = facingNormal(glm::vec3(size, 0, 0), glm::vec3(0, 2 * size, 0), d);
        EXPECT_EQ(n, glm::vec3(0, 0, 1));
        const glm::vec3 tilted = facingNormal(glm::vec3(size, 0, size), glm::vec3(0, size, 0), d);
        EXPECT_NEAR(tilted.x, -std::sqrt(0.5f), 1e-6f);
        EXPECT_NEAR(tilted.z, std::sqrt(0.5f), 1e-6f);
    }
    EXPECT_EQ(facingNormal(glm::vec3(1, 1, 1), glm::vec3(2, 2, 2), d), -d);
    EXPECT_EQ(facingNormal(glm::vec3(0), glm::vec3(0, 1, 0), d), -d);
}

TEST(ShadingTest, LightStraightAbove) {
    Scene scene = floorScene(material(kd, ks, 8.0f));
    scene.lights.push_back({{0, 0, 1}, {1, 1, 1}, 1.0f});
    const RenderOutput out = renderCentre(scene);
    // n.l = 1, the mirror of l is the view direction (specular 1), distance 1.
    expectColor(out.color[0], 0.1 * kd + (kd + ks));
    EXPECT_FLOAT_EQ(out.depth[0], 2.0f);
    EXPECT_EQ(out.prim[0], 0.0f);
    EXPECT_EQ(out.normal[0], glm::vec3(0, 0, 1));
    EXPECT_EQ(out.stats.shadowRays, 1u);
    EXPECT_EQ(out.stats.secondaryRays, 0u);
}

TEST(ShadingTest, ObliqueColouredLightWithFalloff) {
    Scene scene = floorScene(material(kd, ks, 8.0f));
    const glm::dvec3 color(1.0, 0.5, 0.25);
    scene.lights.push_back({{1, 0, 1}, glm::vec3(color), 3.0f});
    const RenderOutput out = renderCentre(scene);
    // l = (1, 0, 1)/sqrt 2 at distance sqrt 2; reflect(-l, n) = (-1, 0, 1)/sqrt 2, view (0, 0, 1).
    const double c = 1.0 / std::sqrt(2.0);
    const glm::dvec3 expected = 0.1 * kd + (kd * c + ks * std::pow(c, 8.0)) * color * 3.0 / 2.0;
    expectColor(out.color[0], expected);
}

TEST(ShadingTest, TwoLightsAddUp) {
    Scene scene = floorScene(material(kd, glm::dvec3(0.0), 8.0f));
    scene.lights.push_back({{0, 0, 1}, {1, 1, 1}, 1.0f});
    scene.lights.push_back({{0, 0, 2}, {1, 1, 1}, 2.0f});
    const RenderOutput out = renderCentre(scene);
    expectColor(out.color[0], 0.1 * kd + kd * 1.0 + kd * 2.0 / 4.0);
    EXPECT_EQ(out.stats.shadowRays, 2u);
}

TEST(ShadingTest, OccludedLightLeavesAmbient) {
    Scene scene = floorScene(material(kd, ks, 8.0f));
    scene.lights.push_back({{1, 0, 1}, {1, 1, 1}, 1.0f});
    // A small triangle across the segment from the origin to the light, off the primary ray.
    scene.triangles.push_back(
        {{0.45f, -0.05f, 0.55f}, {0.55f, -0.05f, 0.45f}, {0.5f, 0.08f, 0.5f}});
    scene.materialIds.push_back(0);
    const RenderOutput out = renderCentre(scene);
    EXPECT_EQ(out.prim[0], 0.0f);
    expectColor(out.color[0], 0.1 * kd);
    EXPECT_EQ(out.stats.shadowRays, 1u);
}

TEST(ShadingTest, LightBehindTheSurfaceGetsNoShadowRay) {
    Scene scene = floorScene(material(kd, ks, 8.0f));
    scene.lights.push_back({{0, 0, -1}, {1, 1, 1}, 1.0f});
    const RenderOutput out = renderCentre(scene);
    expectColor(out.color[0], 0.1 * kd);
    EXPECT_EQ(out.stats.shadowRays, 0u);
}

TEST(ShadingTest, HeadlightWhenTheSceneHasNoLights) {
    const Scene scene = floorScene(material(kd, ks, 8.0f));
    const RenderOutput out = renderCentre(scene);
    // Light at the eye (0, 0, 2); the box centre is the origin, so intensity 4 / 2 over distance^2 4.
    expectColor(out.color[0], 0.1 * kd + 0.5 * (kd + ks));
}

TEST(ShadingTest, MirrorAddsWeightedBackgroundOnAMiss) {
    const glm::dvec3 r(0.5, 0.25, 0.125);
    Scene scene = floorScene(material(kd, glm::dvec3(0.0), 8.0f, r));
    scene.lights.push_back({{0, 0, 1}, {1, 1, 1}, 1.0f});
    const glm::dvec3 local = 0.1 * kd + kd;
    const RenderOutput out = renderCentre(scene);
    expectColor(out.color[0], local + r * glm::dvec3(scene.background));
    EXPECT_EQ(out.stats.secondaryRays, 1u);
    const RenderOutput noBounce = renderCentre(scene, 0);
    expectColor(noBounce.color[0], local);
    EXPECT_EQ(noBounce.stats.secondaryRays, 0u);
}

TEST(ShadingTest, MirrorsFacingEachOtherBounceMaxBouncesTimes) {
    const glm::dvec3 rA(0.5, 0.5, 0.5), rB(0.8, 0.6, 0.4), kdB(0.3, 0.6, 0.9);
    Scene scene = floorScene(material(kd, ks, 8.0f, rA));
    // A second mirror at z = 3 (behind the camera) facing down.
    scene.materials.push_back(material(kdB, glm::dvec3(0.0), 8.0f, rB));
    scene.triangles.push_back({{-10, -10, 3}, {0, 10, 3}, {10, -10, 3}});
    scene.materialIds.push_back(1);
    scene.lights.push_back({{0, 0, 1}, {1, 1, 1}, 1.0f});
    // Floor: light at distance 1 straight above; top mirror: light at distance 2 straight below.
    const glm::dvec3 localA = 0.1 * kd + (kd + ks);
    const glm::dvec3 localB = 0.1 * kdB + kdB / 4.0;
    const RenderOutput two = renderCentre(scene, 2);
    expectColor(two.color[0], localA + rA * localB + rA * rB * localA);
    EXPECT_EQ(two.stats.secondaryRays, 2u);
    const RenderOutput three = renderCentre(scene, 3);
    expectColor(three.color[0], localA + rA * localB + rA * rB * localA + rA * rB * rA * localB);
    EXPECT_EQ(three.stats.secondaryRays, 3u);
}

// A unit vector from two numbers in [0, 1), uniform on the sphere.
glm::dvec3 sphereDirection(double a, double b) {
    const double z = 1.0 - 2.0 * a, r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.0 * M_PI * b;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// validReflectionNormal against Cycles' rule found by bisection (LiftedNormal.h): over random
// geometric normals, normals in front of them and view directions in front, a normal whose mirror
// rises above the threshold stays bit for bit; any other turns in the plane of itself and ng,
// towards ng, until its mirror rises exactly the threshold, as the bisection's.
TEST(ShadingTest, ValidReflectionNormalLiftsMirrorsBelowTheSurfaceAsCycles) {
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    const auto next = [&] { return uniform(rng); };
    int kept = 0, turned = 0;
    for (int i = 0; i < 4000; ++i) {
        const glm::dvec3 ng = sphereDirection(next(), next());
        glm::dvec3 n = sphereDirection(next(), next()), wo = sphereDirection(next(), next());
        if (glm::dot(n, ng) < 0.0) n = -n;
        if (glm::dot(wo, ng) < 0.0) wo = -wo;
        if (glm::dot(n, ng) < 0.05 || glm::dot(wo, ng) < 1e-3) continue;  // not a normal a map makes
        const double height = glm::dot(2.0 * glm::dot(n, wo) * n - wo, ng);
        if (std::abs(height - std::min(0.9 * glm::dot(ng, wo), 0.01)) < 1e-4) continue;  // float or double may differ
        const glm::vec3 got = raymath::validReflectionNormal(glm::vec3(n), glm::vec3(ng), glm::vec3(wo));
        const glm::dvec3 expected = test::liftedNormalByBisection(glm::dvec3(glm::vec3(n)), glm::dvec3(glm::vec3(ng)),
                                                                  glm::dvec3(glm::vec3(wo)));
        SCOPED_TRACE(testing::Message() << "case " << i);
        if (expected == glm::dvec3(glm::vec3(n))) {
            ++kept;
            ASSERT_EQ(got, glm::vec3(n));
            continue;
        }
        ++turned;
        ASSERT_NEAR(glm::length(glm::dvec3(got) - expected), 0.0, 2e-4);
        ASSERT_NEAR(glm::length(glm::dvec3(got)), 1.0, 1e-5);
        const glm::dvec3 r = 2.0 * glm::dot(glm::dvec3(got), wo) * glm::dvec3(got) - wo;
        ASSERT_NEAR(glm::dot(r, ng), std::min(0.9 * glm::dot(ng, wo), 0.01), 2e-4);
    }
    EXPECT_GT(kept, 500);
    EXPECT_GT(turned, 500);
}

}  // namespace
}  // namespace gpurt
