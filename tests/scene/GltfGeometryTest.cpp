// glTF geometry beyond plain float accessors (GltfLoader.h): KHR_mesh_quantization, Draco
// (KHR_draco_mesh_compression, the data made here by Draco's own encoder), skins at their bind
// pose against positions worked out by hand, and the warnings for what a file holds that gpurt
// does not use (extensions, attributes, morph targets, animations, points and lines).
#include "scene/GltfLoader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <draco/compression/encode.h>
#include <draco/core/encoder_buffer.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

#include "../common/Refusal.h"
#include "GltfDocument.h"
#include "image/InputError.h"

namespace gpurt {
namespace {

namespace fs = std::filesystem;
using test::Gltf;

Scene parse(const std::string& text, const std::string& name = "scene.gltf") {
    return parseGltf(text, name, fs::temp_directory_path());
}

// What parsing `text` printed on stderr.
std::string warningsOf(const std::string& text) {
    ::testing::internal::CaptureStderr();
    try {
        parse(text);
    } catch (...) {
        ::testing::internal::GetCapturedStderr();
        throw;
    }
    return ::testing::internal::GetCapturedStderr();
}

std::string refusal(const std::string& text) {
    return test::refusalOf([&] { parseGltf(text, "bad.gltf", fs::temp_directory_path()); },
                           "bad.gltf: ");
}

size_t lines(const std::string& text) { return size_t(std::count(text.begin(), text.end(), '\n')); }

std::string oneMesh(int position, const std::string& more = "", const std::string& node = "") {
    return "\"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0" + node +
           "}], \"meshes\": [{\"primitives\": [{"
           "\"attributes\": {\"POSITION\": " +
           std::to_string(position) + more + "}}]}]";
}

// A small closed mesh with coordinates that no quantization step divides: the 12 triangles of a
// box from (-0.73, 0.11, -2.9) to (1.37, 0.96, 0.42), each corner's normal pointing away from
// the box's centre.
struct Box {
    std::vector<float> xyz, normals;
    std::vector<uint16_t> indices;
    glm::vec3 lo{-0.73f, 0.11f, -2.9f}, hi{1.37f, 0.96f, 0.42f};

    Box() {
        for (int c = 0; c < 8; ++c) {
            const glm::vec3 p{c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z};
            const glm::vec3 n =
                glm::normalize(glm::vec3(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1));
            xyz.insert(xyz.end(), {p.x, p.y, p.z});
            normals.insert(normals.end(), {n.x, n.y, n.z});
        }
        // Two triangles per face, wound outwards.
        const uint16_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                      {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
        for (const auto& f : faces)
            indices.insert(indices.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
    }
    glm::vec3 corner(size_t i) const { return {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}; }
    glm::vec3 normal(size_t i) const {
        return {normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]};
    }
};

// Each triangle of `actual` is one of `expected` (in any order, its corners in any rotation)
// with every coordinate within `tolerance`; each expected triangle is met once.
void expectSameTriangles(const Scene& actual, const std::vector<Triangle>& expected,
                         float tolerance, const std::string& what) {
    ASSERT_EQ(actual.triangles.size(), expected.size()) << what;
    std::vector<bool> met(expected.size(), false);
    auto near = [&](glm::vec3 a, glm::vec3 b) {
        return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(tolerance)));
    };
    for (size_t t = 0; t < actual.triangles.size(); ++t) {
        const Triangle& a = actual.triangles[t];
        bool found = false;
        for (size_t e = 0; e < expected.size() && !found; ++e) {
            if (met[e]) continue;
            const glm::vec3 v[3] = {expected[e].v0, expected[e].v1, expected[e].v2};
            for (int r = 0; r < 3 && !found; ++r)
                if (near(a.v0, v[r]) && near(a.v1, v[(r + 1) % 3]) && near(a.v2, v[(r + 2) % 3]))
                    found = met[e] = true;
        }
        EXPECT_TRUE(found) << what << ": triangle " << t << " is none of the expected ones";
    }
}

std::vector<Triangle> boxTriangles(const Box& box) {
    std::vector<Triangle> out;
    for (size_t k = 0; k < box.indices.size(); k += 3)
        out.push_back({box.corner(box.indices[k]), box.corner(box.indices[k + 1]),
                       box.corner(box.indices[k + 2])});
    return out;
}

// The quantized box as gltfpack writes it: positions as unsigned shorts (not normalized) over the
// box's extent, dequantized by the node's scale and translation; normals as normalized bytes
// padded to 4 (byte stride 4).
TEST(GltfQuantization, QuantizedPositionsAndNormalsGiveThePlainTrianglesWithinAStep) {
    const Box box;
    Gltf plain;
    plain.positions(box.xyz);          // accessor 0
    plain.positions(box.normals);      // 1
    plain.indices(box.indices, 5123);  // 2
    const std::string mesh =
        "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0, \"NORMAL\": 1}, "
        "\"indices\": 2}]}]";
    const Scene reference =
        parse(plain.json("\"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0}], " + mesh));

    Gltf quantized;
    const glm::vec3 step = (box.hi - box.lo) / 65535.0f;
    std::vector<uint16_t> q;
    for (size_t v = 0; v < 8; ++v)
        for (int c = 0; c < 3; ++c)
            q.push_back(uint16_t(std::lround((box.corner(v)[c] - box.lo[c]) / step[c])));
    std::vector<int8_t> qn;
    for (size_t v = 0; v < 8; ++v)
        for (int c = 0; c < 4; ++c)
            qn.push_back(c < 3 ? int8_t(std::lround(box.normal(v)[c] * 127.0f)) : 0);
    quantized.accessor(quantized.view(q), 5123, 8, "VEC3");
    quantized.accessor(quantized.view(qn, 4), 5120, 8, "VEC3", ", \"normalized\": true");
    quantized.indices(box.indices, 5123);
    auto number = [](float v) {
        char text[32];
        std::snprintf(text, sizeof text, "%.9g", double(v));  // every float's digits
        return std::string(text);
    };
    const std::string node = "{\"mesh\": 0, \"translation\": [" + number(box.lo.x) + ", " +
                             number(box.lo.y) + ", " + number(box.lo.z) + "], \"scale\": [" +
                             number(step.x) + ", " + number(step.y) + ", " + number(step.z) + "]}";
    const std::string document = quantized.json(
        "\"extensionsUsed\": [\"KHR_mesh_quantization\"], \"extensionsRequired\": "
        "[\"KHR_mesh_quantization\"], "
        "\"scenes\": [{\"nodes\": [0]}], \"nodes\": [" +
        node + "], " + mesh);
    std::string warnings;
    ASSERT_NO_THROW(warnings = warningsOf(document));
    EXPECT_EQ(warnings, "");  // a required extension gpurt reads: no warning
    const Scene scene = parse(document);
    // Half a step of rounding, and the decimal printing of the node's numbers.
    const float tolerance = 0.5f * std::max({step.x, step.y, step.z}) + 1e-5f;
    ASSERT_EQ(scene.triangles.size(), reference.triangles.size());
    expectSameTriangles(scene, reference.triangles, tolerance, "quantized");
    for (size_t t = 0; t < scene.triangles.size(); ++t) {  // same order too
        EXPECT_NEAR(glm::length(scene.triangles[t].v0 - reference.triangles[t].v0), 0.0f,
                    2 * tolerance)
            << t;
        EXPECT_NEAR(glm::length(scene.triangles[t].v2 - reference.triangles[t].v2), 0.0f,
                    2 * tolerance)
            << t;
    }
    // Normals: one byte step (1/127) per component before renormalising; the node's scale turns
    // them by its inverse transpose, so compare against the plain normals through the same map.
    ASSERT_EQ(scene.normals.size(), reference.normals.size());
    for (size_t t = 0; t < scene.normals.size(); ++t) {
        const glm::vec3 expected = glm::normalize(reference.normals[t].n0 / step);
        EXPECT_LT(glm::length(scene.normals[t].n0 - expected), 0.05f) << t;
    }
}

// The glTF spec's formulas for normalized integers, on each type KHR_mesh_quantization allows
// for POSITION: max(c / 127, -1) for bytes (so -128 and -127 are both -1), c / 255, max(c /
// 32767, -1), c / 65535; and integers that are not normalized as they are.
TEST(GltfQuantization, EveryComponentTypeAsTheSpecConvertsIt) {
    struct Case {
        int type;
        bool normalized;
        std::string bytes;
        glm::vec3 v0, v1, v2;
    };
    auto bytes = [](auto... v) {
        std::string out;
        ((out.append(reinterpret_cast<const char*>(&v), sizeof(v))), ...);
        return out;
    };
    using i8 = int8_t;
    using u8 = uint8_t;
    using i16 = int16_t;
    using u16 = uint16_t;
    const std::vector<Case> cases = {
        {5120,
         true,
         bytes(i8(-128), i8(127), i8(0), i8(0), i8(-127), i8(64), i8(1), i8(2), i8(0)),
         {-1, 1, 0},
         {0, -1, 64 / 127.0f},
         {1 / 127.0f, 2 / 127.0f, 0}},
        {5120,
         false,
         bytes(i8(-128), i8(127), i8(0), i8(0), i8(-127), i8(64), i8(1), i8(2), i8(0)),
         {-128, 127, 0},
         {0, -127, 64},
         {1, 2, 0}},
        {5121,
         true,
         bytes(u8(255), u8(0), u8(51), u8(1), u8(2), u8(3), u8(0), u8(0), u8(255)),
         {1, 0, 0.2f},
         {1 / 255.0f, 2 / 255.0f, 3 / 255.0f},
         {0, 0, 1}},
        {5121,
         false,
         bytes(u8(255), u8(0), u8(51), u8(1), u8(2), u8(3), u8(0), u8(0), u8(255)),
         {255, 0, 51},
         {1, 2, 3},
         {0, 0, 255}},
        {5122,
         true,
         bytes(i16(-32768), i16(32767), i16(0), i16(-32767), i16(16384), i16(1), i16(0), i16(0),
               i16(2)),
         {-1, 1, 0},
         {-1, 16384 / 32767.0f, 1 / 32767.0f},
         {0, 0, 2 / 32767.0f}},
        {5122,
         false,
         bytes(i16(-32768), i16(32767), i16(0), i16(-32767), i16(16384), i16(1), i16(0), i16(0),
               i16(2)),
         {-32768, 32767, 0},
         {-32767, 16384, 1},
         {0, 0, 2}},
        {5123,
         true,
         bytes(u16(65535), u16(0), u16(13107), u16(1), u16(2), u16(3), u16(0), u16(0), u16(65535)),
         {1, 0, 0.2f},
         {1 / 65535.0f, 2 / 65535.0f, 3 / 65535.0f},
         {0, 0, 1}},
        {5123,
         false,
         bytes(u16(65535), u16(0), u16(13107), u16(1), u16(2), u16(3), u16(0), u16(0), u16(65535)),
         {65535, 0, 13107},
         {1, 2, 3},
         {0, 0, 65535}},
    };
    for (const Case& c : cases) {
        Gltf g;
        // Elements padded to 4 bytes, as the spec requires of vertex attributes.
        const size_t element = c.bytes.size() / 3;
        const size_t stride = (element + 3) / 4 * 4;
        std::string padded;
        for (int v = 0; v < 3; ++v)
            padded +=
                c.bytes.substr(size_t(v) * element, element) + std::string(stride - element, '\0');
        const int p = g.accessor(g.view(padded, int(stride)), c.type, 3, "VEC3",
                                 c.normalized ? ", \"normalized\": true" : "");
        const Scene scene =
            parse(g.json("\"extensionsUsed\": [\"KHR_mesh_quantization\"], "
                         "\"extensionsRequired\": [\"KHR_mesh_quantization\"], " +
                         oneMesh(p)));
        const std::string what =
            "component type " + std::to_string(c.type) + (c.normalized ? " normalized" : "");
        ASSERT_EQ(scene.triangles.size(), 1u) << what;
        // Exact but for the last bit of float rounding (the reader divides in double).
        for (const auto& [got, want] :
             {std::pair(scene.triangles[0].v0, c.v0), std::pair(scene.triangles[0].v1, c.v1),
              std::pair(scene.triangles[0].v2, c.v2)})
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(got[k], want[k], 1e-7f * std::max(1.0f, std::abs(want[k]))) << what;
    }
}

// Draco data of the box, made by Draco's encoder: positions quantized to `bits`, normals to 10
// bits. Sequential encoding keeps the faces in their order; edgebreaker (the default, what real
// files use) may reorder them. Returns the data and the unique ids of POSITION and NORMAL.
struct DracoData {
    std::string bytes;
    int position = -1, normal = -1;
};

DracoData encodeBox(const Box& box, int bits, bool sequential) {
    draco::TriangleSoupMeshBuilder builder;
    builder.Start(int(box.indices.size() / 3));
    const int position =
        builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int normal = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
    for (size_t f = 0; f < box.indices.size() / 3; ++f) {
        const glm::vec3 p[3] = {box.corner(box.indices[3 * f]), box.corner(box.indices[3 * f + 1]),
                                box.corner(box.indices[3 * f + 2])};
        const glm::vec3 n[3] = {box.normal(box.indices[3 * f]), box.normal(box.indices[3 * f + 1]),
                                box.normal(box.indices[3 * f + 2])};
        builder.SetAttributeValuesForFace(position, draco::FaceIndex(uint32_t(f)), &p[0], &p[1],
                                          &p[2]);
        builder.SetAttributeValuesForFace(normal, draco::FaceIndex(uint32_t(f)), &n[0], &n[1],
                                          &n[2]);
    }
    const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    draco::Encoder encoder;
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, bits);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
    if (sequential) encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
    draco::EncoderBuffer out;
    const draco::Status status = encoder.EncodeMeshToBuffer(*mesh, &out);
    EXPECT_TRUE(status.ok()) << status.error_msg_string();
    DracoData data;
    data.bytes.assign(out.data(), out.size());
    data.position = int(mesh->attribute(position)->unique_id());
    data.normal = int(mesh->attribute(normal)->unique_id());
    return data;
}

// The box as a glTF whose one primitive is Draco-compressed: accessors without buffer views, the
// extension naming the data's view and the attributes' ids.
Gltf dracoBox(const DracoData& data, std::string& rest, const std::string& attributes = "") {
    Gltf g;
    const int view = g.view(data.bytes);
    g.accessor(-1, 5123, 36, "SCALAR");
    g.accessor(-1, 5126, 8, "VEC3");
    g.accessor(-1, 5126, 8, "VEC3");
    rest =
        "\"extensionsUsed\": [\"KHR_draco_mesh_compression\"], \"extensionsRequired\": "
        "[\"KHR_draco_mesh_compression\"], "
        "\"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0}], \"meshes\": [{\"primitives\": "
        "[{\"attributes\": "
        "{\"POSITION\": 1, \"NORMAL\": 2}, \"indices\": 0, \"extensions\": "
        "{\"KHR_draco_mesh_compression\": {\"bufferView\": " +
        std::to_string(view) + ", \"attributes\": " +
        (attributes.empty() ? "{\"POSITION\": " + std::to_string(data.position) +
                                  ", \"NORMAL\": " + std::to_string(data.normal) + "}"
                            : attributes) +
        "}}}]}]";
    return g;
}

TEST(GltfDraco, DracoBoxGivesThePlainTrianglesWithinAQuantizationStep) {
    const Box box;
    const std::vector<Triangle> expected = boxTriangles(box);
    const float range = std::max({box.hi.x - box.lo.x, box.hi.y - box.lo.y, box.hi.z - box.lo.z});
    for (const bool sequential : {true, false}) {
        const DracoData data = encodeBox(box, 14, sequential);
        std::string rest;
        const Gltf g = dracoBox(data, rest);
        // Draco's quantization: the largest extent in 2^bits - 1 steps, half a step of rounding.
        const float tolerance = 0.5f * range / 16383.0f + 1e-6f;
        const std::string what = sequential ? "sequential" : "edgebreaker";
        std::string warnings;
        ASSERT_NO_THROW(warnings = warningsOf(g.json(rest))) << what;
        EXPECT_EQ(warnings, "") << what;
        const Scene gltf = parse(g.json(rest));
        expectSameTriangles(gltf, expected, tolerance, what + " .gltf");
        if (sequential) {  // in the plain order too
            for (size_t t = 0; t < expected.size(); ++t)
                EXPECT_LE(glm::length(gltf.triangles[t].v0 - expected[t].v0), 2 * tolerance) << t;
        }
        const Scene glb = parse(g.glb(rest), "scene.glb");
        expectSameTriangles(glb, expected, tolerance, what + " .glb");
        // Normals come along: each corner's is the box corner's direction (10 bits of it).
        ASSERT_EQ(gltf.normals.size(), expected.size());
        for (size_t t = 0; t < expected.size(); ++t) {
            const glm::vec3 centre = 0.5f * (box.lo + box.hi);
            const glm::vec3 outward = glm::sign(gltf.triangles[t].v0 - centre);
            EXPECT_LT(glm::length(gltf.normals[t].n0 - glm::normalize(outward)), 0.01f)
                << what << " triangle " << t;
        }
    }
}

// Damaged Draco data is one error naming the file and the primitive; so are attribute ids the
// data does not hold and a Draco view that does not exist. This used to be refused as an
// "invalid bufferView" of the indices accessor.
TEST(GltfDraco, DamagedDracoDataIsAnErrorNamingThePrimitive) {
    const Box box;
    const DracoData data = encodeBox(box, 14, false);
    std::string rest;
    for (const std::string& damaged :
         {data.bytes.substr(0, data.bytes.size() / 2),
          std::string("DRACO") + std::string(40, '\x7f'), std::string("not draco at all")}) {
        DracoData broken = data;
        broken.bytes = damaged;
        const Gltf g = dracoBox(broken, rest);
        const std::string message = refusal(g.json(rest));
        EXPECT_NE(message.find("bad.gltf: mesh 0 primitive 0: Draco data"), std::string::npos)
            << message;
        EXPECT_EQ(message.find("invalid bufferView"), std::string::npos) << message;
    }
    const Gltf wrongId = dracoBox(
        data, rest, "{\"POSITION\": " + std::to_string(data.position) + ", \"NORMAL\": 7}");
    EXPECT_NE(refusal(wrongId.json(rest))
                  .find("mesh 0 primitive 0: Draco data has no attribute 7 (NORMAL)"),
              std::string::npos);
    const Gltf g = dracoBox(data, rest);
    std::string noView = rest;
    noView.replace(noView.find("\"bufferView\": 0"), 15, "\"bufferView\": 9");
    EXPECT_NE(
        refusal(g.json(noView))
            .find("mesh 0 primitive 0 KHR_draco_mesh_compression: buffer view 9 does not exist"),
        std::string::npos);
}

// A skinned triangle whose POSITION, JOINTS_0 and WEIGHTS_0 are all in the Draco data (as
// glTF-Draco exports of rigged models have them): joints and weights as unsigned bytes, the
// weights' accessor normalized, so that 255 is a weight of 1 (no warning of weights that do not
// sum to 1). One joint, node 1 (translation (0, 0, -1), scale 3), no inverseBindMatrices; the
// mesh node's own translation (100, 0, 0) is not used: each vertex is 3 p + (0, 0, -1).
TEST(GltfDraco, DracoCompressedSkin) {
    const glm::vec3 corners[3] = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0.5f}};
    draco::TriangleSoupMeshBuilder builder;
    builder.Start(1);
    const int position =
        builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int joints = builder.AddAttribute(draco::GeometryAttribute::GENERIC, 4, draco::DT_UINT8);
    const int weights =
        builder.AddAttribute(draco::GeometryAttribute::GENERIC, 4, draco::DT_UINT8, true);
    const uint8_t joint[4] = {0, 0, 0, 0}, weight[4] = {255, 0, 0, 0};
    builder.SetAttributeValuesForFace(position, draco::FaceIndex(0), &corners[0], &corners[1],
                                      &corners[2]);
    builder.SetAttributeValuesForFace(joints, draco::FaceIndex(0), joint, joint, joint);
    builder.SetAttributeValuesForFace(weights, draco::FaceIndex(0), weight, weight, weight);
    const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    draco::Encoder encoder;
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 16);
    encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
    draco::EncoderBuffer out;
    ASSERT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &out).ok());
    Gltf g;
    const int view = g.view(std::string(out.data(), out.size()));
    g.accessor(-1, 5126, 3, "VEC3");
    g.accessor(-1, 5121, 3, "VEC4");
    g.accessor(-1, 5121, 3, "VEC4", ", \"normalized\": true");
    auto id = [&](int attribute) {
        return std::to_string(mesh->attribute(attribute)->unique_id());
    };
    const std::string document = g.json(
        "\"extensionsUsed\": [\"KHR_draco_mesh_compression\"], \"scenes\": [{\"nodes\": [0, 1]}], "
        "\"nodes\": [{\"mesh\": 0, \"skin\": 0, \"translation\": [100, 0, 0]}, {\"translation\": "
        "[0, 0, -1], \"scale\": [3, 3, 3]}], "
        "\"skins\": [{\"joints\": [1]}], \"meshes\": [{\"primitives\": [{\"attributes\": "
        "{\"POSITION\": 0, \"JOINTS_0\": 1, "
        "\"WEIGHTS_0\": 2}, \"extensions\": {\"KHR_draco_mesh_compression\": {\"bufferView\": " +
        std::to_string(view) + ", \"attributes\": {\"POSITION\": " + id(position) +
        ", \"JOINTS_0\": " + id(joints) + ", \"WEIGHTS_0\": " + id(weights) + "}}}}]}]");
    std::string warnings;
    ASSERT_NO_THROW(warnings = warningsOf(document));
    EXPECT_EQ(warnings, "");
    const Scene scene = parse(document);
    ASSERT_EQ(scene.triangles.size(), 1u);
    const glm::vec3 got[3] = {scene.triangles[0].v0, scene.triangles[0].v1, scene.triangles[0].v2};
    const float step =
        3.0f * 2.0f / 65535.0f;  // 16 bits over the largest extent (2), times the scale
    for (int k = 0; k < 3; ++k) {
        const glm::vec3 want = 3.0f * corners[k] + glm::vec3(0, 0, -1);
        EXPECT_LE(glm::length(got[k] - want), step) << k;
    }
}

// A two-joint skin: node 0 holds the mesh (its own translation must be ignored), node 1 is joint 0
// (translation (0, 1, 0), scale 2) and its child node 2 is joint 1 (translation (1, 0, 0), a
// quarter turn about z). Joint 0's inverse bind matrix translates by (0, -1, 0), joint 1's is the
// identity. Vertex 0 follows joint 0, vertex 1 joint 1, vertex 2 both equally (weights given as
// normalized unsigned bytes); vertex 3 takes joint 1 through the second set JOINTS_1/WEIGHTS_1.
struct SkinnedTriangles {
    Gltf g;
    std::string nodes, skin;
    int weights = -1;

    explicit SkinnedTriangles(const std::vector<uint8_t>& weights0 = {255, 0, 0, 0, 255, 0, 0, 0,
                                                                      128, 127, 0, 0, 0, 0, 0, 0},
                              const std::vector<uint8_t>& joints0 = {0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
                                                                     0, 0, 0, 0, 0, 0}) {
        g.positions({1, 1, 0, 1, 0, 0, 0, 0, 1, 0, 2, 0});
        g.accessor(g.view(joints0), 5121, 4, "VEC4");
        weights = g.accessor(g.view(weights0), 5121, 4, "VEC4", ", \"normalized\": true");
        g.accessor(g.view(std::vector<uint8_t>{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0}),
                   5121, 4, "VEC4");
        g.accessor(g.view(std::vector<uint8_t>{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 255, 0, 0, 0}),
                   5121, 4, "VEC4", ", \"normalized\": true");
        const std::vector<float> inverseBind = {
            1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1,  // column-major
            1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0,  0, 1};
        g.accessor(g.view(inverseBind), 5126, 2, "MAT4");
        g.indices(std::vector<uint8_t>{0, 1, 2, 0, 2, 3}, 5121);
        const double s = std::sqrt(0.5);
        nodes =
            "\"nodes\": [{\"mesh\": 0, \"skin\": 0, \"translation\": [100, 0, 0]}, "
            "{\"translation\": [0, 1, 0], \"scale\": [2, 2, 2], \"children\": [2]}, "
            "{\"translation\": [1, 0, 0], \"rotation\": [0, 0, " +
            std::to_string(s) + ", " + std::to_string(s) + "]}]";
        skin = "\"skins\": [{\"joints\": [1, 2], \"inverseBindMatrices\": 5}]";
    }
    std::string document(const std::string& skins = "", const std::string& attributes = "") const {
        return g.json("\"scenes\": [{\"nodes\": [0, 1]}], " + nodes + ", " +
                      (skins.empty() ? skin : skins) +
                      ", \"meshes\": [{\"primitives\": [{\"attributes\": " +
                      (attributes.empty() ? "{\"POSITION\": 0, \"JOINTS_0\": 1, \"WEIGHTS_0\": 2, "
                                            "\"JOINTS_1\": 3, \"WEIGHTS_1\": 4}"
                                          : attributes) +
                      ", \"indices\": 6}]}]");
    }
};

TEST(GltfSkin, SkinnedVerticesAreTheJointsMatricesTimesTheInverseBindMatrices) {
    const SkinnedTriangles skinned;
    std::string warnings;
    ASSERT_NO_THROW(warnings = warningsOf(skinned.document()));
    EXPECT_EQ(warnings, "");  // 128 + 127 = 255: the weights sum to 1
    const Scene scene = parse(skinned.document());
    // Joint 0: world J0 = T(0,1,0) S(2); with its inverse bind matrix p -> 2 (p - (0,1,0)) +
    // (0,1,0).
    auto joint0 = [](glm::vec3 p) { return 2.0f * (p - glm::vec3(0, 1, 0)) + glm::vec3(0, 1, 0); };
    // Joint 1: J0's world of (1,0,0) + Rz(90) p, with Rz(90)(x, y, z) = (-y, x, z).
    auto joint1 = [](glm::vec3 p) {
        return 2.0f * (glm::vec3(1, 0, 0) + glm::vec3(-p.y, p.x, p.z)) + glm::vec3(0, 1, 0);
    };
    const glm::vec3 v0 = joint0({1, 1, 0});  // (2, 1, 0)
    const glm::vec3 v1 = joint1({1, 0, 0});  // (2, 3, 0)
    const glm::vec3 v2 = (128.0f * joint0({0, 0, 1}) + 127.0f * joint1({0, 0, 1})) / 255.0f;
    const glm::vec3 v3 = joint1({0, 2, 0});  // through JOINTS_1
    ASSERT_EQ(scene.triangles.size(), 2u);
    const glm::vec3 got[6] = {scene.triangles[0].v0, scene.triangles[0].v1, scene.triangles[0].v2,
                              scene.triangles[1].v0, scene.triangles[1].v1, scene.triangles[1].v2};
    const glm::vec3 want[6] = {v0, v1, v2, v0, v2, v3};
    for (int k = 0; k < 6; ++k) {
        EXPECT_NEAR(got[k].x, want[k].x, 1e-5f) << k;
        EXPECT_NEAR(got[k].y, want[k].y, 1e-5f) << k;
        EXPECT_NEAR(got[k].z, want[k].z, 1e-5f) << k;
    }
    // The bounds: those of the four skinned vertices, nowhere near the mesh node's x = 100.
    const glm::vec3 lo = glm::min(glm::min(v0, v1), glm::min(v2, v3)),
                    hi = glm::max(glm::max(v0, v1), glm::max(v2, v3));
    glm::vec3 sceneLo(INFINITY), sceneHi(-INFINITY);
    for (const glm::vec3& v : got) sceneLo = glm::min(sceneLo, v), sceneHi = glm::max(sceneHi, v);
    EXPECT_LT(glm::length(sceneLo - lo), 1e-5f);
    EXPECT_LT(glm::length(sceneHi - hi), 1e-5f);
}

// Khronos' SimpleSkin (tests/assets/gltf/skin): its joints' world transforms are their inverse
// bind matrices' inverses, so at the bind pose every vertex is where POSITION puts it: the
// bounds are the accessor's min and max, (-0.5, 0, 0) to (0.5, 2, 0); its animation is a warning.
TEST(GltfSkin, SimpleSkinAtItsBindPose) {
    ::testing::internal::CaptureStderr();
    const Scene scene = loadGltf("tests/assets/gltf/skin/SimpleSkin.gltf");
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(warnings,
              "tests/assets/gltf/skin/SimpleSkin.gltf: warning: 1 animation is not used; the scene "
              "is drawn at "
              "rest (its nodes' own transforms)\n");
    ASSERT_EQ(scene.triangles.size(), 8u);  // 24 indices
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const Triangle& t : scene.triangles)
        for (const glm::vec3& v : {t.v0, t.v1, t.v2}) lo = glm::min(lo, v), hi = glm::max(hi, v);
    EXPECT_LT(glm::length(lo - glm::vec3(-0.5f, 0.0f, 0.0f)), 1e-6f);
    EXPECT_LT(glm::length(hi - glm::vec3(0.5f, 2.0f, 0.0f)), 1e-6f);
}

// Weights that do not sum to 1 are normalised (a warning), a vertex without weight keeps its
// node's transform (a warning); JOINTS and WEIGHTS of a node without a skin are a warning.
TEST(GltfSkin, WeightsAreNormalisedWithAWarning) {
    // Vertex 2: weights 64/255 and 64/255, normalised to half and half: the same place as 128/127
    // within rounding; vertex 0 has no weight at all in set 0 and none in set 1.
    const SkinnedTriangles skinned({0, 0, 0, 0, 255, 0, 0, 0, 64, 64, 0, 0, 0, 0, 0, 0});
    std::string warnings;
    ASSERT_NO_THROW(warnings = warningsOf(skinned.document()));
    EXPECT_EQ(lines(warnings), 2u) << warnings;
    EXPECT_NE(warnings.find("mesh 0 primitive 0: 1 vertices have no joint weight"),
              std::string::npos)
        << warnings;
    EXPECT_NE(
        warnings.find(
            "mesh 0 primitive 0: the joint weights of 1 vertices do not sum to 1; normalised"),
        std::string::npos)
        << warnings;
    const Scene scene = parse(skinned.document());
    ASSERT_EQ(scene.triangles.size(), 2u);
    EXPECT_NEAR(scene.triangles[0].v0.x, 101.0f,
                1e-4f);  // (1, 1, 0) through the node's own transform
    const glm::vec3 half = 0.5f * (glm::vec3(0, -1, 2) + glm::vec3(2, 1, 2));
    EXPECT_LT(glm::length(scene.triangles[0].v2 - half), 1e-5f);

    // The same mesh drawn by a node without a skin: the attributes are named once each.
    SkinnedTriangles unskinned;
    unskinned.nodes = "\"nodes\": [{\"mesh\": 0}, {}, {}]";
    ASSERT_NO_THROW(warnings = warningsOf(unskinned.document()));
    EXPECT_EQ(lines(warnings), 4u) << warnings;
    for (const char* name : {"JOINTS_0", "WEIGHTS_0", "JOINTS_1", "WEIGHTS_1"})
        EXPECT_NE(warnings.find(std::string(name) + " is not used"), std::string::npos) << warnings;
    // JOINTS_1 without WEIGHTS_1: that set is not used (a warning), so vertex 3 has no weight.
    const SkinnedTriangles partial;
    ASSERT_NO_THROW(
        warnings = warningsOf(partial.document(
            "", "{\"POSITION\": 0, \"JOINTS_0\": 1, \"WEIGHTS_0\": 2, \"JOINTS_1\": 3}")));
    EXPECT_EQ(lines(warnings), 2u) << warnings;
    EXPECT_NE(warnings.find("mesh 0 primitive 0: JOINTS_1 is not used (the complete sets of "
                            "JOINTS_n and WEIGHTS_n are 1)"),
              std::string::npos)
        << warnings;
    EXPECT_NE(warnings.find("mesh 0 primitive 0: 1 vertices have no joint weight"),
              std::string::npos)
        << warnings;
}

// Broken skins: one line naming the file and the glTF path.
TEST(GltfSkin, BrokenSkinsAreErrorsNamingThePath) {
    const SkinnedTriangles outOfRange({255, 0, 0, 0, 255, 0, 0, 0, 128, 127, 0, 0, 0, 0, 0, 0},
                                      {0, 0, 0, 0, 5, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0});
    EXPECT_NE(refusal(outOfRange.document())
                  .find("bad.gltf: mesh 0 primitive 0: JOINTS_0 of vertex 1 names joint 5; skin 0 "
                        "has 2 joints"),
              std::string::npos);
    const SkinnedTriangles skinned;
    EXPECT_NE(
        refusal(skinned.document("\"skins\": [{\"joints\": [1, 2], \"inverseBindMatrices\": 42}]"))
            .find("bad.gltf: skin 0 inverseBindMatrices: accessor 42 does not exist"),
        std::string::npos);
    EXPECT_NE(
        refusal(skinned.document("\"skins\": [{\"joints\": [1, 9], \"inverseBindMatrices\": 5}]"))
            .find("bad.gltf: skin 0: joint 1 is node 9, which does not exist"),
        std::string::npos);
    EXPECT_NE(
        refusal(skinned.document("\"skins\": [{\"joints\": [1], \"inverseBindMatrices\": 5}]"))
            .find("bad.gltf: skin 0: 2 inverseBindMatrices for 1 joints"),
        std::string::npos);
    EXPECT_NE(refusal(skinned.document("\"skins\": [{\"joints\": []}]"))
                  .find("bad.gltf: skin 0: no joints"),
              std::string::npos);
    SkinnedTriangles shortWeights;
    shortWeights.g.accessors[2] =
        "{\"bufferView\": 2, \"componentType\": 5126, \"count\": 1, \"type\": \"VEC4\"}";
    EXPECT_NE(refusal(shortWeights.document()).find("WEIGHTS_0 is not VEC4 of one per vertex"),
              std::string::npos);
}

// Extensions, morph targets, animations and attributes gpurt does not use: one warning each,
// naming them; the extensions the materials read and the geometry ones gpurt reads: none. Points
// and lines are left out with one warning per mode.
// EXT_mesh_gpu_instancing: the node's mesh once per instance, at the node's world transform times
// the instance's T R S (the extension's order), each vertex computed here by hand; ROTATION also as
// normalized shorts (the extension allows them); a custom attribute is a warning.
TEST(GltfInstancing, EachInstanceIsTheMeshAtTheNodeTimesItsTranslationRotationAndScale) {
    for (const bool shorts : {false, true}) {
        Gltf g;
        const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
        const int t = g.positions({0, 0, 0, 10, 0, 0, 0, 0, -5});
        // Instance 0: none; 1: 90 degrees about +y; 2: 180 degrees about +z.
        const float h = std::sqrt(0.5f);
        int r;
        if (shorts) {
            const std::vector<int16_t> q = {0, 0, 0, 32767, 0, int16_t(std::lround(h * 32767)), 0,
                                            int16_t(std::lround(h * 32767)), 0, 0, 32767, 0};
            r = g.accessor(g.view(q), 5122, 3, "VEC4", ", \"normalized\": true");
        } else {
            r = g.accessor(g.view(std::vector<float>{0, 0, 0, 1, 0, h, 0, h, 0, 0, 1, 0}), 5126, 3, "VEC4");
        }
        const int sc = g.positions({1, 1, 1, 2, 2, 2, 1, 3, 1});
        const std::string instancing = ", \"extensions\": {\"EXT_mesh_gpu_instancing\": {\"attributes\": "
                                       "{\"TRANSLATION\": " + std::to_string(t) + ", \"ROTATION\": " + std::to_string(r) +
                                       ", \"SCALE\": " + std::to_string(sc) + ", \"_ID\": " + std::to_string(t) + "}}}";
        const std::string rest = "\"extensionsUsed\": [\"EXT_mesh_gpu_instancing\"], " +
                                 oneMesh(p, "", ", \"translation\": [0, 100, 0]" + instancing);
        std::string warnings;
        ASSERT_NO_THROW(warnings = warningsOf(g.json(rest)));
        EXPECT_EQ(warnings, "scene.gltf: warning: node 0 EXT_mesh_gpu_instancing: attribute _ID is not used\n");
        // The triangle (0,0,0) (1,0,0) (0,1,0) under each instance, then the node's +100 y:
        // scale, then rotate (y by 90: (x, y, z) -> (z, y, -x); z by 180: (x, y, z) -> (-x, -y, z)), then move.
        const std::vector<Triangle> expected = {
            {{0, 100, 0}, {1, 100, 0}, {0, 101, 0}},
            {{10, 100, 0}, {10, 100, -2}, {10, 102, 0}},
            {{0, 100, -5}, {-1, 100, -5}, {0, 97, -5}}};
        expectSameTriangles(parse(g.json(rest)), expected, shorts ? 2e-4f : 1e-5f, shorts ? "shorts" : "floats");
    }
}

TEST(GltfInstancing, BrokenInstancesAreErrorsNamingTheNode) {
    Gltf g;
    const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const int two = g.positions({0, 0, 0, 1, 1, 1});
    const int three = g.positions({0, 0, 0, 1, 1, 1, 2, 2, 2});
    const int q = g.accessor(g.view(std::vector<float>{0, 0, 0, 0}), 5126, 1, "VEC4");
    auto doc = [&](const std::string& attributes) {
        return g.json(oneMesh(p, "", ", \"extensions\": {\"EXT_mesh_gpu_instancing\": {\"attributes\": {" + attributes + "}}}"));
    };
    EXPECT_REFUSED(doc("\"TRANSLATION\": " + std::to_string(two) + ", \"SCALE\": " + std::to_string(three)), "node 0 EXT_mesh_gpu_instancing: TRANSLATION has 2 instances, another attribute 3");
    EXPECT_REFUSED(doc("\"ROTATION\": " + std::to_string(two)), "node 0 EXT_mesh_gpu_instancing: ROTATION has 3 components, not 4");
    EXPECT_REFUSED(doc("\"ROTATION\": " + std::to_string(q)), "node 0 EXT_mesh_gpu_instancing: instance 0's rotation is zero");
    EXPECT_REFUSED(doc("\"TRANSLATION\": 99"), "node 0 EXT_mesh_gpu_instancing TRANSLATION: accessor 99 does not exist");
    EXPECT_REFUSED(doc(""), "node 0 EXT_mesh_gpu_instancing: no attributes object");
    ::testing::internal::CaptureStderr();  // (the warning of _ID)
    EXPECT_REFUSED(doc("\"_ID\": 0"), "node 0 EXT_mesh_gpu_instancing: none of TRANSLATION, ROTATION, SCALE");
    ::testing::internal::GetCapturedStderr();
    // Instances are capped with what one accessor may hold: a sparse accessor needs no data.
    const int many = g.accessor(-1, 5126, size_t(1) << 27, "VEC3", ", \"sparse\": {\"count\": 0, \"indices\": "
                                "{\"bufferView\": 0, \"componentType\": 5125}, \"values\": {\"bufferView\": 0}}");
    EXPECT_REFUSED(doc("\"TRANSLATION\": " + std::to_string(many)), "node 0 EXT_mesh_gpu_instancing: 134217728 instances of 3 vertices are too many");
}

// Morph targets at rest (the glTF spec, "Morph Targets"): each vertex's POSITION and NORMAL plus
// the targets' displacements times the weights, the node's `weights` over the mesh's, written by
// hand here; a weight count other than the targets' is refused.
TEST(GltfMorph, TargetsDisplaceTheMeshByTheirDefaultWeights) {
    Gltf g;
    const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const int n = g.positions({0, 0, 1, 0, 0, 1, 0, 0, 1});
    const int up = g.positions({0, 0, 2, 0, 0, 2, 0, 0, 2});       // target 0: +2 z everywhere
    const int stretch = g.positions({0, 0, 0, 4, 0, 0, 0, 0, 0});  // target 1: vertex 1 +4 x
    const int tilt = g.positions({2, 0, 0, 2, 0, 0, 2, 0, 0});     // target 1's NORMAL: +2 x
    auto doc = [&](const std::string& meshWeights, const std::string& nodeWeights) {
        return g.json("\"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0" + nodeWeights +
                      "}], \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(p) +
                      ", \"NORMAL\": " + std::to_string(n) + "}, \"targets\": [{\"POSITION\": " + std::to_string(up) +
                      "}, {\"POSITION\": " + std::to_string(stretch) + ", \"NORMAL\": " + std::to_string(tilt) + "}]}]" +
                      meshWeights + "}]");
    };
    // Mesh weights (0.5, 0.25): z + 1, vertex 1's x + 1, normals (0.5, 0, 1) normalized.
    const Scene mesh = parse(doc(", \"weights\": [0.5, 0.25]", ""));
    expectSameTriangles(mesh, {{{0, 0, 1}, {2, 0, 1}, {0, 1, 1}}}, 1e-6f, "mesh weights");
    const glm::vec3 tilted = glm::normalize(glm::vec3(0.5f, 0.0f, 1.0f));
    ASSERT_EQ(mesh.normals.size(), 1u);
    EXPECT_NEAR(glm::length(mesh.normals[0].n0 - tilted), 0.0f, 1e-6f);
    // The node's weights (0, 1) over the mesh's: vertex 1's x + 4, normals (2, 0, 1) normalized.
    const Scene node = parse(doc(", \"weights\": [0.5, 0.25]", ", \"weights\": [0, 1]"));
    expectSameTriangles(node, {{{0, 0, 0}, {5, 0, 0}, {0, 1, 0}}}, 1e-6f, "node weights");
    EXPECT_NEAR(glm::length(node.normals[0].n2 - glm::normalize(glm::vec3(2.0f, 0.0f, 1.0f))), 0.0f, 1e-6f);
    // No weights: the base shape.
    expectSameTriangles(parse(doc("", "")), {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, 0.0f, "no weights");
    EXPECT_REFUSED(doc(", \"weights\": [1]", ""), "mesh 0 primitive 0: 1 morph target weights for 2 targets");
    // A target of another count is refused before it is read: a sparse one of 2^27 needs no data.
    const int huge = g.accessor(-1, 5126, size_t(1) << 27, "VEC3", ", \"sparse\": {\"count\": 0, \"indices\": "
                                "{\"bufferView\": 0, \"componentType\": 5125}, \"values\": {\"bufferView\": 0}}");
    const std::string text = g.json("\"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0}], \"meshes\": [{\"primitives\": "
                                    "[{\"attributes\": {\"POSITION\": " + std::to_string(p) + "}, \"targets\": [{\"POSITION\": " +
                                    std::to_string(huge) + "}]}], \"weights\": [1]}]");
    EXPECT_REFUSED(text, "mesh 0 primitive 0 target 0 POSITION: not VEC3 of one per vertex");
}

TEST(GltfWarnings, WhatIsNotUsedIsNamedOnce) {
    Gltf g;
    const int p = g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const std::string rest =
        "\"extensionsUsed\": [\"KHR_materials_emissive_strength\", \"KHR_materials_transmission\", "
        "\"KHR_materials_ior\", "
        "\"KHR_texture_transform\", \"KHR_lights_punctual\", \"KHR_mesh_quantization\", "
        "\"KHR_draco_mesh_compression\", "
        "\"KHR_materials_variants\", \"KHR_materials_diffuse_transmission\", \"EXT_texture_webp\"], \"extensionsRequired\": "
        "[\"KHR_materials_variants\", \"EXT_texture_webp\"], "
        "\"animations\": [{\"channels\": [], \"samplers\": []}], "
        "\"scenes\": [{\"nodes\": [0, 1]}], \"nodes\": [{\"mesh\": 0}, {\"mesh\": 0}], \"meshes\": "
        "[{\"primitives\": ["
        "{\"attributes\": {\"POSITION\": " +
        std::to_string(p) + ", \"_BATCHID\": " + std::to_string(p) +
        ", \"TANGENT\": " + std::to_string(p) +
        "}, \"targets\": [{\"POSITION\": " + std::to_string(p) + ", \"TEXCOORD_0\": " + std::to_string(p) +
        "}]},"
        "{\"attributes\": {\"POSITION\": " +
        std::to_string(p) +
        "}, \"mode\": 1},"
        "{\"attributes\": {\"POSITION\": " +
        std::to_string(p) +
        "}, \"mode\": 1},"
        "{\"attributes\": {\"POSITION\": " +
        std::to_string(p) +
        "}, \"mode\": 0},"
        "{\"attributes\": {\"POSITION\": " +
        std::to_string(p) + "}, \"mode\": 5}]}]";
    std::string warnings;
    ASSERT_NO_THROW(warnings = warningsOf(g.json(rest)));
    const std::vector<std::string> expected = {
        "scene.gltf: warning: extension KHR_materials_variants is not used (the file requires it): each "
        "primitive's default material is drawn, not its variants\n",
        "scene.gltf: warning: extension KHR_materials_diffuse_transmission is not used: no light passes through "
        "surfaces diffusely\n",
        "scene.gltf: warning: extension EXT_texture_webp is not used (the file requires it: the picture may be "
        "wrong)\n",
        "scene.gltf: warning: 1 animation is not used; the scene is drawn at rest (its nodes' own "
        "transforms)\n",
        "scene.gltf: warning: mesh 0 primitive 0: attribute _BATCHID is not used\n",
        "scene.gltf: warning: mesh 0 primitive 0: morph target attribute TEXCOORD_0 is not used\n",
        "scene.gltf: warning: mesh 0 primitive 3: mode POINTS is not triangles and is left out "
        "(gpurt draws triangles); so is 1 more primitive of that mode\n",
        "scene.gltf: warning: mesh 0 primitive 1: mode LINES is not triangles and is left out "
        "(gpurt draws triangles); "
        "so are 3 more primitives of that mode\n"};
    std::string all;
    for (const std::string& line : expected) all += line;
    EXPECT_EQ(warnings, all);
    const Scene scene = parse(g.json(rest));
    EXPECT_EQ(scene.triangles.size(), 2u * 2u);  // each node: the triangle and the strip's one
}

}  // namespace
}  // namespace gpurt
