// KHR_materials_unlit (glsl/common/material.h GPURT_MODEL_UNLIT; CONTRACT.md, "Lights"): camera
// rays and what a mirror shows see its base colour exactly, whatever lights it; it casts no
// shadow (shadow rays pass it) and lights nothing (path rays after a diffuse bounce pass it). Both
// backends, both integrators.
#include "../common/GLTest.h"
#include "TestScenes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace gpurt {
namespace {

using test::addMaterial;
using test::addPolygon;

constexpr glm::vec3 kBase{0.3f, 0.6f, 0.9f};

class Unlit : public test::GLTest {};

uint32_t addUnlit(Scene& scene, glm::vec3 base) {
    const uint32_t m = addMaterial(scene, base);
    scene.materials[m].model = GPURT_MODEL_UNLIT;
    return m;
}

// A floor y = 0 of albedo 0.5 under a point light at height 3 (and, with `blocker`, an unlit quad
// at height 2 between them), seen straight down from height 1.
Scene floorScene(bool blocker) {
    Scene scene;
    scene.background = glm::vec3(0.0f);
    addPolygon(scene, {{-4, 0, -4}, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}}, addMaterial(scene, glm::vec3(0.5f)));
    if (blocker) addPolygon(scene, {{-2, 2, -2}, {-2, 2, 2}, {2, 2, 2}, {2, 2, -2}}, addUnlit(scene, glm::vec3(1.0f)));
    Light light;
    light.position = {0.0f, 3.0f, 0.0f};
    light.intensity = 9.0f;
    scene.lights.push_back(light);
    return scene;
}

const CameraSpec kDown{{0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0, 0, -1}, 60.0f};

TEST_F(Unlit, CameraRaysSeeItsBaseColourWhateverLightsIt) {
    Scene scene = floorScene(false);
    addPolygon(scene, {{-1, 0.5f, -1}, {-1, 0.5f, 1}, {1, 0.5f, 1}, {1, 0.5f, -1}}, addUnlit(scene, kBase));
    for (const Integrator integrator : {Integrator::Whitted, Integrator::Path}) {
        const test::Both both = test::renderBoth(scene, kDown, 16, 16, 4, 3, integrator);
        for (const RenderOutput* out : {&both.gl, &both.cpu}) {
            SCOPED_TRACE(std::string(integrator == Integrator::Path ? "path, " : "whitted, ") + (out == &both.gl ? "gl" : "cpu"));
            // The quad fills the middle of the view (half a unit below the camera, 2 wide).
            for (int j = 4; j < 12; ++j)
                for (int i = 4; i < 12; ++i) EXPECT_EQ(out->color[size_t(j) * 16 + size_t(i)], kBase) << i << "," << j;
        }
    }
}

TEST_F(Unlit, AMirrorShowsItsBaseColour) {
    Scene scene;
    scene.background = glm::vec3(0.0f);
    constexpr float kReflectivity = 0.8f;
    const uint32_t mirror = addMaterial(scene, glm::vec3(0.0f));
    scene.materials[mirror].reflectivity = glm::vec3(kReflectivity);
    addPolygon(scene, {{-4, 0, -4}, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}}, mirror);  // the floor a mirror
    addPolygon(scene, {{-4, 2, -4}, {4, 2, -4}, {4, 2, 4}, {-4, 2, 4}}, addUnlit(scene, kBase));  // a ceiling
    Light light;
    light.position = {0.0f, 1.5f, 0.0f};
    scene.lights.push_back(light);
    for (const Integrator integrator : {Integrator::Whitted, Integrator::Path}) {
        const test::Both both = test::renderBoth(scene, kDown, 8, 8, 1, 3, integrator);
        for (const RenderOutput* out : {&both.gl, &both.cpu}) {
            SCOPED_TRACE(std::string(integrator == Integrator::Path ? "path, " : "whitted, ") + (out == &both.gl ? "gl" : "cpu"));
            for (const glm::vec3& c : out->color)
                for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], kReflectivity * kBase[k], 1e-6f);
        }
    }
}

TEST_F(Unlit, ItCastsNoShadowAndLightsNothing) {
    // Direct light only (one bounce of path), then whole paths: the floor under the unlit quad is
    // lit as if the quad were not there.
    for (const int bounces : {1, 8}) {
        for (const Integrator integrator : {Integrator::Whitted, Integrator::Path}) {
            if (integrator == Integrator::Whitted && bounces > 1) continue;
            SCOPED_TRACE(std::string(integrator == Integrator::Path ? "path, " : "whitted, ") + std::to_string(bounces));
            const test::Both with = test::renderBoth(floorScene(true), kDown, 16, 16, 16, bounces, integrator);
            const test::Both without = test::renderBoth(floorScene(false), kDown, 16, 16, 16, bounces, integrator);
            for (const auto& [a, b] : {std::pair{&with.gl, &without.gl}, std::pair{&with.cpu, &without.cpu}}) {
                SCOPED_TRACE(a == &with.gl ? "gl" : "cpu");
                double sum = 0.0;
                // Sample for sample: the shadow rays pass the quad, and a path ray that meets it
                // goes on as it came and leaves into the black sky, as it does without the quad
                // (were the quad seen, its colour 1 would light the floor from above).
                for (size_t p = 0; p < a->color.size(); ++p) {
                    EXPECT_NEAR(a->color[p].x, b->color[p].x, 1e-4f * std::max(1.0f, b->color[p].x)) << p;
                    sum += b->color[p].x;
                }
                EXPECT_GT(sum, 0.0);
            }
        }
    }
}

}  // namespace
}  // namespace gpurt
