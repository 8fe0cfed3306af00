// Rescaling by powers of two (SceneScale.h): which scenes are rescaled and how far, and that a
// rescaled scene renders the same image, bit for bit, with depths scaled back exactly.
#include "raytrace/scene/SceneScale.h"

#include <cfloat>
#include <cmath>

#include <glm/gtx/component_wise.hpp>
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

// A KHR_materials_volume solid's attenuation distance is a length: rescaled with the scene, a box
// of coloured glass absorbs the same (within what the secondary rays' offset from the surface,
// which does not scale exactly, changes of the length inside), and visibly (the same box without
// its volume differs).
TEST(SceneScaleTest, RescaledVolumesAbsorbTheSame) {
    Scene original = loadJsonScene("scenes/boxes.json");
    Material& glass = original.materials[original.materialIds[0]];
    glass.model = GPURT_MODEL_GLTF;
    glass.diffuse = glm::vec3(1.0f);
    glass.roughness = 0.0f;
    glass.ior = 1.5f;
    glass.transmission = glm::vec3(1.0f);
    glass.thickness = 1.0f;
    glass.attenuationColor = glm::vec3(0.9f, 0.5f, 0.2f);
    glass.attenuationDistance = 0.5f;
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    auto render = [&](const Scene& scene) {
        const UniformGrid grid = buildGrid(scene, {});
        return CpuTracer(scene, grid).render(makeCamera(*scene.camera, 64, 48), settings);
    };
    const RenderOutput reference = render(original);
    Scene clear = original;
    clear.materials[original.materialIds[0]].thickness = 0.0f;
    const RenderOutput unabsorbed = render(clear);
    double change = 0.0;
    for (size_t k = 0; k < reference.color.size(); ++k)
        change = std::max(change, double(glm::compMax(glm::abs(unabsorbed.color[k] - reference.color[k]))));
    EXPECT_GT(change, 0.05);
    for (int exponent : {40, -20}) {
        SCOPED_TRACE(exponent);
        Scene scene = original;
        rescaleScene(scene, exponent);
        EXPECT_EQ(scene.materials[original.materialIds[0]].attenuationDistance, std::ldexp(0.5f, -exponent));
        EXPECT_EQ(scene.materials[0].attenuationDistance == INFINITY, original.materials[0].attenuationDistance == INFINITY);
        const RenderOutput out = render(scene);
        for (size_t k = 0; k < out.color.size(); ++k)
            ASSERT_LE(glm::compMax(glm::abs(out.color[k] - reference.color[k])), 1e-3f * (1.0f + glm::compMax(reference.color[k])))
                << "pixel " << k;
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
