// Rescaling by powers of two (SceneScale.h): which scenes are rescaled and how far, and that a
// rescaled scene renders the same image, bit for bit, with depths scaled back exactly.
#include "raytrace/scene/SceneScale.h"

#include <cfloat>
#include <cmath>

#include <gtest/gtest.h>

#include "raytrace/camera/Camera.h"
#include "raytrace/render/CpuTracer.h"
#include "scene/JsonScene.h"
#include "scene/ObjLoader.h"

namespace gpurt {
namespace {

Scene scaled(Scene scene, int exponent) {
    for (Triangle& t : scene.triangles) {
        t.v0 = rescalePoint(t.v0, -exponent);
        t.v1 = rescalePoint(t.v1, -exponent);
        t.v2 = rescalePoint(t.v2, -exponent);
    }
    return scene;
}

// Largest coordinate and shortest non-zero edge (largest axis difference).
std::pair<double, double> extremes(const Scene& scene) {
    double largest = 0.0, shortest = INFINITY;
    for (const Triangle& t : scene.triangles) {
        for (glm::vec3 v : {t.v0, t.v1, t.v2})
            largest = std::max(
                {largest, double(std::abs(v.x)), double(std::abs(v.y)), double(std::abs(v.z))});
        for (auto [a, b] : {std::pair{t.v0, t.v1}, {t.v1, t.v2}, {t.v2, t.v0}}) {
            const glm::dvec3 e = glm::abs(glm::dvec3(b) - glm::dvec3(a));
            const double length = std::max({e.x, e.y, e.z});
            if (length > 0.0) shortest = std::min(shortest, length);
        }
    }
    return {largest, shortest};
}

TEST(SceneScaleTest, OrdinaryScenesAreLeftAlone) {
    for (const char* model : {"teapot.obj", "bunny.obj", "bunny_lo.obj", "cornell_box.obj"})
        EXPECT_EQ(renderScaleExponent(loadObj(std::string("../shared/models/") + model)), 0)
            << model;
    for (const char* scene : {"boxes.json", "room.json", "highlow.json"})
        EXPECT_EQ(renderScaleExponent(loadJsonScene(std::string("scenes/") + scene)), 0) << scene;
    EXPECT_EQ(renderScaleExponent(Scene{}), 0);
}

TEST(SceneScaleTest, FarFromUnitSizeIsBroughtToUnitSize) {
    const Scene teapot = loadObj("../shared/models/teapot.obj");
    for (int k : {-126, -100, -40, 40, 100, 120}) {
        SCOPED_TRACE(k);
        const Scene far = scaled(teapot, k);
        const int exponent = renderScaleExponent(far);
        EXPECT_NE(exponent, 0);
        const auto [largest, shortest] = extremes(scaled(far, -exponent));
        EXPECT_GE(largest, 1.0);
        EXPECT_LT(largest, 2.0);
        EXPECT_GE(shortest, 0x1p-28);  // the teapot's own edges come along
    }
    // A scene of ordinary size with a triangle 1e-30 across is left alone: scaling it up would
    // push the rest (lights included) towards overflow, for a triangle no pixel can show.
    Scene mixed;
    mixed.triangles = {{{1, 0, 0}, {3, 1, 0}, {1, 2, 1}},
                       {{0, 0, 0}, {1e-30f, 0, 0}, {0, 1e-30f, 0}}};
    EXPECT_EQ(renderScaleExponent(mixed), 0);
    mixed.triangles[0] = {{1e30f, 0, 0}, {3e30f, 1e30f, 0}, {1e30f, 2e30f, 1e30f}};
    EXPECT_EQ(extremes(scaled(mixed, -renderScaleExponent(mixed))).first, double(3e30f) / 0x1p101);
}

// The CPU backend on a scene with lights, rescaled by 2^-40 and by 2^20 (both stay within the
// range where nothing over- or underflows): every colour, triangle and normal is the same, every
// depth the same times the scale.
TEST(SceneScaleTest, RescaledSceneRendersTheSameImage) {
    const Scene original = loadJsonScene("scenes/boxes.json");
    const CameraSpec camera = *original.camera;
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    auto render = [&](const Scene& scene, const CameraSpec& spec) {
        const UniformGrid grid = buildGrid(scene, {});
        return CpuTracer(scene, grid).render(makeCamera(spec, 64, 48), settings);
    };
    const RenderOutput reference = render(original, camera);
    for (int exponent : {40, -20}) {
        SCOPED_TRACE(exponent);
        Scene scene = original;
        rescaleScene(scene, exponent);
        ASSERT_TRUE(scene.camera.has_value());
        EXPECT_EQ(scene.camera->eye, rescalePoint(camera.eye, exponent));
        EXPECT_EQ(scene.lights[0].intensity,
                  std::ldexp(original.lights[0].intensity, -2 * exponent));
        RenderOutput out = render(scene, *scene.camera);
        unscaleDepth(out.depth, exponent);
        EXPECT_EQ(out.color, reference.color);
        EXPECT_EQ(out.prim, reference.prim);
        EXPECT_EQ(out.normal, reference.normal);
        EXPECT_EQ(out.depth, reference.depth);
    }
}

TEST(SceneScaleTest, DepthsBeyondTheLargestFloatSaturate) {
    std::vector<float> depth = {1.0f, 3.0f, INFINITY, 0x1p-20f};
    unscaleDepth(depth, 127);
    EXPECT_EQ(depth[0], 0x1p127f);
    EXPECT_EQ(depth[1], FLT_MAX);   // 1.5 * 2^128 is not a float
    EXPECT_EQ(depth[2], INFINITY);  // a miss stays a miss
    EXPECT_EQ(depth[3], 0x1p107f);
}

}  // namespace
}  // namespace gpurt
