// glTF scenes (GltfLoader.h), written here with their buffers as data URIs: the node hierarchy's
// transforms (TRS and matrices) against positions worked out by hand, the contract's triangle
// numbering, every index type, strides, strips and fans, sparse and normalized accessors,
// materials, the camera and point lights; and every way a file can fail to be a usable glTF.
#include "scene/GltfLoader.h"

#include <gtest/gtest.h>

#include "../common/Refusal.h"
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "GltfDocument.h"
#include "../common/TransmissionQuad.h"
#include "image/InputError.h"

namespace gpurt {
namespace {

namespace fs = std::filesystem;
using test::Gltf;

Scene parse(const std::string& text) { return parseGltf(text, "scene.gltf", fs::temp_directory_path()); }

void expectNear(glm::vec3 a, glm::vec3 b, const std::string& what) {
    EXPECT_NEAR(a.x, b.x, 1e-5f) << what;
    EXPECT_NEAR(a.y, b.y, 1e-5f) << what;
    EXPECT_NEAR(a.z, b.z, 1e-5f) << what;
}

// Node 0 (translate 1,2,3; rotate 90 degrees about y; scale 2) holds a triangle with byte
// indices and has two children: node 1 (a column-major matrix translating by 0,0,-5) with a quad
// of short indices, then node 2 (no transform of its own) with a fan. Node 3, the scene's second
// root, holds an unindexed strip whose positions are interleaved with padding (byte stride 16).
TEST(GltfLoader, NodesDepthFirstWithTheirWorldTransforms) {
    Gltf g;
    const int tri = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const int triIndex = g.indices(std::vector<uint8_t>{2, 0, 1}, 5121);
    const int quad = g.positions({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
    const int quadIndex = g.indices(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, 5123);
    const int fan = g.positions({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
    const int fanIndex = g.indices(std::vector<uint32_t>{0, 1, 2, 3}, 5125);
    const int strip = g.accessor(g.view(std::vector<float>{0, 0, 9, -1, 1, 0, 9, -1, 0, 1, 9, -1, 1, 1, 9, -1}, 16), 5126, 4, "VEC3");
    const double s = std::sqrt(0.5);
    const std::string rest =
        "\"scene\": 0, \"scenes\": [{\"nodes\": [0, 3]}], \"nodes\": ["
        "{\"translation\": [1, 2, 3], \"rotation\": [0, " + std::to_string(s) + ", 0, " + std::to_string(s) +
        "], \"scale\": [2, 2, 2], \"mesh\": 0, \"children\": [1, 2]},"
        "{\"matrix\": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -5, 1], \"mesh\": 1},"
        "{\"mesh\": 2}, {\"mesh\": 3}],"
        "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(tri) + "}, \"indices\": " +
        std::to_string(triIndex) + "}]}, {\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(quad) +
        "}, \"indices\": " + std::to_string(quadIndex) + "}]}, {\"primitives\": [{\"attributes\": {\"POSITION\": " +
        std::to_string(fan) + "}, \"indices\": " + std::to_string(fanIndex) + ", \"mode\": 6}]}, {\"primitives\": [{\"attributes\": "
        "{\"POSITION\": " + std::to_string(strip) + "}, \"mode\": 5}]}]";
    const Scene scene = parse(g.json(rest));
    // Node 0's world map: p -> (1, 2, 3) + 2 Ry(90)(p), with Ry(90)(x, y, z) = (z, y, -x).
    auto node0 = [](glm::vec3 p) { return glm::vec3(1, 2, 3) + 2.0f * glm::vec3(p.z, p.y, -p.x); };
    auto node1 = [&](glm::vec3 p) { return node0(p + glm::vec3(0, 0, -5)); };
    const std::vector<Triangle> expected = {
        {node0({0, 1, 0}), node0({0, 0, 0}), node0({1, 0, 0})},                       // node 0, indices 2 0 1
        {node1({0, 0, 0}), node1({1, 0, 0}), node1({1, 1, 0})},                       // node 1, quad
        {node1({0, 0, 0}), node1({1, 1, 0}), node1({0, 1, 0})},
        {node0({1, 0, 0}), node0({1, 1, 0}), node0({0, 0, 0})},                       // node 2, fan:
        {node0({1, 1, 0}), node0({0, 1, 0}), node0({0, 0, 0})},                       // (v_i+1, v_i+2, v_0)
        {glm::vec3(0, 0, 9), glm::vec3(1, 0, 9), glm::vec3(0, 1, 9)},                 // node 3, strip:
        {glm::vec3(1, 0, 9), glm::vec3(1, 1, 9), glm::vec3(0, 1, 9)}};                // (v_i, v_i+1+i%2, v_i+2-i%2)                                           // reversed: 2nd of a strip
    ASSERT_EQ(scene.triangles.size(), expected.size());
    for (size_t t = 0; t < expected.size(); ++t) {
        expectNear(scene.triangles[t].v0, expected[t].v0, "triangle " + std::to_string(t) + " v0");
        expectNear(scene.triangles[t].v1, expected[t].v1, "triangle " + std::to_string(t) + " v1");
        expectNear(scene.triangles[t].v2, expected[t].v2, "triangle " + std::to_string(t) + " v2");
    }
    EXPECT_EQ(scene.materialIds, std::vector<uint32_t>(expected.size(), 0));
}

// A sparse accessor without a buffer view (zeros, then two substituted elements), normalized
// unsigned shorts (KHR_mesh_quantization) and normals turned by the inverse transpose.
TEST(GltfLoader, SparseNormalizedAccessorsAndNormals) {
    Gltf g;
    const int sparseIndices = g.view(std::vector<uint16_t>{1, 2});
    const int sparseValues = g.view(std::vector<float>{4, 0, 0, 0, 5, 0});
    g.accessors.push_back("{\"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\", \"sparse\": {\"count\": 2, "
                          "\"indices\": {\"bufferView\": " + std::to_string(sparseIndices) + ", \"componentType\": 5123}, "
                          "\"values\": {\"bufferView\": " + std::to_string(sparseValues) + "}}}");
    const int sparse = int(g.accessors.size() - 1);
    const int quantized = g.accessor(g.view(std::vector<uint16_t>{0, 0, 0, 65535, 0, 0, 0, 65535, 0, 0}), 5123, 3, "VEC3",
                                     ", \"normalized\": true");
    const int normals = g.positions({0, 0, 1, 0, 0, 1, 0, 0, 1});
    const std::string rest =
        "\"extensionsUsed\": [\"KHR_mesh_quantization\"], \"extensionsRequired\": [\"KHR_mesh_quantization\"], "
        "\"scenes\": [{\"nodes\": [0, 1]}], \"nodes\": [{\"mesh\": 0}, {\"mesh\": 1, \"scale\": [1, 1, 4]}], \"meshes\": ["
        "{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(sparse) + "}}]},"
        "{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(quantized) + ", \"NORMAL\": " +
        std::to_string(normals) + "}}]}]";
    const Scene scene = parse(g.json(rest));
    ASSERT_EQ(scene.triangles.size(), 2u);
    EXPECT_EQ(scene.triangles[0].v0, glm::vec3(0, 0, 0));
    EXPECT_EQ(scene.triangles[0].v1, glm::vec3(4, 0, 0));
    EXPECT_EQ(scene.triangles[0].v2, glm::vec3(0, 5, 0));
    EXPECT_EQ(scene.triangles[1].v1, glm::vec3(1, 0, 0));
    EXPECT_EQ(scene.triangles[1].v2, glm::vec3(0, 1, 0));
    ASSERT_EQ(scene.normals.size(), 2u);
    // None from the file: flat, as the spec says ((4, 0, 0) x (0, 5, 0) along +z).
    for (const glm::vec3& n : {scene.normals[0].n0, scene.normals[0].n1, scene.normals[0].n2}) EXPECT_EQ(n, glm::vec3(0, 0, 1));
    expectNear(scene.normals[1].n0, {0, 0, 1}, "normal");  // scaled along z, renormalised
}

// COLOR_0 (linear, as the spec says) in each form the spec allows: VEC3 FLOAT, VEC4 normalized
// UNSIGNED_BYTE (its alpha not used: a warning when it is not 1) and VEC3 normalized
// UNSIGNED_SHORT; a primitive without colours in a scene with some is white; another component
// type is a warning and no colours.
TEST(GltfLoader, VertexColoursFromColor0) {
    Gltf g;
    const int position = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const int floats = g.accessor(g.view(std::vector<float>{1, 0, 0, 0, 0.5f, 0, 0.25f, 0.75f, 1}), 5126, 3, "VEC3");
    const int bytes = g.accessor(g.view(std::vector<uint8_t>{255, 0, 51, 255, 0, 255, 0, 128, 0, 0, 255, 255}), 5121, 3,
                                 "VEC4", ", \"normalized\": true");
    const int shorts = g.accessor(g.view(std::vector<uint16_t>{65535, 0, 0, 0, 65535, 0, 0, 0, 13107}), 5123, 3, "VEC3",
                                  ", \"normalized\": true");
    const int ints = g.accessor(g.view(std::vector<uint8_t>{1, 2, 3, 4, 5, 6, 7, 8, 9, 0, 0, 0}), 5121, 3, "VEC3");
    auto primitive = [&](int colour) {
        return "{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(position) +
               (colour >= 0 ? ", \"COLOR_0\": " + std::to_string(colour) : std::string()) + "}}]}";
    };
    const std::string rest = "\"scenes\": [{\"nodes\": [0, 1, 2, 3, 4]}], \"nodes\": [{\"mesh\": 0}, {\"mesh\": 1}, "
                             "{\"mesh\": 2}, {\"mesh\": 3}, {\"mesh\": 4}], \"meshes\": [" +
                             primitive(-1) + ", " + primitive(floats) + ", " + primitive(bytes) + ", " + primitive(shorts) +
                             ", " + primitive(ints) + "]";
    ::testing::internal::CaptureStderr();
    const Scene scene = parse(g.json(rest));
    const std::string err = ::testing::internal::GetCapturedStderr();
    ASSERT_EQ(scene.triangles.size(), 5u);
    ASSERT_EQ(scene.colors.size(), 5u);
    for (const glm::vec3 c : {scene.colors[0].c0, scene.colors[0].c2, scene.colors[4].c1}) EXPECT_EQ(c, glm::vec3(1.0f));
    EXPECT_EQ(scene.colors[1].c0, glm::vec3(1, 0, 0));
    EXPECT_EQ(scene.colors[1].c2, glm::vec3(0.25f, 0.75f, 1));
    EXPECT_EQ(scene.colors[2].c0, glm::vec3(1.0f, 0.0f, float(51 / 255.0)));
    EXPECT_EQ(scene.colors[2].c1, glm::vec3(0.0f, 1.0f, 0.0f));
    EXPECT_EQ(scene.colors[2].c2, glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(scene.colors[3].c2, glm::vec3(0.0f, 0.0f, float(13107 / 65535.0)));
    EXPECT_NE(err.find("mesh 2 primitive 0: the alpha of COLOR_0 is not used"), std::string::npos) << err;
    EXPECT_NE(err.find("mesh 4 primitive 0: COLOR_0 of component type 5121"), std::string::npos) << err;
}

TEST(GltfLoader, MaterialsCameraAndPointLights) {
    Gltf g;
    const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    std::string meshes;
    for (int m = 0; m < 4; ++m)
        meshes += std::string(m ? ", " : "") + "{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(p) + "}" +
                  (m < 3 ? ", \"material\": " + std::to_string(m) : std::string()) + "}]}";
    const std::string rest =
        "\"extensionsUsed\": [\"KHR_lights_punctual\", \"KHR_materials_transmission\", \"KHR_materials_ior\", "
        "\"KHR_materials_emissive_strength\"], "
        "\"extensions\": {\"KHR_lights_punctual\": {\"lights\": [{\"type\": \"point\", \"color\": [1, 0.5, 0.25], "
        "\"intensity\": 40}]}}, "
        "\"cameras\": [{\"type\": \"orthographic\", \"orthographic\": {\"xmag\": 1, \"ymag\": 1, \"znear\": 0.1, \"zfar\": 10}}, "
        "{\"type\": \"perspective\", \"perspective\": {\"yfov\": 0.5, \"znear\": 0.1}}], "
        "\"materials\": ["
        "{\"name\": \"chrome\", \"pbrMetallicRoughness\": {\"baseColorFactor\": [0.2, 0.4, 0.6, 1], \"metallicFactor\": 1, "
        "\"roughnessFactor\": 0}},"
        "{\"pbrMetallicRoughness\": {\"baseColorFactor\": [0.9, 1, 0.8, 1], \"metallicFactor\": 0}, \"extensions\": {"
        "\"KHR_materials_transmission\": {\"transmissionFactor\": 1}, \"KHR_materials_ior\": {\"ior\": 1.33}}},"
        "{\"pbrMetallicRoughness\": {\"baseColorFactor\": [0.5, 0.5, 0.5, 1], \"metallicFactor\": 0}, \"emissiveFactor\": [1, 0.5, 0], "
        "\"extensions\": {\"KHR_materials_emissive_strength\": {\"emissiveStrength\": 8}}}], "
        "\"scenes\": [{\"nodes\": [0, 1, 2, 3, 4, 5, 6]}], \"nodes\": [{\"mesh\": 0}, {\"mesh\": 1}, {\"mesh\": 2}, {\"mesh\": 3}, "
        "{\"camera\": 0}, {\"camera\": 1, \"translation\": [0, 1, 10]}, "
        "{\"translation\": [3, 4, 5], \"extensions\": {\"KHR_lights_punctual\": {\"light\": 0}}}], "
        "\"meshes\": [" + meshes + "]";
    const Scene scene = parse(g.json(rest));
    ASSERT_EQ(scene.materials.size(), 4u);  // gpurt's default (mesh 3 has none), then the three
    EXPECT_EQ(scene.materialIds, (std::vector<uint32_t>{1, 2, 3, 0}));
    const Material& chrome = scene.materials[1];
    EXPECT_EQ(chrome.name, "chrome");
    EXPECT_EQ(chrome.model, 2);  // GPURT_MODEL_GLTF: glTF's metallic-roughness model, factors as given
    EXPECT_EQ(chrome.diffuse, glm::vec3(0.2f, 0.4f, 0.6f));
    EXPECT_EQ(chrome.metallic, 1.0f);
    EXPECT_EQ(chrome.roughness, 0.0f);
    EXPECT_EQ(chrome.ior, 0.0f);  // no KHR_materials_ior: 1.5, F0 0.04
    EXPECT_EQ(chrome.transmission, glm::vec3(0.0f));
    const Material& glass = scene.materials[2];  // the glTF model's rough dielectric
    EXPECT_EQ(glass.model, 2);
    EXPECT_FLOAT_EQ(glass.ior, 1.33f);
    EXPECT_EQ(glass.transmission, glm::vec3(1.0f));  // the factor; the tint is the base colour
    EXPECT_EQ(glass.diffuse, glm::vec3(0.9f, 1.0f, 0.8f));
    EXPECT_EQ(scene.materials[3].emission, glm::vec3(8.0f, 4.0f, 0.0f));
    EXPECT_EQ(scene.materials[3].diffuse, glm::vec3(0.5f));
    ASSERT_TRUE(scene.camera.has_value());  // the first perspective one
    EXPECT_EQ(scene.camera->eye, glm::vec3(0, 1, 10));
    EXPECT_EQ(scene.camera->target, glm::vec3(0, 1, 9));
    EXPECT_EQ(scene.camera->up, glm::vec3(0, 1, 0));
    EXPECT_FLOAT_EQ(scene.camera->fovy, float(0.5 * 180.0 / 3.14159265358979323846));
    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_EQ(scene.lights[0].position, glm::vec3(3, 4, 5));
    EXPECT_EQ(scene.lights[0].color, glm::vec3(1, 0.5f, 0.25f));
    EXPECT_FLOAT_EQ(scene.lights[0].intensity, float(40.0 / std::numbers::pi));  // the Sample Viewer's units
    EXPECT_EQ(scene.lights[0].kind, LightKind::Point);
    // The emissive material glows but is no light of the scene's (without its point light, the
    // default light would stay on).
    EXPECT_FALSE(scene.materials[3].emissionIsLight);
    Scene unlit = scene;
    unlit.lights.clear();
    EXPECT_FALSE(hasOwnLight(unlit));
}

// KHR_lights_punctual's spot and directional lights shine down their node's -z (a node turned -90
// degrees about x points them down -y), in the glTF Sample Viewer's units (gpurt's over pi); a
// spot's cone as given, its range scaled with its node.
TEST(GltfLoader, SpotAndDirectionalLights) {
    Gltf g;
    const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const std::string rest =
        "\"extensionsUsed\": [\"KHR_lights_punctual\"], "
        "\"extensions\": {\"KHR_lights_punctual\": {\"lights\": ["
        "{\"type\": \"spot\", \"intensity\": 10, \"range\": 4, \"spot\": {\"innerConeAngle\": 0.2, \"outerConeAngle\": 0.5}},"
        "{\"type\": \"directional\", \"color\": [1, 0.9, 0.8], \"intensity\": 3}]}}, "
        "\"scenes\": [{\"nodes\": [0, 1, 2]}], \"nodes\": [{\"mesh\": 0}, "
        "{\"translation\": [1, 5, 2], \"rotation\": [-0.70710678, 0, 0, 0.70710678], \"scale\": [2, 2, 2], "
        "\"extensions\": {\"KHR_lights_punctual\": {\"light\": 0}}}, "
        "{\"extensions\": {\"KHR_lights_punctual\": {\"light\": 1}}}], "
        "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(p) + "}}]}]";
    const Scene scene = parse(g.json(rest));
    ASSERT_EQ(scene.lights.size(), 2u);
    const Light& spot = scene.lights[0];
    EXPECT_EQ(spot.kind, LightKind::Spot);
    EXPECT_EQ(spot.position, glm::vec3(1, 5, 2));
    EXPECT_NEAR(spot.direction.x, 0.0f, 1e-6f);  // -90 degrees about x takes -z to -y
    EXPECT_NEAR(spot.direction.y, -1.0f, 1e-6f);
    EXPECT_NEAR(spot.direction.z, 0.0f, 1e-6f);
    EXPECT_FLOAT_EQ(spot.innerCone, 0.2f);
    EXPECT_FLOAT_EQ(spot.outerCone, 0.5f);
    EXPECT_FLOAT_EQ(spot.range, 8.0f);  // the node's scale of 2
    EXPECT_FLOAT_EQ(spot.intensity, float(10.0 / std::numbers::pi));
    const Light& sun = scene.lights[1];
    EXPECT_EQ(sun.kind, LightKind::Directional);
    EXPECT_EQ(sun.direction, glm::vec3(0, 0, -1));
    EXPECT_EQ(sun.color, glm::vec3(1, 0.9f, 0.8f));
    EXPECT_FLOAT_EQ(sun.intensity, float(3.0 / std::numbers::pi));
}

// KHR_materials_unlit: the unlit model (glsl/common/material.h GPURT_MODEL_UNLIT) with the base
// colour; its emission is not used (a warning), and it casts no shadow.
TEST(GltfLoader, UnlitMaterials) {
    Gltf g;
    const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const Scene scene = parse(g.json(
        "\"extensionsUsed\": [\"KHR_materials_unlit\"], \"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0}], "
        "\"materials\": [{\"pbrMetallicRoughness\": {\"baseColorFactor\": [0.2, 0.4, 0.6, 1]}, \"emissiveFactor\": [1, 1, 1], "
        "\"extensions\": {\"KHR_materials_unlit\": {}}}], "
        "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(p) + "}, \"material\": 0}]}]"));
    ASSERT_EQ(scene.materials.size(), 2u);
    const Material& unlit = scene.materials[1];
    EXPECT_EQ(unlit.model, 3);
    EXPECT_EQ(unlit.diffuse, glm::vec3(0.2f, 0.4f, 0.6f));
    EXPECT_EQ(unlit.emission, glm::vec3(0.0f));
    EXPECT_TRUE(unlit.castsNoShadow());
    EXPECT_FALSE(hasOwnLight(scene));
}

// alphaMode: MASK with its alphaCutoff (default 0.5), BLEND; alpha is baseColorFactor[3] (no
// texture here); OPAQUE and no mode are opaque. A cutoff outside [0, 1] is refused naming the
// material.
std::string alphaTriangle(const std::string& material) {
    Gltf g;
    const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    return g.json("\"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0}], \"materials\": [" + material +
                  "], \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(p) +
                  "}, \"material\": 0}]}]");
}

TEST(GltfLoader, AlphaModesAndCutoff) {
    const std::string base = "\"pbrMetallicRoughness\": {\"baseColorFactor\": [1, 1, 1, 0.25]}";
    const Scene mask = parse(alphaTriangle("{" + base + ", \"alphaMode\": \"MASK\", \"alphaCutoff\": 0.3}"));
    EXPECT_EQ(mask.materials[1].alphaMode, 1);  // GPURT_ALPHA_MASK
    EXPECT_EQ(mask.materials[1].alphaFactor, 0.25f);
    EXPECT_EQ(mask.materials[1].alphaCutoff, 0.3f);
    EXPECT_FALSE(mask.materials[1].alphaTexture.given());
    const Scene defaultCutoff = parse(alphaTriangle("{" + base + ", \"alphaMode\": \"MASK\"}"));
    EXPECT_EQ(defaultCutoff.materials[1].alphaCutoff, 0.5f);
    const Scene blend = parse(alphaTriangle("{" + base + ", \"alphaMode\": \"BLEND\"}"));
    EXPECT_EQ(blend.materials[1].alphaMode, 2);  // GPURT_ALPHA_BLEND
    EXPECT_EQ(blend.materials[1].alphaFactor, 0.25f);
    EXPECT_EQ(parse(alphaTriangle("{" + base + ", \"alphaMode\": \"OPAQUE\"}")).materials[1].alphaMode, 0);
    EXPECT_EQ(parse(alphaTriangle("{" + base + "}")).materials[1].alphaMode, 0);
    for (const char* cutoff : {"-0.5", "1.5", "1e38"}) {
        const std::string message =
            test::refusalOf([&] { parseGltf(alphaTriangle("{\"name\": \"leaves\", " + base +
                                                          ", \"alphaMode\": \"MASK\", \"alphaCutoff\": " + cutoff + "}"),
                                            "bad.gltf", fs::temp_directory_path()); },
                            "bad.gltf: ");
        EXPECT_NE(message.find("'leaves'"), std::string::npos) << cutoff << ": " << message;
        EXPECT_NE(message.find("alphaCutoff"), std::string::npos) << cutoff << ": " << message;
    }
}

// doubleSided per material, false by default (the glTF spec): such a material culls its back
// faces unless it is transmissive (glass).
TEST(GltfLoader, DoubleSidedPerMaterialDefaultFalse) {
    Gltf g;
    const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const std::string prim = "{\"attributes\": {\"POSITION\": " + std::to_string(p) + "}, \"material\": ";
    const Scene scene = parse(g.json(
        "\"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0}], \"materials\": [{}, {\"doubleSided\": true}, "
        "{\"doubleSided\": false}, {\"extensions\": {\"KHR_materials_transmission\": {\"transmissionFactor\": 1}}}], "
        "\"extensionsUsed\": [\"KHR_materials_transmission\"], "
        "\"meshes\": [{\"primitives\": [" + prim + "0}, " + prim + "1}, " + prim + "2}, " + prim + "3}]}]"));
    ASSERT_EQ(scene.materials.size(), 5u);  // gpurt's default, then the four in order of use
    EXPECT_TRUE(scene.materials[0].doubleSided) << "gpurt's default material";
    EXPECT_FALSE(scene.materials[1].doubleSided) << "glTF's default";
    EXPECT_TRUE(scene.materials[1].cullsBackFaces());
    EXPECT_TRUE(scene.materials[2].doubleSided);
    EXPECT_FALSE(scene.materials[2].cullsBackFaces());
    EXPECT_FALSE(scene.materials[3].doubleSided);
    EXPECT_FALSE(scene.materials[4].doubleSided);
    EXPECT_GT(scene.materials[4].ior, 0.0f);
    EXPECT_FALSE(scene.materials[4].cullsBackFaces()) << "glass is never culled";
}

// The front of a triangle is counter-clockwise in its node's frame; a node whose transform has a
// negative determinant (a mirror) keeps its front faces on the same side of the surface (the glTF
// spec: its winding turns clockwise), so the scene's triangle, counter-clockwise at the front,
// has its corners 1 and 2 swapped: its cross(e1, e2) points along the mirrored normal.
TEST(GltfLoader, MirroredNodesKeepTheirFrontFaces) {
    for (const char* node : {"{\"mesh\": 0}", "{\"mesh\": 0, \"scale\": [-1, 1, 1]}",
                             "{\"mesh\": 0, \"scale\": [1, -1, -1]}", "{\"mesh\": 0, \"scale\": [1, 1, -1]}"}) {
        SCOPED_TRACE(node);
        Gltf g;
        const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});  // counter-clockwise seen from +z
        const Scene scene = parse(g.json(std::string("\"scenes\": [{\"nodes\": [0]}], \"nodes\": [") + node +
                                         "], \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " +
                                         std::to_string(p) + "}}]}]"));
        ASSERT_EQ(scene.triangles.size(), 1u);
        const Triangle& t = scene.triangles[0];
        const glm::vec3 front = glm::cross(t.v1 - t.v0, t.v2 - t.v0);
        // The local normal +z through the inverse transpose of diag(sx, sy, sz): +z times sz.
        const float sz = std::string(node).find("-1]") != std::string::npos ? -1.0f : 1.0f;
        EXPECT_EQ(front.x, 0.0f);
        EXPECT_EQ(front.y, 0.0f);
        EXPECT_GT(front.z * sz, 0.0f) << front.z;
        EXPECT_EQ(t.v0, glm::vec3(0.0f));
    }
}

// With a baseColorTexture, alpha is baseColorFactor[3] times the texture's A.
TEST(GltfLoader, AlphaTextureIsTheBaseColourTexturesA) {
    std::ifstream in("tests/assets/textures/quad_separate.gltf");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t at = text.find("\"alphaMode\": \"OPAQUE\"");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, std::strlen("\"alphaMode\": \"OPAQUE\""), "\"alphaMode\": \"BLEND\"");
    const Scene scene = parseGltf(text, "quad_separate.gltf", "tests/assets/textures");
    const Material& m = scene.materials[scene.materialIds[0]];
    EXPECT_EQ(m.alphaMode, 2);
    ASSERT_GE(m.diffuseTexture, 0);
    EXPECT_EQ(m.alphaTexture.texture, m.diffuseTexture);
    EXPECT_EQ(m.alphaTexture.channel, 3);
}

// The message of the InputError parsing `text` throws (Refusal.h).
std::string refusal(const std::string& text, const fs::path& folder = fs::temp_directory_path()) {
    return test::refusalOf([&] { parseGltf(text, "bad.gltf", folder); }, "bad.gltf: ");
}

TEST(GltfLoader, RefusesWhatIsNotAUsableGltf) {
    auto triangle = [](const std::string& mode, const std::string& indices) {
        Gltf g;
        const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
        const int i = g.indices(std::vector<uint16_t>{0, 1, 2}, 5123);
        (void)i;
        return g.json("\"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0}], \"meshes\": [{\"primitives\": [{"
                      "\"attributes\": {\"POSITION\": " + std::to_string(p) + "}" + mode + indices + "}]}]");
    };
    EXPECT_NO_THROW(parse(triangle("", ", \"indices\": 1")));
    EXPECT_REFUSED("{\"meshes\": []}", "bad.gltf: ");  // JSON, no asset
    EXPECT_REFUSED("glTF\x02\0\0\0\x10\0\0\0", "bad.gltf: ");  // a GLB header that lies
    EXPECT_REFUSED("not json at all", "bad.gltf: ");
    EXPECT_REFUSED(triangle(", \"mode\": 9", ""),
                   "mode 9 is no glTF primitive mode");  // points and lines: a warning
    EXPECT_REFUSED(triangle("", ", \"indices\": 7"), "indices accessor");
    // Indices out of range, a view past its buffer, elements past their view.
    {
        Gltf g;
        const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
        const int i = g.indices(std::vector<uint16_t>{0, 1, 3}, 5123);
        EXPECT_REFUSED(g.json("\"nodes\": [{\"mesh\": 0}], \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " +
                              std::to_string(p) + "}, \"indices\": " + std::to_string(i) + "}]}]"),
                       "index 3 out of range (3 vertices)");
        Gltf h = g;
        h.accessors[0] = "{\"bufferView\": 0, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\"}";
        EXPECT_REFUSED(h.json("\"nodes\": [{\"mesh\": 0}], \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0}}]}]"),
                       "4 elements do not fit buffer view 0");
        Gltf k = g;
        k.views[0] = "{\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": 4000}";
        EXPECT_REFUSED(k.json("\"nodes\": [{\"mesh\": 0}], \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0}}]}]"),
                       "bad.gltf: ");
    }
    {  // A position that is no number, a node that is its own ancestor.
        Gltf g;
        const float nan = std::nanf("");
        const int p = g.positions({0, 0, 0, 1, nan, 0, 0, 1, 0});
        EXPECT_REFUSED(g.json("\"nodes\": [{\"mesh\": 0}], \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " +
                              std::to_string(p) + "}}]}]"),
                       "vertex 1 is not finite");
        EXPECT_REFUSED(g.json("\"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"children\": [1]}, {\"children\": [0]}], "
                              "\"meshes\": []"),
                       "bad.gltf: ");
    }
    // External buffers: missing, or shorter than they say.
    const fs::path folder = fs::temp_directory_path() / ("gpurt-gltf-" + std::to_string(::getpid()));
    fs::create_directories(folder);
    const std::string external = "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [{\"byteLength\": 36, \"uri\": \"tri.bin\"}], "
                                 "\"bufferViews\": [{\"buffer\": 0, \"byteLength\": 36}], \"accessors\": [{\"bufferView\": 0, "
                                 "\"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\"}], \"nodes\": [{\"mesh\": 0}], "
                                 "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0}}]}]}";
    const std::string missing = refusal(external, folder);
    EXPECT_NE(missing.find("tri.bin"), std::string::npos) << missing;
    std::ofstream(folder / "tri.bin", std::ios::binary) << std::string(20, '\0');
    const std::string shortBuffer = refusal(external, folder);
    EXPECT_NE(shortBuffer.find("bad.gltf: "), std::string::npos) << shortBuffer;
    std::ofstream(folder / "tri.bin", std::ios::binary) << std::string(36, '\0');
    EXPECT_NO_THROW(parseGltf(external, "good.gltf", folder));
    fs::remove_all(folder);
}

// A 2 x 2 PNG of the colour (200, 90, 230): a normal map for the tangent tests.
const char kNormalMapPng[] =
    "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAIAAAACCAIAAAD91JpzAAAAEElEQVR4nGM4EfUMiBggFAA4dggh9f1xhQAAAABJRU5ErkJggg==";

// A quad in z = 0 (NORMAL +z, TEXCOORD_0) whose primitive has TANGENT `tangent` (an accessor, or
// -1: none) and material `material` (0: with a normal map, 1: without); one node per entry of
// `nodes` (its mesh and transform).
std::string tangentQuads(Gltf& g, const std::vector<std::string>& meshes, const std::vector<std::string>& nodes) {
    std::string meshList, nodeList, roots;
    for (const std::string& m : meshes) meshList += (meshList.empty() ? "" : ", ") + m;
    for (size_t k = 0; k < nodes.size(); ++k) {
        nodeList += (k ? ", " : "") + nodes[k];
        roots += (k ? ", " : "") + std::to_string(k);
    }
    return g.json("\"extensionsUsed\": [\"KHR_mesh_quantization\"], \"scenes\": [{\"nodes\": [" + roots +
                  "]}], \"nodes\": [" + nodeList + "], \"meshes\": [" + meshList +
                  "], \"images\": [{\"uri\": \"" + kNormalMapPng + "\"}], \"textures\": [{\"source\": 0}], "
                  "\"materials\": [{\"normalTexture\": {\"index\": 0}}, {}]");
}

struct TangentQuad {
    int position, normal, texcoord, indices;
    explicit TangentQuad(Gltf& g) {
        position = g.positions({-1, 1, 0, -1, -1, 0, 1, -1, 0, 1, 1, 0});
        normal = g.positions({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1});
        texcoord = g.accessor(g.view(std::vector<float>{0, 0, 0, 1, 1, 1, 1, 0}), 5126, 4, "VEC2");
        indices = g.indices(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, 5123);
    }
    std::string mesh(int tangent, int material, bool normals = true) const {
        return "{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(position) +
               (normals ? ", \"NORMAL\": " + std::to_string(normal) : std::string()) + ", \"TEXCOORD_0\": " +
               std::to_string(texcoord) + (tangent >= 0 ? ", \"TANGENT\": " + std::to_string(tangent) : std::string()) +
               "}, \"indices\": " + std::to_string(indices) + ", \"material\": " + std::to_string(material) + "}]}";
    }
};

// TANGENT (issue 22): per corner, normalised, w its sign (0: +1); through the node's transform,
// a mirroring one turning w over; normalized BYTE (KHR_mesh_quantization) as the spec converts it;
// a zero tangent kept as zero (the hit falls back to generated tangents). Not stored for a material
// without a normal map (nothing to frame; no warning, as for texture coordinates no texture
// uses), nor without NORMAL (the spec ignores tangents then: a warning).
TEST(GltfLoader, TangentsFromTheTangentAttribute) {
    Gltf g;
    const TangentQuad quad(g);
    // Corners: scaled, w 0.5, w -3, zero.
    const int floats = g.accessor(g.view(std::vector<float>{0, 2, 0, 1, 0, 1, 0, 0.5f, 0, 1, 0, -3, 0, 0, 0, 1}), 5126, 4,
                                  "VEC4");
    const int bytes = g.accessor(g.view(std::vector<int8_t>{127, 0, 0, -127, 127, 0, 0, -127, 0, -127, 0, 127, 0, 0, 127, 0}),
                                 5120, 4, "VEC4", ", \"normalized\": true");
    ::testing::internal::CaptureStderr();
    const Scene scene = parse(tangentQuads(
        g, {quad.mesh(floats, 0), quad.mesh(floats, 1), quad.mesh(bytes, 0), quad.mesh(floats, 0, false)},
        {"{\"mesh\": 0}", "{\"mesh\": 0, \"scale\": [-1, 2, 1]}", "{\"mesh\": 1}", "{\"mesh\": 2}", "{\"mesh\": 3}"}));
    const std::string err = ::testing::internal::GetCapturedStderr();
    ASSERT_EQ(scene.triangles.size(), 10u);
    ASSERT_EQ(scene.tangents.size(), 10u);
    // Triangle 0 is corners 0, 1, 2; triangle 1 corners 0, 2, 3.
    EXPECT_EQ(scene.tangents[0].t0, glm::vec4(0, 1, 0, 1));
    EXPECT_EQ(scene.tangents[0].t1, glm::vec4(0, 1, 0, 1));
    EXPECT_EQ(scene.tangents[0].t2, glm::vec4(0, 1, 0, -1));
    EXPECT_EQ(scene.tangents[1].t2, glm::vec4(0, 0, 0, 1));
    // Mirrored in x, stretched in y: the tangent (0, 1, 0) stays, its handedness turns over; the
    // mirrored triangle's corners are 0, 2, 1 (its front face kept, as the spec says).
    EXPECT_EQ(scene.tangents[2].t0, glm::vec4(0, 1, 0, -1));
    EXPECT_EQ(scene.tangents[2].t1, glm::vec4(0, 1, 0, 1));
    EXPECT_EQ(scene.tangents[2].t2, glm::vec4(0, 1, 0, -1));
    // No normal map: none.
    for (size_t t : {4u, 5u}) EXPECT_EQ(scene.tangents[t].t0, glm::vec4(0.0f)) << t;
    // Normalized bytes: 127 is 1, -127 is -1, 0 is +1's sign.
    EXPECT_EQ(scene.tangents[6].t0, glm::vec4(1, 0, 0, -1));
    EXPECT_EQ(scene.tangents[6].t2, glm::vec4(0, -1, 0, 1));
    EXPECT_EQ(scene.tangents[7].t2, glm::vec4(0, 0, 1, 1));
    // Without NORMAL: none, and said.
    for (size_t t : {8u, 9u}) EXPECT_EQ(scene.tangents[t].t1, glm::vec4(0.0f)) << t;
    EXPECT_NE(err.find("mesh 3 primitive 0: TANGENT is not used (no NORMAL"), std::string::npos) << err;
    EXPECT_EQ(err.find("TANGENT is not used;"), std::string::npos) << "the old warning: " << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;

    // A scene whose TANGENT only meets materials without a normal map has no tangents at all.
    Gltf plain;
    const TangentQuad other(plain);
    const int unused = plain.accessor(plain.view(std::vector<float>(16, 0.5f)), 5126, 4, "VEC4");
    EXPECT_TRUE(parse(tangentQuads(plain, {other.mesh(unused, 1)}, {"{\"mesh\": 0}"})).tangents.empty());
}

// A TANGENT accessor that is not VEC4 of FLOAT or normalized BYTE / SHORT with one element per
// vertex: exit 1 naming the file and the primitive.
TEST(GltfLoader, RefusesTangentsOfTheWrongTypeOrCount) {
    struct Case {
        int componentType;
        size_t count;
        const char* type;
        const char* extra;
        const char* message;
    };
    const Case cases[] = {
        {5126, 4, "VEC3", "", "mesh 0 primitive 0: TANGENT (accessor 4) is not VEC4 of one per vertex"},
        {5126, 3, "VEC4", "", "mesh 0 primitive 0: TANGENT (accessor 4) is not VEC4 of one per vertex"},
        {5121, 4, "VEC4", ", \"normalized\": true",
         "mesh 0 primitive 0: TANGENT (accessor 4) of component type 5121 (not FLOAT or normalized BYTE or SHORT)"},
        {5122, 4, "VEC4", "", "mesh 0 primitive 0: TANGENT (accessor 4) of component type 5122"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.message);
        Gltf g;
        const TangentQuad quad(g);
        const int tangent = g.accessor(g.view(std::vector<float>(16, 0.5f)), c.componentType, c.count, c.type, c.extra);
        ASSERT_EQ(tangent, 4);
        const std::string message = refusal(tangentQuads(g, {quad.mesh(tangent, 0)}, {"{\"mesh\": 0}"}));
        EXPECT_NE(message.find(c.message), std::string::npos) << message;
    }
    Gltf g;
    const TangentQuad quad(g);
    EXPECT_NE(refusal(tangentQuads(g, {quad.mesh(9, 0)}, {"{\"mesh\": 0}"})).find("mesh 0 primitive 0 TANGENT: accessor 9 does not exist"),
              std::string::npos);
}

// Hostile material values (issue 22): texCoord indices no file can have, transforms that are not
// numbers, scales and strengths out of range: exit 1 naming the material and the slot.
TEST(GltfLoaderMaterials, RefusesHostileTextureSlots) {
    auto withMaterial = [](const std::string& material) {
        Gltf g;
        const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
        return g.json("\"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0}], \"meshes\": [{\"primitives\": [{"
                      "\"attributes\": {\"POSITION\": " + std::to_string(p) + "}, \"material\": 0}]}], "
                      "\"images\": [{\"uri\": \"missing.png\"}], \"textures\": [{\"source\": 0}], "
                      "\"materials\": [" + material + "]");
    };
    EXPECT_NE(refusal(withMaterial("{\"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 0, \"texCoord\": 100000}}}"))
                  .find("material 0"),
              std::string::npos);
    EXPECT_NE(refusal(withMaterial("{\"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 0, \"texCoord\": 100000}}}"))
                  .find("texCoord 100000 out of range"),
              std::string::npos);
    EXPECT_NE(refusal(withMaterial("{\"normalTexture\": {\"index\": 0, \"extensions\": {\"KHR_texture_transform\": "
                                   "{\"scale\": [1, \"x\"]}}}}"))
                  .find("normalTexture KHR_texture_transform scale is not 2 numbers"),
              std::string::npos);
    EXPECT_NE(refusal(withMaterial("{\"occlusionTexture\": {\"index\": 0, \"strength\": 2}}")).find("strength must be in [0, 1]"),
              std::string::npos);
    EXPECT_NE(refusal(withMaterial("{\"pbrMetallicRoughness\": {\"roughnessFactor\": 1.5}}")).find("roughnessFactor"),
              std::string::npos);
}

// KHR_materials_clearcoat, KHR_materials_specular and KHR_materials_sheen (TransmissionQuad.h's
// window with the extensions added): their factors, colours and maps as given (each map's channel
// as the extensions say: clearcoat R, its roughness G, specular A, sheen roughness A, the colours
// textures), the coat's
// normal map with its scale, through the window's shared texture coordinates, and no warning
// about them; values outside their ranges are refused naming the material.
// A textureInfo of texture 0 through the window's TEXCOORD_1 turned as its transmissionTexture is
// (TransmissionQuad.h), for the extensions' slots.
const std::string kTurnedSlot = "{\"index\": 0, \"texCoord\": 1, \"extensions\": {\"KHR_texture_transform\": "
                                "{\"rotation\": 1.5707963267948966, \"offset\": [0, 1]}}}";

// TransmissionQuad's window (transmission 0.75, the texture `image`) with more material extensions
// beside its KHR_materials_transmission.
std::string windowWith(const std::string& extensions, const std::string& image = "bands.bmp") {
    std::string text = test::TransmissionQuad::gltf(0.75, image);
    const std::string at = "\"KHR_materials_transmission\": {";
    text.replace(text.find(at), at.size(), extensions + ", " + at);
    return text;
}

TEST(GltfLoaderMaterials, ClearcoatSpecularAndSheenAreRead) {
    const fs::path dir = fs::temp_directory_path() / ("gpurt-layers-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "bands.bmp", std::ios::binary) << test::TransmissionQuad::image();
    const std::string info = kTurnedSlot;
    const std::string layers =
        "\"KHR_materials_clearcoat\": {\"clearcoatFactor\": 0.75, \"clearcoatRoughnessFactor\": 0.25, "
        "\"clearcoatTexture\": " + info + ", \"clearcoatRoughnessTexture\": " + info +
        ", \"clearcoatNormalTexture\": {\"index\": 0, \"texCoord\": 1, \"scale\": 0.5, \"extensions\": "
        "{\"KHR_texture_transform\": {\"rotation\": 1.5707963267948966, \"offset\": [0, 1]}}}}, "
        "\"KHR_materials_specular\": {\"specularFactor\": 0.5, \"specularColorFactor\": [1, 0.5, 2], "
        "\"specularTexture\": " + info + ", \"specularColorTexture\": " + info + "}, "
        "\"KHR_materials_sheen\": {\"sheenColorFactor\": [1, 0.5, 0.25], \"sheenRoughnessFactor\": 0.5, "
        "\"sheenColorTexture\": " + info + ", \"sheenRoughnessTexture\": " + info + "}";
    ::testing::internal::CaptureStderr();
    const Scene scene = parseGltf(windowWith(layers), "window.gltf", dir);
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    for (const char* name : {"clearcoat", "specular", "not used", "not read"}) EXPECT_EQ(warnings.find(name), std::string::npos) << warnings;
    ASSERT_EQ(scene.materials.size(), 2u);
    const Material& m = scene.materials[1];
    EXPECT_EQ(m.clearcoat, 0.75f);
    EXPECT_EQ(m.clearcoatRoughness, 0.25f);
    EXPECT_EQ(m.clearcoatTexture.texture, 0);
    EXPECT_EQ(m.clearcoatTexture.channel, 0);  // R
    EXPECT_EQ(m.clearcoatRoughnessTexture.texture, 0);
    EXPECT_EQ(m.clearcoatRoughnessTexture.channel, 1);  // G
    EXPECT_EQ(m.clearcoatNormalTexture, 0);
    EXPECT_EQ(m.clearcoatNormalScale, 0.5f);
    EXPECT_EQ(m.specularFactor, 0.5f);
    EXPECT_EQ(m.specularColor, glm::vec3(1.0f, 0.5f, 2.0f));
    EXPECT_EQ(m.specularTexture.texture, 0);
    EXPECT_EQ(m.specularTexture.channel, 3);  // A
    EXPECT_EQ(m.specularColorTexture, 0);
    EXPECT_EQ(m.sheenColor, glm::vec3(1.0f, 0.5f, 0.25f));
    EXPECT_EQ(m.sheenRoughness, 0.5f);
    EXPECT_EQ(m.sheenColorTexture, 0);
    EXPECT_EQ(m.sheenRoughnessTexture.texture, 0);
    EXPECT_EQ(m.sheenRoughnessTexture.channel, 3);  // A
    EXPECT_TRUE(m.hasClearcoat());
    EXPECT_TRUE(m.hasSpecularLayer());
    EXPECT_TRUE(m.hasSheen());
    EXPECT_EQ(scene.textures.size(), 1u);  // one image, one texture, every slot
    // Without the extensions: no layer.
    const Scene plain = parseGltf(test::TransmissionQuad::gltf(0.75, "bands.bmp"), "window.gltf", dir);
    EXPECT_FALSE(plain.materials[1].hasClearcoat());
    EXPECT_FALSE(plain.materials[1].hasSpecularLayer());
    for (const auto& [bad, part] : std::vector<std::pair<std::string, std::string>>{
             {"\"KHR_materials_clearcoat\": {\"clearcoatFactor\": 1.5}", "material 0: clearcoatFactor and clearcoatRoughnessFactor must be in [0, 1]"},
             {"\"KHR_materials_clearcoat\": {\"clearcoatFactor\": 1, \"clearcoatRoughnessFactor\": -1}", "clearcoatRoughnessFactor must be in [0, 1]"},
             {"\"KHR_materials_clearcoat\": {\"clearcoatFactor\": 1, \"clearcoatTexture\": {\"texCoord\": 1}}", "material 0 ('window'): clearcoatTexture has no texture index"},
             {"\"KHR_materials_specular\": {\"specularFactor\": 2}", "material 0: specularFactor must be in [0, 1]"},
             {"\"KHR_materials_specular\": {\"specularColorFactor\": [1, 1]}", "material 0: specularColorFactor is not 3 numbers"},
             {"\"KHR_materials_specular\": {\"specularColorFactor\": [1, -1, 1]}", "specularColorFactor must be 3 numbers in [0, 1000]"},
             {"\"KHR_materials_sheen\": {\"sheenColorFactor\": [1, 2, 1]}", "material 0: sheenColorFactor must be 3 numbers in [0, 1]"},
             {"\"KHR_materials_sheen\": {\"sheenColorFactor\": 1}", "sheenColorFactor is not 3 numbers"},
             {"\"KHR_materials_sheen\": {\"sheenColorFactor\": [1, 1, 1], \"sheenRoughnessFactor\": 3}", "sheenRoughnessFactor must be in [0, 1]"}}) {
        const std::string message = test::refusalOf([&] { parseGltf(windowWith(bad), "window.gltf", dir); }, "window.gltf: ");
        EXPECT_NE(message.find(part), std::string::npos) << message;
    }
    fs::remove_all(dir);
}

// KHR_materials_volume: thicknessFactor, attenuationColor and attenuationDistance are read (the
// defaults without: a thin wall, white, infinite; the transmission a thin wall's without a
// thickness above 0), the absorption is -ln(colour) / distance, the
// thicknessTexture is a warning naming the material (rays measure the distance inside), and bad
// values are refused naming the material.
TEST(GltfLoaderMaterials, VolumeIsRead) {
    const fs::path dir = fs::temp_directory_path() / ("gpurt-volume-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "bands.bmp", std::ios::binary) << test::TransmissionQuad::image();
    ::testing::internal::CaptureStderr();
    const Scene scene = parseGltf(windowWith("\"KHR_materials_volume\": {\"thicknessFactor\": 0.5, \"attenuationColor\": "
                                             "[0.5, 0.25, 1], \"attenuationDistance\": 2, \"thicknessTexture\": {\"index\": 0}}"),
                                  "window.gltf", dir);
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(warnings.find("material 0 ('window'): KHR_materials_volume's thicknessTexture is not used"), std::string::npos)
        << warnings;
    const Material& m = scene.materials[1];
    EXPECT_EQ(m.thickness, 0.5f);
    EXPECT_EQ(m.attenuationColor, glm::vec3(0.5f, 0.25f, 1.0f));
    EXPECT_EQ(m.attenuationDistance, 2.0f);
    ASSERT_TRUE(m.hasVolume());
    EXPECT_NEAR(m.absorption().x, std::log(2.0) / 2.0, 1e-6);
    EXPECT_NEAR(m.absorption().y, std::log(4.0) / 2.0, 1e-6);
    EXPECT_EQ(m.absorption().z, 0.0f);
    const Material thin = parseGltf(windowWith("\"KHR_materials_volume\": {\"attenuationColor\": [0.5, 0.5, 0.5]}"),
                                    "window.gltf", dir).materials[1];
    EXPECT_EQ(thin.thickness, 0.0f);
    EXPECT_EQ(thin.attenuationDistance, std::numeric_limits<float>::infinity());
    EXPECT_FALSE(thin.hasVolume());
    EXPECT_EQ(thin.absorption(), glm::vec3(0.0f));
    // Transmission is through a thin wall without a volume of thickness above 0 (the extensions'
    // default), a solid with one.
    EXPECT_FALSE(m.thinWalled);
    EXPECT_TRUE(thin.thinWalled && thin.thin());
    const Material bare = parseGltf(test::TransmissionQuad::gltf(0.75, "bands.bmp"), "window.gltf", dir).materials[1];
    EXPECT_TRUE(bare.thinWalled && bare.thin());
    for (const auto& [bad, part] : std::vector<std::pair<std::string, std::string>>{
             {"\"KHR_materials_volume\": {\"thicknessFactor\": -1}", "material 0: thicknessFactor must be a number >= 0"},
             {"\"KHR_materials_volume\": {\"attenuationDistance\": 0}", "material 0: attenuationDistance must be a number > 0"},
             {"\"KHR_materials_volume\": {\"attenuationColor\": [1, 2, 1]}", "attenuationColor must be 3 numbers in [0, 1]"}}) {
        const std::string message = test::refusalOf([&] { parseGltf(windowWith(bad), "window.gltf", dir); }, "window.gltf: ");
        EXPECT_NE(message.find(part), std::string::npos) << message;
    }
    fs::remove_all(dir);
}

// KHR_materials_dispersion: read on a transmissive volume (KHR_materials_volume's thickness above
// 0), without a warning; on a thin wall (no volume) it changes nothing and a warning names it;
// a negative value is refused naming the material.
TEST(GltfLoaderMaterials, DispersionIsReadOnVolumes) {
    const fs::path dir = fs::temp_directory_path() / ("gpurt-dispersion-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "bands.bmp", std::ios::binary) << test::TransmissionQuad::image();
    ::testing::internal::CaptureStderr();
    const Scene scene = parseGltf(windowWith("\"KHR_materials_volume\": {\"thicknessFactor\": 0.5}, "
                                             "\"KHR_materials_dispersion\": {\"dispersion\": 0.4}"),
                                  "window.gltf", dir);
    std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(warnings.find("dispersion"), std::string::npos) << warnings;
    EXPECT_EQ(scene.materials[1].dispersion, 0.4f);
    EXPECT_TRUE(scene.materials[1].disperses());
    ::testing::internal::CaptureStderr();
    const Material thin = parseGltf(windowWith("\"KHR_materials_dispersion\": {\"dispersion\": 0.4}"), "window.gltf", dir).materials[1];
    warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(warnings.find("material 0 ('window'): KHR_materials_dispersion is not used: it applies to transmissive volumes only"),
              std::string::npos)
        << warnings;
    EXPECT_FALSE(thin.disperses());
    const std::string message = test::refusalOf(
        [&] { parseGltf(windowWith("\"KHR_materials_dispersion\": {\"dispersion\": -1}"), "window.gltf", dir); }, "window.gltf: ");
    EXPECT_NE(message.find("material 0: dispersion must be a number in [0, 1000]"), std::string::npos) << message;
    fs::remove_all(dir);
}

// KHR_materials_iridescence: the factor, index and thickness range are read (the extension's
// defaults without them: 0, 1.3, 100..400 nm), the factor's map is the texture's R and the
// thickness's its G, read through the slot's texCoord and transform; factor 0 reads no map; bad
// values are refused naming the material.
TEST(GltfLoaderMaterials, IridescenceIsRead) {
    const fs::path dir = fs::temp_directory_path() / ("gpurt-iridescence-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "bands.bmp", std::ios::binary) << test::TransmissionQuad::image();
    const std::string info = kTurnedSlot;
    ::testing::internal::CaptureStderr();
    const Scene scene = parseGltf(windowWith("\"KHR_materials_iridescence\": {\"iridescenceFactor\": 0.75, \"iridescenceIor\": 1.8, "
                                             "\"iridescenceThicknessMinimum\": 250, \"iridescenceThicknessMaximum\": 700, "
                                             "\"iridescenceTexture\": " + info + ", \"iridescenceThicknessTexture\": " + info + "}"),
                                  "window.gltf", dir);
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    for (const char* name : {"iridescence", "not used", "not read"}) EXPECT_EQ(warnings.find(name), std::string::npos) << warnings;
    const Material& m = scene.materials[1];
    EXPECT_EQ(m.iridescenceFactor, 0.75f);
    EXPECT_EQ(m.iridescenceIor, 1.8f);
    EXPECT_EQ(m.iridescenceThicknessMin, 250.0f);
    EXPECT_EQ(m.iridescenceThicknessMax, 700.0f);
    EXPECT_EQ(m.iridescenceTexture.texture, 0);
    EXPECT_EQ(m.iridescenceTexture.channel, 0);  // R
    EXPECT_EQ(m.iridescenceThicknessTexture.texture, 0);
    EXPECT_EQ(m.iridescenceThicknessTexture.channel, 1);  // G
    EXPECT_TRUE(m.hasIridescence());
    EXPECT_EQ(scene.textures.size(), 1u);  // the slots share the window's coordinates and image
    const Material defaults =
        parseGltf(windowWith("\"KHR_materials_iridescence\": {\"iridescenceFactor\": 1}"), "window.gltf", dir).materials[1];
    EXPECT_EQ(defaults.iridescenceIor, 1.3f);
    EXPECT_EQ(defaults.iridescenceThicknessMin, 100.0f);
    EXPECT_EQ(defaults.iridescenceThicknessMax, 400.0f);
    const Material off = parseGltf(windowWith("\"KHR_materials_iridescence\": {\"iridescenceTexture\": " + info + "}"),
                                   "window.gltf", dir).materials[1];
    EXPECT_FALSE(off.hasIridescence());
    EXPECT_FALSE(off.iridescenceTexture.given());
    for (const auto& [bad, part] : std::vector<std::pair<std::string, std::string>>{
             {"\"KHR_materials_iridescence\": {\"iridescenceFactor\": 2}", "material 0: iridescenceFactor must be in [0, 1]"},
             {"\"KHR_materials_iridescence\": {\"iridescenceIor\": 0.5}", "material 0: iridescenceIor must be in [1, 1000]"},
             {"\"KHR_materials_iridescence\": {\"iridescenceThicknessMaximum\": -1}", "must be in [0, 1e6] nm"}}) {
        const std::string message = test::refusalOf([&] { parseGltf(windowWith(bad), "window.gltf", dir); }, "window.gltf: ");
        EXPECT_NE(message.find(part), std::string::npos) << message;
    }
    fs::remove_all(dir);
}

// KHR_materials_anisotropy: the strength, the rotation and the map (a whole texture, linear RGB);
// strength 0 leaves the map unread; a strength outside [0, 1] is refused naming the material. The direction needs a tangent frame: TANGENT is kept for an
// anisotropic material without a normal map, and a primitive with neither TANGENT nor texture
// coordinates is a warning (its lobe is isotropic).
TEST(GltfLoaderMaterials, AnisotropyIsRead) {
    const fs::path dir = fs::temp_directory_path() / ("gpurt-anisotropy-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "bands.bmp", std::ios::binary) << test::TransmissionQuad::image();
    ::testing::internal::CaptureStderr();
    const Scene scene = parseGltf(windowWith("\"KHR_materials_anisotropy\": {\"anisotropyStrength\": 0.75, "
                                             "\"anisotropyRotation\": 1.25, \"anisotropyTexture\": " + kTurnedSlot + "}"),
                                  "window.gltf", dir);
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    for (const char* name : {"anisotropy", "not used", "not read"}) EXPECT_EQ(warnings.find(name), std::string::npos) << warnings;
    const Material& m = scene.materials[1];
    EXPECT_EQ(m.anisotropyStrength, 0.75f);
    EXPECT_EQ(m.anisotropyRotation, 1.25f);
    EXPECT_EQ(m.anisotropyTexture, 0);
    EXPECT_TRUE(m.hasAnisotropy());
    EXPECT_EQ(scene.textures.size(), 1u);  // the window's image, its coordinates shared
    const Material off = parseGltf(windowWith("\"KHR_materials_anisotropy\": {\"anisotropyTexture\": " + kTurnedSlot + "}"),
                                   "window.gltf", dir).materials[1];
    EXPECT_FALSE(off.hasAnisotropy());
    EXPECT_EQ(off.anisotropyTexture, -1);
    for (const auto& [bad, part] : std::vector<std::pair<std::string, std::string>>{
             {"\"KHR_materials_anisotropy\": {\"anisotropyStrength\": 1.5}", "material 0: anisotropyStrength must be in [0, 1]"},
             {"\"KHR_materials_anisotropy\": {\"anisotropyStrength\": -0.1}", "anisotropyStrength must be in [0, 1]"}}) {
        const std::string message = test::refusalOf([&] { parseGltf(windowWith(bad), "window.gltf", dir); }, "window.gltf: ");
        EXPECT_NE(message.find(part), std::string::npos) << message;
    }
    fs::remove_all(dir);

    // The frame: a quad with TANGENT keeps it for the anisotropic material; one without TANGENT and
    // without textures (so without texture coordinates) is said to take the up axis's, once.
    Gltf g;
    const TangentQuad quad(g);
    const int tangent = g.accessor(g.view(std::vector<float>{0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1}), 5126, 4, "VEC4");
    ::testing::internal::CaptureStderr();
    const Scene framed = parse(g.json(
        "\"scenes\": [{\"nodes\": [0, 1]}], \"nodes\": [{\"mesh\": 0}, {\"mesh\": 1}], \"meshes\": [" +
        quad.mesh(tangent, 0) + ", " + quad.mesh(-1, 0) +
        "], \"materials\": [{\"extensions\": {\"KHR_materials_anisotropy\": {\"anisotropyStrength\": 0.5}}}]"));
    const std::string said = ::testing::internal::GetCapturedStderr();
    ASSERT_EQ(framed.tangents.size(), 4u);
    EXPECT_EQ(framed.tangents[0].t0, glm::vec4(0, 1, 0, 1));
    EXPECT_EQ(framed.tangents[2].t0, glm::vec4(0.0f));
    EXPECT_NE(said.find("mesh 1 primitive 0: no TANGENT (with NORMAL) and no texture coordinates"), std::string::npos) << said;
    EXPECT_NE(said.find("its direction runs around the up axis"), std::string::npos) << said;
    EXPECT_EQ(said.find("mesh 0"), std::string::npos) << said;
}

// KHR_materials_pbrSpecularGlossiness becomes the metallic-roughness model with
// KHR_materials_specular (as Khronos' tools convert it): the base colour is diffuseFactor with
// diffuseTexture, metallic 0, F0 = 0.04 x specular colour = specularFactor with
// specularGlossinessTexture's RGB as the specular colour's map, and roughness 1 - glossinessFactor,
// or with the map a texture whose A is 1 - glossinessFactor x the map's A; no warning. Bad factors
// are refused naming the material.
TEST(GltfLoaderMaterials, SpecularGlossinessIsConverted) {
    const fs::path dir = fs::temp_directory_path() / ("gpurt-specgloss-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::vector<unsigned char> rgba = {10, 20, 30, 0, 40, 50, 60, 64, 70, 80, 90, 200, 100, 110, 120, 255};
    std::ofstream(dir / "gloss.tga", std::ios::binary) << test::tgaOf(4, 1, 32, true, false, rgba);
    auto document = [](const std::string& extension) { return windowWith(extension, "gloss.tga"); };
    const std::string info = kTurnedSlot;
    ::testing::internal::CaptureStderr();
    const Scene scene = parseGltf(document("\"KHR_materials_pbrSpecularGlossiness\": {\"diffuseFactor\": [0.5, 0.25, 1, 0.8], "
                                           "\"specularFactor\": [0.04, 0.5, 1], \"glossinessFactor\": 0.5, "
                                           "\"diffuseTexture\": " + info + ", \"specularGlossinessTexture\": " + info + "}"),
                                  "old.gltf", dir);
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    for (const char* name : {"Glossiness", "not used", "asks for other"}) EXPECT_EQ(warnings.find(name), std::string::npos) << warnings;
    const Material& m = scene.materials[1];
    EXPECT_EQ(m.model, GPURT_MODEL_GLTF);
    EXPECT_EQ(m.diffuse, glm::vec3(0.5f, 0.25f, 1.0f));
    EXPECT_EQ(m.metallic, 0.0f);
    EXPECT_EQ(m.diffuseTexture, 0);
    EXPECT_EQ(m.specularColorTexture, 0);
    const glm::vec3 f0(0.04f, 0.5f, 1.0f);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(0.04f * m.specularColor[c], f0[c], 1e-6f) << c;
    EXPECT_EQ(m.specularFactor, 1.0f);
    EXPECT_EQ(m.roughness, 1.0f);
    ASSERT_EQ(m.roughnessTexture.channel, 3);  // A
    ASSERT_EQ(scene.textures.size(), 2u);      // the image, and the roughness made from its A
    ASSERT_EQ(m.roughnessTexture.texture, 1);
    const Rgba8Image& rough = scene.textures[1].image;
    ASSERT_EQ(rough.texels.size(), 4u);
    for (size_t k = 0; k < 4; ++k) {
        const double expected = 255.0 * (1.0 - 0.5 * rgba[4 * k + 3] / 255.0);
        EXPECT_NEAR(double(rough.texels[k] >> 24), expected, 0.5) << k;
        EXPECT_EQ(rough.texels[k] & 0xffffffu, scene.textures[0].image.texels[k] & 0xffffffu) << k;
    }
    const Material plain = parseGltf(document("\"KHR_materials_pbrSpecularGlossiness\": {\"glossinessFactor\": 0.25}"),
                                     "old.gltf", dir).materials[1];
    EXPECT_EQ(plain.roughness, 0.75f);
    EXPECT_FALSE(plain.roughnessTexture.given());
    EXPECT_EQ(plain.diffuse, glm::vec3(1.0f));  // the extension's defaults: diffuse 1, specular 1
    EXPECT_NEAR(0.04f * plain.specularColor.x, 1.0f, 1e-6f);
    for (const auto& [bad, part] : std::vector<std::pair<std::string, std::string>>{
             {"\"KHR_materials_pbrSpecularGlossiness\": {\"glossinessFactor\": 2}", "material 0: glossinessFactor must be in [0, 1]"},
             {"\"KHR_materials_pbrSpecularGlossiness\": {\"diffuseFactor\": [1, 1]}", "material 0: diffuseFactor is not 4 numbers"},
             {"\"KHR_materials_pbrSpecularGlossiness\": {\"diffuseFactor\": [1, 1, 2, 1]}", "diffuseFactor must be 4 numbers in [0, 1]"},
             {"\"KHR_materials_pbrSpecularGlossiness\": {\"specularFactor\": [1, 1, 2]}", "specularFactor must be 3 numbers in [0, 1]"}}) {
        const std::string message = test::refusalOf([&] { parseGltf(document(bad), "old.gltf", dir); }, "old.gltf: ");
        EXPECT_NE(message.find(part), std::string::npos) << message;
    }
    fs::remove_all(dir);
}

// KHR_materials_transmission's transmissionTexture (TransmissionQuad.h): the slot is the texture's
// R channel, read through its texCoord (1) and its KHR_texture_transform (rotation pi/2, offset
// (0, 1): u' = v, v' = 1 - u by the extension's matrix), with no warning about the slot; the
// factor stays as given. Without the texture, or with factor 0 (nothing transmits), no slot.
TEST(GltfLoaderMaterials, TransmissionTextureSlotTexCoordAndTransform) {
    const fs::path dir = fs::temp_directory_path() / ("gpurt-transmission-slot-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "bands.bmp", std::ios::binary) << test::TransmissionQuad::image();
    auto load = [&](const std::string& text) { return parseGltf(text, "window.gltf", dir); };
    ::testing::internal::CaptureStderr();
    const Scene scene = load(test::TransmissionQuad::gltf(0.75, "bands.bmp"));
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(warnings.find("transmissionTexture"), std::string::npos) << warnings;
    ASSERT_EQ(scene.materials.size(), 2u);  // gpurt's default, then the window
    const Material& m = scene.materials[1];
    EXPECT_EQ(scene.materialIds, (std::vector<uint32_t>{1, 1}));
    EXPECT_EQ(m.transmission, glm::vec3(0.75f));
    EXPECT_EQ(m.ior, 1.0f);
    EXPECT_TRUE(m.transmits());
    ASSERT_EQ(scene.textures.size(), 1u);
    EXPECT_EQ(m.transmissionTexture.texture, 0);
    EXPECT_EQ(m.transmissionTexture.channel, 0);  // R
    EXPECT_EQ(m.diffuseTexture, -1);
    EXPECT_EQ(scene.textures[0].image.width, test::TransmissionQuad::kColumns);
    EXPECT_EQ(scene.textures[0].wrapS, uint32_t(kWrapClamp));
    // TEXCOORD_1 at the corners (indices 0 1 2, 0 2 3) through the extension's u' = cos(r) u +
    // sin(r) v + ox, v' = -sin(r) u + cos(r) v + oy with r = pi/2, (ox, oy) = (0, 1).
    const glm::dvec2 uv1[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    const double r = 1.5707963267948966;
    auto mapped = [&](int k) {
        const glm::dvec2 t = uv1[k];
        return glm::vec2(float(std::cos(r) * t.x + std::sin(r) * t.y), float(-std::sin(r) * t.x + std::cos(r) * t.y + 1.0));
    };
    ASSERT_EQ(scene.texcoords.size(), 2u);
    const int corners[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int tri = 0; tri < 2; ++tri) {
        const glm::vec2 got[3] = {scene.texcoords[size_t(tri)].t0, scene.texcoords[size_t(tri)].t1, scene.texcoords[size_t(tri)].t2};
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(got[k].x, mapped(corners[tri][k]).x, 1e-6f) << "triangle " << tri << " corner " << k;
            EXPECT_NEAR(got[k].y, mapped(corners[tri][k]).y, 1e-6f) << "triangle " << tri << " corner " << k;
        }
    }
    const Scene plain = load(test::TransmissionQuad::gltf(0.75, "bands.bmp", false, false));
    EXPECT_FALSE(plain.materials[1].transmissionTexture.given());
    EXPECT_TRUE(plain.texcoords.empty());
    const Scene opaque = load(test::TransmissionQuad::gltf(0.0, "bands.bmp"));
    EXPECT_FALSE(opaque.materials[1].transmits());
    EXPECT_FALSE(opaque.materials[1].transmissionTexture.given());
    // Hostile slots: exit 1 naming the material and the slot.
    auto withInfo = [&](const std::string& info) {
        std::string text = test::TransmissionQuad::gltf(1.0, "bands.bmp");
        const std::string slot = "\"transmissionTexture\": {\"index\": 0, \"texCoord\": 1";
        const size_t at = text.find(slot);
        EXPECT_NE(at, std::string::npos);
        text.replace(at, slot.size(), "\"transmissionTexture\": {" + info);
        return test::refusalOf([&] { load(text); }, "window.gltf: ");
    };
    for (const auto& [info, part] : std::vector<std::pair<std::string, std::string>>{
             {"\"texCoord\": 1", "material 0 ('window'): transmissionTexture has no texture index"},
             {"\"index\": -1, \"texCoord\": 1", "transmissionTexture has no texture index"},
             {"\"index\": \"0\", \"texCoord\": 1", "transmissionTexture has no texture index"},
             {"\"index\": 7, \"texCoord\": 1", "material 0 ('window'): texture 7 does not exist"},
             {"\"index\": 0, \"texCoord\": 300", "transmissionTexture texCoord 300 out of range"},
             {"\"index\": 0, \"texCoord\": 0.5", "transmissionTexture texCoord is not a whole number"}}) {
        const std::string message = withInfo(info);
        EXPECT_NE(message.find(part), std::string::npos) << info << ": " << message;
    }
    std::string badTransform = test::TransmissionQuad::gltf(1.0, "bands.bmp");
    const std::string offset = "\"offset\": [0, 1]";
    badTransform.replace(badTransform.find(offset), offset.size(), "\"offset\": [0, \"1\"]");
    EXPECT_NE(test::refusalOf([&] { load(badTransform); }, "window.gltf: ")
                  .find("transmissionTexture KHR_texture_transform offset is not 2 numbers"),
              std::string::npos);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace gpurt
