// JSON scene files (JsonScene.h) and format detection (SceneLoader.h): transforms against an
// independent computation, numbering and materials across meshes, every kind of validation error,
// and the shipped demo scenes.
#include "scene/JsonScene.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "image/InputError.h"
#include "scene/ObjLoader.h"
#include "raytrace/scene/SceneLoader.h"
#include "../common/TransmissionQuad.h"

namespace gpurt {
namespace {

namespace fs = std::filesystem;

fs::path sourceDir() {
#ifdef GPURT_SOURCE_DIR
    return fs::path(GPURT_SOURCE_DIR);
#else
    return fs::path(__FILE__).parent_path().parent_path().parent_path();
#endif
}

// A fresh folder per test, removed afterwards.
class JsonSceneTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("gpurt-json-" + std::to_string(::getpid()) + "-" +
                                            info->test_suite_name() + "-" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path write(const std::string& name, const std::string& text) const {
        const fs::path path = dir_ / name;
        std::ofstream(path, std::ios::binary) << text;
        return path;
    }

    // Expects loading `json` (as scene.json) to throw InputError, with a one-line message that
    // names the file and contains `expected` (usually the JSON pointer and what is wrong).
    void expectError(const std::string& json, const std::vector<std::string>& expected) const {
        const fs::path path = write("scene.json", json);
        try {
            loadJsonSceneFile(path);
            ADD_FAILURE() << "no error for: " << json;
        } catch (const InputError& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find(path.string() + ":"), std::string::npos) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
            for (const std::string& part : expected)
                EXPECT_NE(message.find(part), std::string::npos)
                    << "'" << part << "' not in: " << message;
        }
    }

    fs::path dir_;
};

const char* kTriangleObj = "v 1 2 3\nv -4 5 0.5\nv 0 -1 2\nf 1 2 3\n";

void expectNear(glm::vec3 actual, glm::dvec3 expected, double tolerance = 1e-5) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(actual[i], expected[i], tolerance) << "component " << i;
}

// Rotation by `degrees` about one axis, written out (not via glm), applied to p.
glm::dvec3 rotateX(glm::dvec3 p, double degrees) {
    const double a = degrees * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
    return {p.x, c * p.y - s * p.z, s * p.y + c * p.z};
}
glm::dvec3 rotateY(glm::dvec3 p, double degrees) {
    const double a = degrees * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
    return {c * p.x + s * p.z, p.y, -s * p.x + c * p.z};
}
glm::dvec3 rotateZ(glm::dvec3 p, double degrees) {
    const double a = degrees * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
    return {c * p.x - s * p.y, s * p.x + c * p.y, p.z};
}

TEST_F(JsonSceneTest, TranslateRotateScaleIsTRzRyRxS) {
    write("tri.obj", kTriangleObj);
    const Scene scene =
        loadJsonScene(write("scene.json", R"({"meshes": [{"file": "tri.obj", "transform":
        {"translate": [1, -2, 3], "rotate": [30, 45, -60], "scale": [2, 0.5, -3]}}]})"));
    ASSERT_EQ(scene.triangles.size(), 1u);
    const glm::dvec3 in[3] = {{1, 2, 3}, {-4, 5, 0.5}, {0, -1, 2}};
    const glm::vec3 out[3] = {scene.triangles[0].v0, scene.triangles[0].v1, scene.triangles[0].v2};
    for (int k = 0; k < 3; ++k) {
        glm::dvec3 p = in[k] * glm::dvec3(2, 0.5, -3);
        p = rotateZ(rotateY(rotateX(p, 30), 45), -60) + glm::dvec3(1, -2, 3);
        expectNear(out[k], p);
    }
}

TEST_F(JsonSceneTest, ScalarScaleAndPartialTransforms) {
    write("tri.obj", kTriangleObj);
    const Scene scene = loadJsonScene(write("scene.json", R"({"meshes": [
        {"file": "tri.obj", "transform": {"scale": 2}},
        {"file": "tri.obj", "transform": {"rotate": [0, 90, 0]}},
        {"file": "tri.obj", "transform": {}},
        {"file": "tri.obj"}]})"));
    ASSERT_EQ(scene.triangles.size(), 4u);
    expectNear(scene.triangles[0].v1, glm::dvec3(-8, 10, 1));
    expectNear(scene.triangles[1].v0, rotateY({1, 2, 3}, 90));
    EXPECT_EQ(scene.triangles[2].v2, glm::vec3(0, -1, 2));
    EXPECT_EQ(scene.triangles[3].v2, glm::vec3(0, -1, 2));
}

TEST_F(JsonSceneTest, MatrixIsRowMajor) {
    write("tri.obj", kTriangleObj);
    const Scene scene =
        loadJsonScene(write("scene.json", R"({"meshes": [{"file": "tri.obj", "transform":
        {"matrix": [0, -1, 0, 5,   1, 0, 0, 6,   0, 0, 2, 7,   0, 0, 0, 1]}}]})"));
    ASSERT_EQ(scene.triangles.size(), 1u);
    // x' = -y + 5, y' = x + 6, z' = 2z + 7
    EXPECT_EQ(scene.triangles[0].v0, glm::vec3(3, 7, 13));
    EXPECT_EQ(scene.triangles[0].v1, glm::vec3(0, 2, 8));
    EXPECT_EQ(scene.triangles[0].v2, glm::vec3(6, 6, 11));
}

TEST_F(JsonSceneTest, NumberingContinuesAcrossMeshesAndMaterialsAreOffset) {
    write("quad.mtl",
          "newmtl red\nKd 1 0 0\nnewmtl glass\nKd 0 0 0\nKs 0.5 0.6 0.7\nNs 80\nillum 3\n");
    write("quad.obj",
          "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl glass\nf 1 2 3 4\nusemtl "
          "red\nf 1 2 4\n");
    write("tri.obj", kTriangleObj);
    const Scene scene = loadJsonScene(write("scene.json", R"({"meshes": [
        {"file": "tri.obj"},
        {"file": "quad.obj"},
        {"file": "quad.obj", "material": {"diffuse": [0.1, 0.2, 0.3], "specular": [0.4, 0.5, 0.6],
                                          "shininess": 7, "reflectivity": 0.25, "name": "override"}},
        {"file": "tri.obj", "material": {"reflectivity": [0.1, 0.2, 0.3]}}]})"));

    // tri (1), quad fan (2) + triangle (1), quad again (3), tri (1), in list order.
    ASSERT_EQ(scene.triangles.size(), 8u);
    EXPECT_EQ(scene.triangles[0].v0, glm::vec3(1, 2, 3));
    EXPECT_EQ(scene.triangles[1].v2, glm::vec3(1, 1, 0));  // fan (v0, v1, v2)
    EXPECT_EQ(scene.triangles[2].v1, glm::vec3(1, 1, 0));  // fan (v0, v2, v3)
    EXPECT_EQ(scene.triangles[3].v2, glm::vec3(0, 1, 0));
    EXPECT_EQ(scene.triangles[4].v2, glm::vec3(1, 1, 0));
    EXPECT_EQ(scene.triangles[7].v0, glm::vec3(1, 2, 3));

    // Materials: tri.obj's default, quad's red and glass, the two overrides.
    const Scene tri = loadObj(dir_ / "tri.obj");
    ASSERT_EQ(tri.materials.size(), 1u);
    ASSERT_EQ(scene.materials.size(), 5u);
    EXPECT_EQ(scene.materials[1].name, "red");
    EXPECT_EQ(scene.materials[2].name, "glass");
    EXPECT_EQ(scene.materials[2].reflectivity, glm::vec3(0.5f, 0.6f, 0.7f));  // illum 3: Ks
    const Material& override = scene.materials[3];
    EXPECT_EQ(override.name, "override");
    EXPECT_EQ(override.diffuse, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(override.specular, glm::vec3(0.4f, 0.5f, 0.6f));
    EXPECT_EQ(override.shininess, 7.0f);
    EXPECT_EQ(override.reflectivity, glm::vec3(0.25f));
    // Unspecified fields of an override keep Material's defaults.
    EXPECT_EQ(scene.materials[4].diffuse, Material{}.diffuse);
    EXPECT_EQ(scene.materials[4].reflectivity, glm::vec3(0.1f, 0.2f, 0.3f));
    const std::vector<uint32_t> ids = {0, 2, 2, 1, 3, 3, 3, 4};
    EXPECT_EQ(scene.materialIds, ids);
}

// Each mesh file's textures follow the earlier files' in the scene's list, and every texture slot
// of its materials is moved with them: an OBJ's map_d (alpha) listed after another textured OBJ
// names its own texture, as its map_Kd does.
TEST_F(JsonSceneTest, LaterMeshFilesKeepEveryTextureSlotOnTheirOwnTextures) {
    write("bands.bmp", test::TransmissionQuad::image());
    const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nusemtl m\nf 1/1 2/2 3/3\n";
    write("first.mtl", "newmtl m\nKd 1 1 1\nmap_Kd bands.bmp\n");
    write("second.mtl", "newmtl m\nKd 1 1 1\nd 0.5\nmap_Kd bands.bmp\nmap_d bands.bmp\n");
    write("first.obj", "mtllib first.mtl\n" + quad);
    write("second.obj", "mtllib second.mtl\n" + quad);
    const Scene scene = loadJsonScene(write("scene.json", R"({"meshes": [{"file": "first.obj"}, {"file": "second.obj"}]})"));
    ASSERT_EQ(scene.textures.size(), 2u);
    ASSERT_EQ(scene.materialIds.size(), 2u);
    const Material& first = scene.materials[scene.materialIds[0]];
    const Material& second = scene.materials[scene.materialIds[1]];
    EXPECT_EQ(first.diffuseTexture, 0);
    EXPECT_EQ(second.diffuseTexture, 1);
    ASSERT_TRUE(second.alphaTexture.given());
    EXPECT_EQ(second.alphaTexture.texture, 1);
}

TEST_F(JsonSceneTest, LightsCameraBackgroundRender) {
    write("tri.obj", kTriangleObj);
    const JsonSceneFile file = loadJsonSceneFile(write("scene.json", R"({
        "meshes": [{"file": "tri.obj"}],
        "lights": [{"position": [1, 2, 3], "color": [0.5, 0.25, 2], "intensity": 40},
                   {"position": [-1, 0, 0]}],
        "camera": {"eye": [0, 1, 5], "target": [0, 1, 0], "up": [1, 0, 0], "fovy": 30.5},
        "background": [0.25, 0.5, 1],
        "render": {"size": [320, 200], "max_bounces": 0}})"));
    const Scene& scene = file.scene;
    ASSERT_EQ(scene.lights.size(), 2u);
    EXPECT_EQ(scene.lights[0].position, glm::vec3(1, 2, 3));
    EXPECT_EQ(scene.lights[0].color, glm::vec3(0.5f, 0.25f, 2.0f));
    EXPECT_EQ(scene.lights[0].intensity, 40.0f);
    EXPECT_EQ(scene.lights[1].color, glm::vec3(1.0f));
    EXPECT_EQ(scene.lights[1].intensity, 1.0f);
    ASSERT_TRUE(scene.camera.has_value());
    EXPECT_EQ(scene.camera->eye, glm::vec3(0, 1, 5));
    EXPECT_EQ(scene.camera->target, glm::vec3(0, 1, 0));
    EXPECT_EQ(scene.camera->up, glm::vec3(1, 0, 0));
    EXPECT_EQ(scene.camera->fovy, 30.5f);
    EXPECT_EQ(scene.background, glm::vec3(0.25f, 0.5f, 1.0f));
    ASSERT_TRUE(file.size.has_value());
    EXPECT_EQ(*file.size, glm::ivec2(320, 200));
    EXPECT_EQ(scene.maxBounces, 0);
}

// Spot and directional lights (docs/SCENE_FORMAT.md, "Light"), and the lights it refuses.
TEST_F(JsonSceneTest, SpotAndDirectionalLights) {
    write("tri.obj", kTriangleObj);
    const std::string head = R"({"meshes": [{"file": "tri.obj"}], "lights": [)";
    const Scene scene = loadJsonSceneFile(write("scene.json", head + R"(
        {"type": "spot", "position": [0, 4, 0], "direction": [0, -2, 0], "inner_cone": 10, "outer_cone": 30,
         "range": 6, "intensity": 20},
        {"type": "directional", "direction": [1, -1, 0], "color": [1, 0.9, 0.8], "intensity": 2},
        {"position": [1, 1, 1]}]})")).scene;
    ASSERT_EQ(scene.lights.size(), 3u);
    const Light& spot = scene.lights[0];
    EXPECT_EQ(spot.kind, LightKind::Spot);
    EXPECT_EQ(spot.direction, glm::vec3(0, -1, 0));  // normalised
    EXPECT_FLOAT_EQ(spot.innerCone, float(10.0 * std::numbers::pi / 180.0));
    EXPECT_FLOAT_EQ(spot.outerCone, float(30.0 * std::numbers::pi / 180.0));
    EXPECT_EQ(spot.range, 6.0f);
    EXPECT_EQ(spot.intensity, 20.0f);  // gpurt's own units, as given
    const Light& sun = scene.lights[1];
    EXPECT_EQ(sun.kind, LightKind::Directional);
    EXPECT_NEAR(sun.direction.x, 0.70710678f, 1e-6f);
    EXPECT_NEAR(sun.direction.y, -0.70710678f, 1e-6f);
    EXPECT_EQ(scene.lights[2].kind, LightKind::Point);
    expectError(head + R"({"type": "area", "position": [0, 1, 0]}]})", {"/lights/0/type"});
    expectError(head + R"({"type": "spot", "position": [0, 1, 0]}]})", {"/lights/0", "direction"});
    expectError(head + R"({"type": "directional", "direction": [0, -1, 0], "position": [0, 1, 0]}]})",
                {"/lights/0/position", "no position"});
    expectError(head + R"({"type": "directional", "direction": [0, 0, 0]}]})", {"/lights/0/direction"});
    expectError(head + R"({"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "inner_cone": 40,
                           "outer_cone": 30}]})", {"/lights/0/outer_cone"});
    expectError(head + R"({"position": [0, 1, 0], "direction": [0, -1, 0]}]})", {"/lights/0/direction"});
    expectError(head + R"({"position": [0, 1, 0], "range": 0}]})", {"/lights/0/range"});
}

// The thin lens's fields (CONTRACT.md, depth of field), and the lenses the contract does not know.
TEST_F(JsonSceneTest, TheCameraTakesALens) {
    write("tri.obj", kTriangleObj);
    const std::string head = R"({"meshes": [{"file": "tri.obj"}], "camera": {"eye": [0, 1, 5], "target": [0, 1, 0], )";
    const Scene scene = loadJsonSceneFile(write("scene.json", head + R"("fstop": 2.8, "focus_distance": 4.5,
        "blades": 6, "blade_rotation": 15}})")).scene;
    ASSERT_TRUE(scene.camera.has_value());
    EXPECT_EQ(scene.camera->fstop, 2.8f);
    EXPECT_EQ(scene.camera->lensRadius, 0.0f);
    EXPECT_EQ(scene.camera->focusDistance, 4.5f);
    EXPECT_EQ(scene.camera->blades, 6);
    EXPECT_EQ(scene.camera->bladeRotation, 15.0f);
    EXPECT_EQ(loadJsonSceneFile(write("scene.json", head + R"("lens_radius": 0.05}})")).scene.camera->lensRadius, 0.05f);
    expectError(head + R"("lens_radius": -0.05}})", {"/camera/lens_radius", ">= 0"});
    expectError(head + R"("fstop": 0}})", {"/camera/fstop", "> 0"});
    expectError(head + R"("fstop": 2, "lens_radius": 0.1}})", {"/camera/fstop", "not both"});
    expectError(head + R"("blades": 2}})", {"/camera/blades"});
    expectError(head + R"("focus_distance": 0}})", {"/camera/focus_distance"});
}

// A camera animation: the keys as given (defaults as for the camera), frame f at time f / fps,
// each value interpolated linearly between the keys around it (computed here in double), and the
// first and last key's camera before and after them.
TEST_F(JsonSceneTest, CameraAnimationInterpolatesItsKeysLinearly) {
    const Scene scene = loadJsonSceneFile(write("scene.json", R"({"meshes": [],
        "animation": {"fps": 10, "camera": [
            {"time": 0.5, "eye": [0, 0, 10], "target": [0, 0, 0]},
            {"time": 1.5, "eye": [10, 2, 0], "target": [1, 1, 1], "up": [1, 1, 0], "fovy": 85},
            {"time": 1.7, "eye": [10, 2, -4], "target": [1, 1, 1], "up": [1, 1, 0], "fovy": 5}]}})")).scene;
    ASSERT_TRUE(scene.animation.has_value());
    EXPECT_FALSE(scene.camera.has_value());
    const CameraAnimation& a = *scene.animation;
    EXPECT_EQ(a.fps, 10.0f);
    ASSERT_EQ(a.keys.size(), 3u);
    EXPECT_EQ(a.keys[0].camera.up, glm::vec3(0, 1, 0));
    EXPECT_EQ(a.keys[0].camera.fovy, 45.0f);
    for (int frame : {0, 3, 5}) {  // up to the first key
        const CameraSpec c = a.at(frame);
        EXPECT_EQ(c.eye, glm::vec3(0, 0, 10)) << frame;
        EXPECT_EQ(c.fovy, 45.0f) << frame;
    }
    for (int frame : {18, 1000}) EXPECT_EQ(a.at(frame).eye, glm::vec3(10, 2, -4)) << frame;
    for (int frame = 5; frame <= 17; ++frame) {
        const double t = frame / 10.0;
        const int k = t <= 1.5 ? 0 : 1;
        const double t0 = k == 0 ? 0.5 : 1.5, t1 = k == 0 ? 1.5 : 1.7;
        const double s = (t - t0) / (double(float(t1)) - double(float(t0)));
        const double eye0[2][3] = {{0, 0, 10}, {10, 2, 0}}, eye1[2][3] = {{10, 2, 0}, {10, 2, -4}};
        const double fovy0[2] = {45, 85}, fovy1[2] = {85, 5};
        const CameraSpec c = a.at(frame);
        for (int i = 0; i < 3; ++i)
            EXPECT_NEAR(c.eye[i], eye0[k][i] + (eye1[k][i] - eye0[k][i]) * s, 1e-5) << frame << " " << i;
        EXPECT_NEAR(c.fovy, fovy0[k] + (fovy1[k] - fovy0[k]) * s, 1e-4) << frame;
        EXPECT_NEAR(c.up.x, k == 0 ? s : 1.0, 1e-6) << frame;
    }
    const std::string keys = R"({"meshes": [], "animation": {"camera": [
        {"time": 0, "eye": [0, 0, 1], "target": [0, 0, 0]}, )";
    expectError(keys + R"({"time": 0, "eye": [0, 0, 2], "target": [0, 0, 0]}]}})",
                {"/animation/camera/1/time: must be later than the key before (0), got 0"});
    expectError(keys + R"({"eye": [0, 0, 2], "target": [0, 0, 0]}]}})", {"/animation/camera/1/time: missing required key"});
    expectError(keys + R"({"time": 1, "eye": [0, 0, 2], "target": [0, 0, 2]}]}})", {"/animation/camera/1/target"});
    expectError(keys + R"({"time": 1, "eye": [0, 0, 2], "target": [0, 0, 0], "roll": 3}]}})",
                {"/animation/camera/1/roll: unknown key"});
    expectError(R"({"meshes": [], "animation": {"camera": []}})", {"/animation/camera: needs at least one key"});
    expectError(R"({"meshes": [], "animation": {"fps": 0, "camera": []}})", {"/animation/fps: must be in (0, 1000]"});
    expectError(R"({"meshes": [], "animation": {"fps": 24}})", {"/animation/camera: missing required key"});
    expectError(R"({"meshes": [], "animation": {"camera": [3]}})", {"/animation/camera/0: expected an object"});
}

TEST_F(JsonSceneTest, DefaultsWhenOptionalPartsAreMissing) {
    const JsonSceneFile file = loadJsonSceneFile(write("scene.json", R"({"meshes": [],
        "camera": {"eye": [0, 0, 1], "target": [0, 0, 0]}})"));
    EXPECT_TRUE(file.scene.triangles.empty());
    EXPECT_EQ(file.scene.materials.size(), 1u);
    EXPECT_TRUE(file.scene.lights.empty());
    EXPECT_EQ(file.scene.camera->up, glm::vec3(0, 1, 0));
    EXPECT_EQ(file.scene.camera->fovy, 45.0f);
    EXPECT_EQ(file.scene.maxBounces, Scene{}.maxBounces);
    EXPECT_EQ(file.scene.background, Scene{}.background);
    EXPECT_FALSE(file.size.has_value());
    EXPECT_FALSE(
        loadJsonSceneFile(write("bare.json", R"({"meshes": []})")).scene.camera.has_value());
}

TEST_F(JsonSceneTest, SyntaxErrorsNameLineAndColumn) {
    expectError("{\n  \"meshes\": [\n    ,\n  ]\n}\n", {"scene.json:3:5: ", "syntax error"});
    expectError("", {"scene.json:1:1: ", "unexpected end of input"});
    expectError("{\"meshes\": []} trailing", {"scene.json:1:"});
    expectError("{\"meshes\": [],\n \"background\": [1e999, 0, 0]}",
                {"scene.json:2:17: ", "1e999"});
    expectError("{\"meshes\": [\"\x01\xff\"]}", {"scene.json:1:"});
}

TEST_F(JsonSceneTest, StructureErrorsNameTheJsonPointer) {
    write("tri.obj", kTriangleObj);
    expectError("[1, 2]", {"top level: expected an object, got array"});
    expectError(R"({"meshes": [], "lihgts": []})", {"/lihgts: unknown key"});
    expectError(R"({"meshes": [], "lights": [{"position": [0, 0, 0], "colour": [1, 1, 1]}]})",
                {"/lights/0/colour: unknown key"});
    expectError(R"({"meshes": [{"file": "tri.obj", "transfrom": {}}]})",
                {"/meshes/0/transfrom: unknown key"});
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"diffuse": [1, 1, 1], "kd": 1}}]})",
                {"/meshes/0/material/kd: unknown key"});
    expectError(R"({"lights": []})", {"/meshes: missing required key"});
    expectError(R"({"meshes": [{"file": "tri.obj"}, {"transform": {}}]})",
                {"/meshes/1/file: missing required key"});
    expectError(R"({"meshes": [], "lights": [{"color": [1, 1, 1]}]})",
                {"/lights/0/position: missing required key"});
    expectError(R"({"meshes": [], "camera": {"eye": [0, 0, 1]}})",
                {"/camera/target: missing required key"});
}

TEST_F(JsonSceneTest, DuplicateKeysAreErrors) {
    expectError(R"({"meshes": [], "meshes": []})", {"/meshes: duplicate key"});
    expectError(R"({"meshes": [], "lights": [{"position": [0, 0, 0]}, [1, [2]], {"color": [1, 1, 1],
        "position": [0, 0, 0], "color": [1, 1, 1]}]})",
                {"/lights/2/color: duplicate key"});
    expectError(
        R"({"meshes": [{"file": "a.obj"}, {"file": "a.obj", "transform": {"scale": 1, "scale": 2}}]})",
        {"/meshes/1/transform/scale: duplicate key"});
}

// A material override's "doubleSided": false culls its back faces (glTF's doubleSided); OBJ's
// materials and overrides without it stay double-sided.
TEST_F(JsonSceneTest, DoubleSidedFalseMakesAMaterialSingleSided) {
    write("tri.obj", kTriangleObj);
    const Scene scene = loadJsonScene(write("scene.json", R"({"meshes": [
        {"file": "tri.obj"},
        {"file": "tri.obj", "material": {"doubleSided": false}},
        {"file": "tri.obj", "material": {"doubleSided": true}},
        {"file": "tri.obj", "material": {"diffuse": [0.5, 0.5, 0.5]}}]})"));
    ASSERT_EQ(scene.materials.size(), 4u);
    EXPECT_TRUE(scene.materials[0].doubleSided);
    EXPECT_FALSE(scene.materials[1].doubleSided);
    EXPECT_TRUE(scene.materials[2].doubleSided);
    EXPECT_TRUE(scene.materials[3].doubleSided);
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"doubleSided": 0}}]})",
                {"/meshes/0/material/doubleSided: expected true or false, got number"});
}

// KHR_materials_volume's keys: "attenuation_color" and "attenuation_distance" make glTF's model
// and a volume (a JSON solid has no thin walls); without them, no volume; bad values name the key.
TEST_F(JsonSceneTest, AttenuationMakesAVolume) {
    write("tri.obj", kTriangleObj);
    const Scene scene = loadJsonScene(write("scene.json", R"({"meshes": [
        {"file": "tri.obj", "material": {"metallic": 0, "roughness": 0, "transmission": 1}},
        {"file": "tri.obj", "material": {"metallic": 0, "roughness": 0, "transmission": 1,
                                         "attenuation_color": [0.5, 1, 0.25], "attenuation_distance": 3}}]})"));
    ASSERT_EQ(scene.materials.size(), 2u);
    EXPECT_FALSE(scene.materials[0].hasVolume());
    const Material& m = scene.materials[1];
    EXPECT_EQ(m.model, GPURT_MODEL_GLTF);
    EXPECT_EQ(m.attenuationColor, glm::vec3(0.5f, 1.0f, 0.25f));
    EXPECT_EQ(m.attenuationDistance, 3.0f);
    ASSERT_TRUE(m.hasVolume());
    EXPECT_NEAR(m.absorption().x, std::log(2.0) / 3.0, 1e-6);
    EXPECT_EQ(m.absorption().y, 0.0f);
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"attenuation_distance": 0}}]})",
                {"/meshes/0/material/attenuation_distance: must be > 0"});
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"attenuation_color": [0.5, 1.5, 1]}}]})",
                {"/meshes/0/material/attenuation_color/1: must be <= 1"});
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"attenuation_color": [0.5, -1, 1]}}]})",
                {"/meshes/0/material/attenuation_color/1: must be >= 0"});
}

// "thin_walled": glTF's model's transmission through a thin wall (a JSON solid otherwise); it
// needs a transmission, has no volume and no classic material.
TEST_F(JsonSceneTest, ThinWalledTransmissionIsAThinWall) {
    write("tri.obj", kTriangleObj);
    const Scene scene = loadJsonScene(write("scene.json", R"({"meshes": [
        {"file": "tri.obj", "material": {"metallic": 0, "roughness": 0, "transmission": 1}},
        {"file": "tri.obj", "material": {"metallic": 0, "roughness": 0.2, "transmission": 0.5, "thin_walled": true}},
        {"file": "tri.obj", "material": {"metallic": 0, "roughness": 0.2, "transmission": 0.5, "thin_walled": false}}]})"));
    ASSERT_EQ(scene.materials.size(), 3u);
    EXPECT_FALSE(scene.materials[0].thin());
    EXPECT_TRUE(scene.materials[1].thin());
    EXPECT_EQ(scene.materials[1].ior, 1.5f);
    EXPECT_FALSE(scene.materials[2].thin());
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"metallic": 0, "thin_walled": true}}]})",
                {"/meshes/0/material/thin_walled: needs a transmission above 0"});
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"metallic": 0, "transmission": 1, "thin_walled": 1}}]})",
                {"/meshes/0/material/thin_walled: expected true or false"});
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"metallic": 0, "transmission": 1, "thin_walled": true,
                                                               "attenuation_distance": 2}}]})",
                {"/meshes/0/material/thin_walled: a thin wall has no volume"});
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"diffuse": [1, 1, 1], "thin_walled": true}}]})",
                {"/meshes/0/material/thin_walled: goes with glTF's model"});
}

// KHR_materials_iridescence's keys: "iridescence" (a factor), "iridescence_ior" and
// "iridescence_thickness" (one thickness, nm) make glTF's model; bad values name the key.
TEST_F(JsonSceneTest, IridescenceMakesAFilm) {
    write("tri.obj", kTriangleObj);
    const Scene scene = loadJsonScene(write("scene.json", R"({"meshes": [
        {"file": "tri.obj", "material": {"iridescence": 0.5, "iridescence_ior": 1.7, "iridescence_thickness": 320}}]})"));
    const Material& m = scene.materials[0];
    EXPECT_EQ(m.model, GPURT_MODEL_GLTF);
    EXPECT_TRUE(m.hasIridescence());
    EXPECT_EQ(m.iridescenceFactor, 0.5f);
    EXPECT_EQ(m.iridescenceIor, 1.7f);
    EXPECT_EQ(m.iridescenceThicknessMin, 320.0f);
    EXPECT_EQ(m.iridescenceThicknessMax, 320.0f);
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"iridescence": 1.5}}]})",
                {"/meshes/0/material/iridescence: must be <= 1"});
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"iridescence_ior": 0.9}}]})",
                {"/meshes/0/material/iridescence_ior: must be >= 1"});
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"iridescence_thickness": -3}}]})",
                {"/meshes/0/material/iridescence_thickness: must be >= 0"});
}

// KHR_materials_anisotropy's keys: "anisotropy" (a factor) and "anisotropy_rotation" (radians)
// make glTF's model; bad values name the key.
TEST_F(JsonSceneTest, AnisotropyStretchesTheLobe) {
    write("tri.obj", kTriangleObj);
    const Scene scene = loadJsonScene(write("scene.json", R"({"meshes": [
        {"file": "tri.obj", "material": {"metallic": 1, "roughness": 0.3, "anisotropy": 0.75, "anisotropy_rotation": -1.5}}]})"));
    const Material& m = scene.materials[0];
    EXPECT_EQ(m.model, GPURT_MODEL_GLTF);
    EXPECT_TRUE(m.hasAnisotropy());
    EXPECT_EQ(m.anisotropyStrength, 0.75f);
    EXPECT_EQ(m.anisotropyRotation, -1.5f);
    EXPECT_EQ(m.anisotropyTexture, -1);
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"anisotropy": 1.5}}]})",
                {"/meshes/0/material/anisotropy: must be <= 1"});
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"anisotropy_rotation": "left"}}]})",
                {"/meshes/0/material/anisotropy_rotation: expected a number"});
}

// KHR_materials_dispersion's key: "dispersion" (20 / the Abbe number) on a transmissive solid makes
// glTF's model; anywhere else (no transmission, a thin wall) it would change nothing and is an
// error naming the key, as are bad values.
TEST_F(JsonSceneTest, DispersionGoesWithTransmissiveSolids) {
    write("tri.obj", kTriangleObj);
    const Scene scene = loadJsonScene(write("scene.json", R"({"meshes": [
        {"file": "tri.obj", "material": {"transmission": 1, "ior": 1.7, "dispersion": 0.6}}]})"));
    const Material& m = scene.materials[0];
    EXPECT_EQ(m.model, GPURT_MODEL_GLTF);
    EXPECT_EQ(m.dispersion, 0.6f);
    EXPECT_TRUE(m.disperses());
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"metallic": 0, "dispersion": 0.5}}]})",
                {"/meshes/0/material/dispersion: applies to a transmissive solid only"});
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"transmission": 1, "thin_walled": true, "dispersion": 0.5}}]})",
                {"/meshes/0/material/dispersion: applies to a transmissive solid only"});
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"transmission": 1, "dispersion": -1}}]})",
                {"/meshes/0/material/dispersion: must be >= 0"});
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"transmission": 1, "dispersion": 2000}}]})",
                {"/meshes/0/material/dispersion: must be <= 1000"});
}

TEST_F(JsonSceneTest, TypeErrorsNameTheJsonPointer) {
    write("tri.obj", kTriangleObj);
    expectError(R"({"meshes": {}})", {"/meshes: expected an array, got object"});
    expectError(R"({"meshes": [{"file": 3}]})", {"/meshes/0/file: expected a string, got number"});
    expectError(R"({"meshes": ["tri.obj"]})", {"/meshes/0: expected an object, got string"});
    expectError(
        R"({"meshes": [], "camera": {"eye": [0, 0, 1], "target": [0, 0, 0], "fovy": "wide"}})",
        {"/camera/fovy: expected a number, got string"});
    expectError(R"({"meshes": [{"file": "tri.obj", "transform": {"translate": [1, null, 3]}}]})",
                {"/meshes/0/transform/translate/1: expected a number, got null"});
    expectError(R"({"meshes": [{"file": "tri.obj", "transform": {"rotate": [1, 2]}}]})",
                {"/meshes/0/transform/rotate: expected an array of 3 numbers, got 2 elements"});
    expectError(R"({"meshes": [], "background": [1, true, 0]})",
                {"/background/1: expected a number, got boolean"});
    expectError(R"({"meshes": [], "render": {"size": [256.5, 256]}})",
                {"/render/size/0: expected an integer, got 256.5"});
    expectError(R"({"meshes": [], "render": {"max_bounces": "3"}})",
                {"/render/max_bounces: expected an integer, got string"});
}

TEST_F(JsonSceneTest, RangeErrorsNameTheJsonPointer) {
    write("tri.obj", kTriangleObj);
    const std::string camera =
        R"({"meshes": [], "camera": {"eye": [0, 0, 1], "target": [0, 0, 0], )";
    expectError(camera + R"("fovy": 0}})", {"/camera/fovy: must be between 0 and 180"});
    expectError(camera + R"("fovy": 180}})", {"/camera/fovy"});
    expectError(camera + R"("fovy": -5}})", {"/camera/fovy"});
    expectError(camera + R"("up": [0, 0, 2]}})",
                {"/camera/up: up must be non-zero and not parallel"});
    expectError(camera + R"("up": [0, 0, 0]}})", {"/camera/up"});
    expectError(R"({"meshes": [], "camera": {"eye": [1, 2, 3], "target": [1, 2, 3]}})",
                {"/camera/target"});
    expectError(R"({"meshes": [], "lights": [{"position": [0, 0, 0], "color": [1, -0.5, 1]}]})",
                {"/lights/0/color/1: must be >= 0"});
    expectError(R"({"meshes": [], "lights": [{"position": [0, 0, 0], "intensity": -1}]})",
                {"/lights/0/intensity: must be >= 0"});
    expectError(R"({"meshes": [], "lights": [{"position": [0, 0, 0], "intensity": 1e39}]})",
                {"/lights/0/intensity: 1e+39 does not fit in a 32-bit float"});
    expectError(R"({"meshes": [], "background": [0, 0, -1]})", {"/background/2: must be >= 0"});
    expectError(R"({"meshes": [], "render": {"size": [0, 256]}})",
                {"/render/size/0: must be in 1..16384"});
    expectError(R"({"meshes": [], "render": {"size": [256, 16385]}})",
                {"/render/size/1: must be in 1..16384"});
    expectError(R"({"meshes": [], "render": {"size": [-3, 16385]}})", {"/render/size/0"});
    expectError(R"({"meshes": [], "render": {"size": [256]}})",
                {"/render/size: expected an array of 2 integers"});
    expectError(R"({"meshes": [], "render": {"max_bounces": -1}})",
                {"/render/max_bounces: must be in 0..64"});
    expectError(R"({"meshes": [], "render": {"max_bounces": 65}})", {"/render/max_bounces"});
    expectError(R"({"meshes": [], "render": {"max_bounces": 18446744073709551615}})",
                {"/render/max_bounces"});
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"shininess": -2}}]})",
                {"/meshes/0/material/shininess: must be >= 0"});
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"reflectivity": 1.5}}]})",
                {"/meshes/0/material/reflectivity: must be <= 1"});
    expectError(R"({"meshes": [{"file": "tri.obj", "material": {"reflectivity": [0, 2, 0]}}]})",
                {"/meshes/0/material/reflectivity/1: must be <= 1"});
}

// The camera check is done in double: in float, |target - eye|^2 overflows for a camera 1e20
// away, which the renderer handles (SceneScale.h), and underflows for one 1e-20 away.
TEST_F(JsonSceneTest, CamerasFarAwayOrVeryCloseAreAccepted) {
    for (const char* camera : {R"("eye": [0, 0, 3e30], "target": [1e30, 0, 0])",
                               R"("eye": [0, 0, 3e-30], "target": [1e-30, 0, 0])",
                               R"("eye": [0, 0, 1], "target": [0, 0, 0], "up": [0, 1e-30, 0])"}) {
        const Scene scene = loadJsonScene(
            write("scene.json", std::string(R"({"meshes": [], "camera": {)") + camera + "}}"));
        EXPECT_TRUE(scene.camera.has_value()) << camera;
    }
}

TEST_F(JsonSceneTest, TransformErrors) {
    write("tri.obj", kTriangleObj);
    expectError(R"({"meshes": [{"file": "tri.obj", "transform": {"scale": [1, 0, 1]}}]})",
                {"/meshes/0/transform/scale: scale must not be 0"});
    expectError(R"({"meshes": [{"file": "tri.obj", "transform": {"matrix": [1, 0, 0, 0,  0, 1, 0, 0,
        0, 0, 0, 0,  0, 0, 0, 1]}}]})",
                {"/meshes/0/transform/matrix: singular matrix"});
    expectError(R"({"meshes": [{"file": "tri.obj", "transform": {"matrix": [1, 2, 3, 0,  2, 4, 6, 0,
        0, 0, 1, 0,  0, 0, 0, 1]}}]})",
                {"/meshes/0/transform/matrix: singular matrix"});
    expectError(R"({"meshes": [{"file": "tri.obj", "transform": {"matrix": [1, 0, 0, 0,  0, 1, 0, 0,
        0, 0, 1, 0,  0, 0, 1, 1]}}]})",
                {"/meshes/0/transform/matrix: last row must be 0, 0, 0, 1"});
    expectError(R"({"meshes": [{"file": "tri.obj", "transform": {"matrix": [1, 0, 0, 0]}}]})",
                {"/meshes/0/transform/matrix: expected an array of 16 numbers"});
    expectError(R"({"meshes": [{"file": "tri.obj", "transform": {"translate": [1, 0, 0],
        "matrix": [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]}}]})",
                {"/meshes/0/transform/matrix: cannot be combined with \"translate\""});
    expectError(R"({"meshes": [{"file": "tri.obj", "transform": {"scale": 3e38}}]})",
                {"/meshes/0/transform: moves a vertex of the mesh's triangle 0 outside the 32-bit "
                 "float range"});
}

TEST_F(JsonSceneTest, MissingAndBadMeshFiles) {
    fs::create_directories(dir_ / "folder.obj");
    write("tri.obj", kTriangleObj);
    expectError(R"({"meshes": [{"file": "tri.obj"}, {"file": "tri.obj"}, {"file": "x.obj"}]})",
                {"/meshes/2/file: no such file 'x.obj'"});
    expectError(R"({"meshes": [{"file": "folder.obj"}]})",
                {"/meshes/0/file: 'folder.obj' is a directory"});
    expectError(R"({"meshes": [{"file": ""}]})", {"/meshes/0/file: empty file name"});
    // An error inside the OBJ keeps the OBJ loader's message, which names the OBJ and its line.
    const fs::path bad = write("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
    try {
        loadJsonScene(write("scene.json", R"({"meshes": [{"file": "bad.obj"}]})"));
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(bad.string() + ":3:"), std::string::npos) << e.what();
    }
}

TEST_F(JsonSceneTest, MeshPathsAreRelativeToTheJsonFile) {
    fs::create_directories(dir_ / "meshes");
    write("meshes/tri.obj", kTriangleObj);
    fs::create_directories(dir_ / "scenes");
    const fs::path scene =
        write("scenes/scene.json", R"({"meshes": [{"file": "../meshes/tri.obj"}]})");
    EXPECT_EQ(loadJsonScene(scene).triangles.size(), 1u);
    const std::string absolute = (dir_ / "meshes" / "tri.obj").string();
    EXPECT_EQ(loadJsonScene(write("abs.json", R"({"meshes": [{"file": ")" + absolute + R"("}]})"))
                  .triangles.size(),
              1u);
}

TEST_F(JsonSceneTest, DeeplyNestedInputIsRefusedWithoutCrashing) {
    expectError(std::string(100000, '[') + std::string(100000, ']'),
                {"top level: expected an object"});
    expectError(
        R"({"meshes": [], "lights": )" + std::string(100000, '[') + std::string(100000, ']') + "}",
        {"/lights/0: expected an object, got array"});
}

TEST_F(JsonSceneTest, LoadSceneRecognisesTheFormatByContent) {
    write("tri.obj", kTriangleObj);
    // JSON content under an .obj name, with leading whitespace and a byte order mark.
    const LoadedScene json = loadScene(write("looks-like.obj",
                                             "\xEF\xBB\xBF \n\t{\"meshes\": [{\"file\": "
                                             "\"tri.obj\"}], \"render\": {\"size\": [64, 32]}}"));
    EXPECT_EQ(json.scene.triangles.size(), 1u);
    ASSERT_TRUE(json.size.has_value());
    EXPECT_EQ(*json.size, glm::ivec2(64, 32));
    // OBJ content under a .json name.
    const LoadedScene obj = loadScene(write("looks-like.json", std::string("\n\n") + kTriangleObj));
    EXPECT_EQ(obj.scene.triangles.size(), 1u);
    EXPECT_FALSE(obj.size.has_value());
    // Long leading whitespace before the '{'.
    EXPECT_EQ(loadScene(write("spaces.json", std::string(10000, ' ') + R"({"meshes": []})"))
                  .scene.triangles.size(),
              0u);

    auto expectLoadError = [](const fs::path& path, const std::string& expected) {
        try {
            loadScene(path);
            ADD_FAILURE() << "no error for " << path;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(path.string() + ": " + expected),
                      std::string::npos)
                << e.what();
        }
    };
    // The magic decides, whatever the name: these go to the packed reader (PackedSceneTest).
    expectLoadError(write("scene.gpscene", std::string("GPRTSCN1") + std::string(32, '\0')),
                    "unknown packed format version 0");
    expectLoadError(write("packed.obj", "GPRTSCN1"), "truncated");
    expectLoadError(write("later.json", "GPRTSCN2"),
                    "not a packed gpurt scene (wrong magic 'GPRTSCN2'");
    expectLoadError(dir_ / "missing.json", "no such file");
    expectLoadError(dir_, "is a directory");
}

// The demo scenes the repository ships (written by scripts/make_scenes.py).
TEST(ShippedScenesTest, LoadWithTheSeedsTriangleCounts) {
    const fs::path scenes = sourceDir() / "scenes";
    struct Expected {
        const char* file;
        size_t triangles;
    };
    for (const Expected& expected : {Expected{"boxes.json", 36}, Expected{"room.json", 2064},
                                     Expected{"highlow.json", 60026}}) {
        SCOPED_TRACE(expected.file);
        const LoadedScene loaded = loadScene(scenes / expected.file);
        const Scene& scene = loaded.scene;
        EXPECT_EQ(scene.triangles.size(), expected.triangles);
        EXPECT_EQ(scene.materialIds.size(), scene.triangles.size());
        EXPECT_TRUE(scene.camera.has_value());
        EXPECT_GE(scene.lights.size(), 2u);
        bool hasMirror = false;
        for (uint32_t id : scene.materialIds) {
            ASSERT_LT(id, scene.materials.size());
            if (scene.materials[id].reflectivity != glm::vec3(0.0f)) hasMirror = true;
        }
        EXPECT_TRUE(hasMirror);
        ASSERT_TRUE(loaded.size.has_value());
        EXPECT_EQ(*loaded.size, glm::ivec2(256, 256));
    }
    // Scene A and B are one OBJ each without transforms: the JSON route has the OBJ's triangles.
    for (const char* name : {"boxes", "room"}) {
        const Scene json = loadJsonScene(scenes / (std::string(name) + ".json"));
        const Scene obj = loadObj(scenes / (std::string(name) + ".obj"));
        ASSERT_EQ(json.triangles.size(), obj.triangles.size());
        for (size_t k = 0; k < obj.triangles.size(); ++k) {
            EXPECT_EQ(json.triangles[k].v0, obj.triangles[k].v0);
            EXPECT_EQ(json.triangles[k].v2, obj.triangles[k].v2);
        }
        EXPECT_EQ(json.materialIds, obj.materialIds);
    }
    // B's camera and lights are inside the room.
    const Scene room = loadJsonScene(scenes / "room.json");
    const Bounds box = room.bounds();
    auto inside = [&](glm::vec3 p) {
        return glm::all(glm::lessThan(box.min, p)) && glm::all(glm::lessThan(p, box.max));
    };
    EXPECT_TRUE(inside(room.camera->eye));
    for (const Light& light : room.lights) EXPECT_TRUE(inside(light.position));
}

// "up_axis" is read, and rotateUpToY turns everything placed in the scene (triangles, normals,
// lights, camera, animation keys) by the rotation that takes that axis to +y: a quarter turn about
// x for z and -z, about z for x and -x, a half turn about x for -y (rotateX/rotateZ above, by
// angle).
TEST_F(JsonSceneTest, UpAxisTurnsEverythingPlacedInTheScene) {
    write("tri.obj", std::string(kTriangleObj) + "vn 0 0 1\nvn 0 1 0\nvn 1 0 0\nf 1//1 2//2 3//3\n");
    const std::pair<const char*, std::function<glm::dvec3(glm::dvec3)>> axes[] = {
        {"z", [](glm::dvec3 p) { return rotateX(p, -90); }}, {"-z", [](glm::dvec3 p) { return rotateX(p, 90); }},
        {"x", [](glm::dvec3 p) { return rotateZ(p, 90); }},  {"-x", [](glm::dvec3 p) { return rotateZ(p, -90); }},
        {"-y", [](glm::dvec3 p) { return rotateX(p, 180); }}, {"y", [](glm::dvec3 p) { return p; }},
    };
    for (const auto& [name, turn] : axes) {
        SCOPED_TRACE(name);
        const std::string up = std::string(name).back() == 'x' ? "0, 1, 0" : "1, 0, 0";
        const fs::path path = write("scene.json", std::string("{\"up_axis\": \"") + name + R"(", "meshes": [{"file": "tri.obj"}],
            "lights": [{"position": [1, 2, 3]}],
            "camera": {"eye": [4, 5, 6], "target": [0, 0, 0], "up": [)" + up + R"(]},
            "animation": {"camera": [{"time": 0, "eye": [7, 8, 9], "target": [1, 0, 0], "up": [)" + up + "]}]}}");
        const Scene file = loadJsonSceneFile(path).scene;
        Scene scene = file;
        UpAxis axis = UpAxis::PosY;
        ASSERT_TRUE(parseUpAxis(name, axis));
        EXPECT_EQ(scene.upAxis, axis);
        EXPECT_STREQ(upAxisName(axis), name);
        rotateUpToY(scene, scene.upAxis);
        EXPECT_EQ(scene.upAxis, UpAxis::PosY);
        // The named axis itself ends up as +y.
        glm::dvec3 named(0.0);
        named[std::string(name).back() - 'x'] = name[0] == '-' ? -1.0 : 1.0;
        expectNear(upAxisToY(glm::vec3(named), axis), turn(named));
        expectNear(upAxisToY(glm::vec3(named), axis), {0, 1, 0});
        ASSERT_EQ(scene.triangles.size(), 2u);
        for (size_t t = 0; t < scene.triangles.size(); ++t) {
            expectNear(scene.triangles[t].v0, turn(file.triangles[t].v0));
            expectNear(scene.triangles[t].v1, turn(file.triangles[t].v1));
            expectNear(scene.triangles[t].v2, turn(file.triangles[t].v2));
        }
        ASSERT_EQ(scene.normals.size(), 2u);
        expectNear(scene.normals[1].n0, turn(file.normals[1].n0));
        expectNear(scene.normals[1].n2, turn(file.normals[1].n2));
        expectNear(scene.lights[0].position, turn({1, 2, 3}));
        expectNear(scene.camera->eye, turn({4, 5, 6}));
        expectNear(scene.camera->up, turn(glm::dvec3(file.camera->up)));
        expectNear(scene.animation->keys[0].camera.eye, turn({7, 8, 9}));
        expectNear(scene.animation->keys[0].camera.target, turn({1, 0, 0}));
    }
    expectError(R"({"up_axis": "w", "meshes": []})", {"/up_axis", "\"z\""});
    expectError(R"({"up_axis": 2, "meshes": []})", {"/up_axis"});
}

}  // namespace
}  // namespace gpurt
