// Packed scene files (PackedScene.h, docs/PACKED_FORMAT.md): the round trip keeps every field,
// every grid array and every texel bit for bit; the bytes are the same for any thread count; the
// CPU backend renders a packed scene exactly as its source; and every kind of damage is refused
// with one line naming the file, never a crash. Damaged files are made by reading and patching
// the documented layout here (with zlib's CRC-32 to reseal them), independently of the writer.
#include "raytrace/accel/bvh/BvhAccelerator.h"
#include "raytrace/accel/grid/GridAccelerator.h"
#include "raytrace/scene/PackedScene.h"
#include "raytrace/accel/bvh/Bvh.h"

#include <gtest/gtest.h>

#include "../common/Refusal.h"
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "raytrace/camera/Camera.h"
#include "raytrace/render/CpuTracer.h"
#include "image/InputError.h"
#include "scene/ObjLoader.h"
#include "raytrace/scene/SceneLoader.h"
#include "raytrace/textures/SceneTextureLayout.h"
#include "raytrace/accel/bvh/BvhTexels.h"
#include "raytrace/accel/grid/GridTexels.h"

namespace gpurt {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<unsigned char>;

// --- The documented layout, read and patched independently of PackedScene.cpp ---------------

uint32_t get32(const Bytes& b, size_t at) {
    uint32_t v = 0;
    for (int k = 3; k >= 0; --k) v = v << 8 | b.at(at + size_t(k));
    return v;
}
uint64_t get64(const Bytes& b, size_t at) {
    return get32(b, at) | uint64_t(get32(b, at + 4)) << 32;
}
void put32(Bytes& b, size_t at, uint32_t v) {
    for (int k = 0; k < 4; ++k) b.at(at + size_t(k)) = static_cast<unsigned char>(v >> (8 * k));
}
void put64(Bytes& b, size_t at, uint64_t v) {
    put32(b, at, static_cast<uint32_t>(v));
    put32(b, at + 4, static_cast<uint32_t>(v >> 32));
}

// The CRC-32 field (offset 12) over bytes 16..end, recomputed after a patch.
void reseal(Bytes& b) {
    put32(b, 12, static_cast<uint32_t>(crc32(0L, b.data() + 16, static_cast<uInt>(b.size() - 16))));
}

struct Entry {
    size_t at;  // of the table entry
    uint64_t offset, size;
};

// The section table entry with this tag (header: 32 bytes; entries of 24 bytes from offset 32:
// tag, reserved, u64 offset, u64 size), if there is one.
std::optional<Entry> findSection(const Bytes& b, const char* tag) {
    const uint32_t count = get32(b, 24);
    for (uint32_t k = 0; k < count; ++k) {
        const size_t at = 32 + 24 * size_t(k);
        if (std::memcmp(b.data() + at, tag, 4) == 0)
            return Entry{at, get64(b, at + 8), get64(b, at + 16)};
    }
    return std::nullopt;
}

Entry section(const Bytes& b, const char* tag) {
    if (const std::optional<Entry> entry = findSection(b, tag)) return *entry;
    ADD_FAILURE() << "no section " << tag;
    return {0, 0, 0};
}

// A file of the header of `header` and the given sections (each from its file, by tag), laid out
// in that order as the layout says (8-byte aligned), its size and checksum rewritten: what another
// writer may have stored.
Bytes relaidOut(const Bytes& header, const std::vector<std::pair<const Bytes*, std::string>>& sections) {
    Bytes out(header.begin(), header.begin() + 32);
    put32(out, 24, uint32_t(sections.size()));
    out.resize(32 + 24 * sections.size(), 0);
    for (size_t k = 0; k < sections.size(); ++k) {
        const auto& [file, tag] = sections[k];
        const Entry e = section(*file, tag.c_str());
        while (out.size() % 8 != 0) out.push_back(0);
        const size_t at = 32 + 24 * k;
        std::memcpy(&out[at], tag.data(), 4);
        put64(out, at + 8, out.size());
        put64(out, at + 16, e.size);
        out.insert(out.end(), file->begin() + std::ptrdiff_t(e.offset), file->begin() + std::ptrdiff_t(e.offset + e.size));
    }
    while (out.size() % 8 != 0) out.push_back(0);
    put64(out, 16, out.size());
    reseal(out);
    return out;
}

// The same with every section from `file`, in the order of `tags`.
Bytes relaidOut(const Bytes& file, const std::vector<std::string>& tags) {
    std::vector<std::pair<const Bytes*, std::string>> sections;
    for (const std::string& tag : tags) sections.emplace_back(&file, tag);
    return relaidOut(file, sections);
}

// The tags of a file's section table, in table order.
std::vector<std::string> sectionTags(const Bytes& b) {
    std::vector<std::string> tags;
    for (uint32_t k = 0; k < get32(b, 24); ++k) tags.emplace_back(reinterpret_cast<const char*>(&b[32 + 24 * size_t(k)]), 4);
    return tags;
}

// --- Scenes ------------------------------------------------------------------------------------

LoadedScene objScene(const char* model) {
    return LoadedScene{loadObj(std::string("../shared/models/") + model), std::nullopt, nullptr};
}

// Every field set, with values a careless writer would get wrong: -0, a denormal, the largest
// float, material names of every length modulo 4 (padding) and with non-ASCII bytes.
LoadedScene unusualScene() {
    LoadedScene loaded = objScene("cornell_box.obj");
    Scene& s = loaded.scene;
    for (int k = 0; k < 5; ++k) {
        Material m;
        m.name = std::string(size_t(k), 'a') + (k == 3 ? "\xff\x01" : "");
        m.diffuse = glm::vec3(-0.0f, std::numeric_limits<float>::denorm_min(), 0.25f * float(k));
        m.specular = glm::vec3(std::numeric_limits<float>::max(), 0.5f, 1.0f);
        m.shininess = 200.0f + float(k);
        m.reflectivity = glm::vec3(0.1f * float(k));
        s.materials.push_back(m);
    }
    for (size_t t = 0; t < s.materialIds.size(); ++t)
        s.materialIds[t] = uint32_t(t % s.materials.size());
    s.lights.push_back({{1.5f, -2.0f, 3.0f}, {0.9f, 0.8f, 0.7f}, 123.0f});
    s.lights.push_back({{-0.0f, 0.0f, 1e30f}, {0.0f, 0.0f, 0.0f}, 0.0f});
    Light spot;  // the kinds travel in their own section
    spot.kind = LightKind::Spot;
    spot.position = {1, 2, 3};
    spot.direction = {0.6f, -0.8f, 0.0f};
    spot.innerCone = 0.125f;
    spot.outerCone = 0.5f;
    spot.range = 12.5f;
    s.lights.push_back(spot);
    Light sun;
    sun.kind = LightKind::Directional;
    sun.direction = {0, -1, 0};
    sun.intensity = 2.5f;
    s.lights.push_back(sun);
    s.camera =
        CameraSpec{{278.0f, 273.0f, -800.0f}, {278.0f, 273.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 39.3077f};
    s.camera->fstop = 2.8f;  // the lens travels in its own section
    s.camera->focusDistance = 650.5f;
    s.camera->blades = 7;
    s.camera->bladeRotation = -12.5f;
    CameraAnimation animation;
    animation.fps = 23.976f;
    animation.keys.push_back({-0.5f, CameraSpec{{1, 2, 3}, {0, 0, 0}, {0, 1, 0}, 10.0f}});
    animation.keys.push_back({0.25f, CameraSpec{{-1, 2, 3e10f}, {0, 0, -0.0f}, {1, 0, 0}, 170.0f}});
    s.animation = animation;
    // Two textures (names of lengths 1 and 6, each wrap mode), one of them used by two
    // materials, and texture coordinates with -0, a denormal and values far outside [0, 1].
    for (int k = 0; k < 2; ++k) {
        Texture t;
        t.name = k == 0 ? "a" : "b\xff.jpeg";
        t.image.width = 3 - k;
        t.image.height = 2 + k;
        for (uint32_t i = 0; i < 6; ++i) t.image.texels.push_back(0x80402010u * (i + 1) + uint32_t(k));
        t.wrapS = uint32_t(k == 0 ? kWrapMirror : kWrapClamp);
        t.wrapT = uint32_t(k == 0 ? kWrapRepeat : kWrapMirror);
        s.textures.push_back(t);
    }
    s.materials[1].diffuseTexture = 1;
    s.materials[2].diffuseTexture = 0;
    s.materials[3].diffuseTexture = 1;
    for (size_t t = 0; t < s.triangles.size(); ++t)
        s.texcoords.push_back({{-0.0f, std::numeric_limits<float>::denorm_min()}, {float(t), -1e6f}, {0.5f, 2.0f}});
    s.background = glm::vec3(0.125f, -0.0f, 3.5f);
    s.maxBounces = 7;
    loaded.size = glm::ivec2(321, 123);
    return loaded;
}

template <class T>
bool sameBits(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

void expectSameScene(const LoadedScene& a, const LoadedScene& b) {
    const Scene &x = a.scene, &y = b.scene;
    ASSERT_EQ(x.triangles.size(), y.triangles.size());
    for (size_t t = 0; t < x.triangles.size(); ++t) {
        ASSERT_TRUE(sameBits(x.triangles[t].v0, y.triangles[t].v0)) << "triangle " << t;
        ASSERT_TRUE(sameBits(x.triangles[t].v1, y.triangles[t].v1)) << "triangle " << t;
        ASSERT_TRUE(sameBits(x.triangles[t].v2, y.triangles[t].v2)) << "triangle " << t;
    }
    EXPECT_EQ(x.materialIds, y.materialIds);
    ASSERT_EQ(x.materials.size(), y.materials.size());
    for (size_t m = 0; m < x.materials.size(); ++m) {
        EXPECT_TRUE(sameBits(x.materials[m].diffuse, y.materials[m].diffuse)) << m;
        EXPECT_TRUE(sameBits(x.materials[m].specular, y.materials[m].specular)) << m;
        EXPECT_TRUE(sameBits(x.materials[m].shininess, y.materials[m].shininess)) << m;
        EXPECT_TRUE(sameBits(x.materials[m].reflectivity, y.materials[m].reflectivity)) << m;
        EXPECT_EQ(x.materials[m].name, y.materials[m].name) << m;
        EXPECT_EQ(x.materials[m].diffuseTexture, y.materials[m].diffuseTexture) << m;
        EXPECT_EQ(x.materials[m].alphaMode, y.materials[m].alphaMode) << m;
        EXPECT_EQ(x.materials[m].doubleSided, y.materials[m].doubleSided) << m;
        EXPECT_TRUE(sameBits(x.materials[m].alphaFactor, y.materials[m].alphaFactor)) << m;
        EXPECT_TRUE(sameBits(x.materials[m].alphaCutoff, y.materials[m].alphaCutoff)) << m;
        EXPECT_EQ(x.materials[m].alphaTexture.texture, y.materials[m].alphaTexture.texture) << m;
        EXPECT_EQ(x.materials[m].alphaTexture.channel, y.materials[m].alphaTexture.channel) << m;
        EXPECT_EQ(x.materials[m].transmissionTexture.texture, y.materials[m].transmissionTexture.texture) << m;
        EXPECT_EQ(x.materials[m].transmissionTexture.channel, y.materials[m].transmissionTexture.channel) << m;
        const Material &a = x.materials[m], &b = y.materials[m];  // LAYR
        EXPECT_TRUE(sameBits(a.sheenColor, b.sheenColor) && sameBits(a.sheenRoughness, b.sheenRoughness) &&
                    a.sheenColorTexture == b.sheenColorTexture && a.sheenRoughnessTexture.texture == b.sheenRoughnessTexture.texture &&
                    a.sheenRoughnessTexture.channel == b.sheenRoughnessTexture.channel)
            << m;
        EXPECT_TRUE(sameBits(a.thickness, b.thickness) && sameBits(a.attenuationColor, b.attenuationColor) &&
                    sameBits(a.attenuationDistance, b.attenuationDistance))
            << m;  // VOLM
        EXPECT_TRUE(sameBits(a.iridescenceFactor, b.iridescenceFactor) && sameBits(a.iridescenceIor, b.iridescenceIor) &&
                    sameBits(a.iridescenceThicknessMin, b.iridescenceThicknessMin) &&
                    sameBits(a.iridescenceThicknessMax, b.iridescenceThicknessMax) &&
                    a.iridescenceTexture.texture == b.iridescenceTexture.texture &&
                    a.iridescenceTexture.channel == b.iridescenceTexture.channel &&
                    a.iridescenceThicknessTexture.texture == b.iridescenceThicknessTexture.texture &&
                    a.iridescenceThicknessTexture.channel == b.iridescenceThicknessTexture.channel)
            << m;  // IRID
        EXPECT_TRUE(sameBits(a.anisotropyStrength, b.anisotropyStrength) &&
                    sameBits(a.anisotropyRotation, b.anisotropyRotation) && a.anisotropyTexture == b.anisotropyTexture)
            << m;  // ANIS
        EXPECT_EQ(a.thinWalled, b.thinWalled) << m;  // THIN
        EXPECT_TRUE(sameBits(a.dispersion, b.dispersion)) << m;  // DISP
        EXPECT_TRUE(sameBits(a.specularFactor, b.specularFactor) && sameBits(a.specularColor, b.specularColor) &&
                    sameBits(a.clearcoat, b.clearcoat) && sameBits(a.clearcoatRoughness, b.clearcoatRoughness) &&
                    sameBits(a.clearcoatNormalScale, b.clearcoatNormalScale))
            << m;
        EXPECT_TRUE(a.specularTexture.texture == b.specularTexture.texture && a.specularTexture.channel == b.specularTexture.channel &&
                    a.specularColorTexture == b.specularColorTexture && a.clearcoatTexture.texture == b.clearcoatTexture.texture &&
                    a.clearcoatTexture.channel == b.clearcoatTexture.channel &&
                    a.clearcoatRoughnessTexture.texture == b.clearcoatRoughnessTexture.texture &&
                    a.clearcoatRoughnessTexture.channel == b.clearcoatRoughnessTexture.channel &&
                    a.clearcoatNormalTexture == b.clearcoatNormalTexture)
            << m;
    }
    ASSERT_EQ(x.textures.size(), y.textures.size());
    for (size_t k = 0; k < x.textures.size(); ++k) {
        const Texture &p = x.textures[k], &q = y.textures[k];
        EXPECT_EQ(p.name, q.name) << k;
        EXPECT_EQ(p.image.width, q.image.width) << k;
        EXPECT_EQ(p.image.height, q.image.height) << k;
        EXPECT_EQ(p.image.texels, q.image.texels) << k;
        EXPECT_EQ(p.wrapS, q.wrapS) << k;
        EXPECT_EQ(p.wrapT, q.wrapT) << k;
    }
    ASSERT_EQ(x.texcoords.size(), y.texcoords.size());
    for (size_t t = 0; t < x.texcoords.size(); ++t)
        ASSERT_TRUE(sameBits(x.texcoords[t], y.texcoords[t])) << "texture coordinates " << t;
    ASSERT_EQ(x.colors.size(), y.colors.size());
    for (size_t t = 0; t < x.colors.size(); ++t)
        ASSERT_TRUE(sameBits(x.colors[t], y.colors[t])) << "vertex colours " << t;
    ASSERT_EQ(x.tangents.size(), y.tangents.size());
    for (size_t t = 0; t < x.tangents.size(); ++t)
        ASSERT_TRUE(sameBits(x.tangents[t], y.tangents[t])) << "vertex tangents " << t;
    ASSERT_EQ(x.lights.size(), y.lights.size());
    for (size_t l = 0; l < x.lights.size(); ++l) {
        EXPECT_TRUE(sameBits(x.lights[l].position, y.lights[l].position)) << l;
        EXPECT_TRUE(sameBits(x.lights[l].color, y.lights[l].color)) << l;
        EXPECT_TRUE(sameBits(x.lights[l].intensity, y.lights[l].intensity)) << l;
        EXPECT_EQ(x.lights[l].kind, y.lights[l].kind) << l;
        EXPECT_TRUE(sameBits(x.lights[l].direction, y.lights[l].direction)) << l;
        EXPECT_TRUE(sameBits(x.lights[l].innerCone, y.lights[l].innerCone) &&
                    sameBits(x.lights[l].outerCone, y.lights[l].outerCone) && sameBits(x.lights[l].range, y.lights[l].range))
            << l;
    }
    ASSERT_EQ(x.camera.has_value(), y.camera.has_value());
    if (x.camera) {
        EXPECT_TRUE(sameBits(x.camera->eye, y.camera->eye));
        EXPECT_TRUE(sameBits(x.camera->target, y.camera->target));
        EXPECT_TRUE(sameBits(x.camera->up, y.camera->up));
        EXPECT_TRUE(sameBits(x.camera->fovy, y.camera->fovy));
        EXPECT_TRUE(sameBits(x.camera->lensRadius, y.camera->lensRadius) && sameBits(x.camera->fstop, y.camera->fstop) &&
                    sameBits(x.camera->focusDistance, y.camera->focusDistance) && x.camera->blades == y.camera->blades &&
                    sameBits(x.camera->bladeRotation, y.camera->bladeRotation));
    }
    ASSERT_EQ(x.animation.has_value(), y.animation.has_value());
    if (x.animation) {
        EXPECT_TRUE(sameBits(x.animation->fps, y.animation->fps));
        ASSERT_EQ(x.animation->keys.size(), y.animation->keys.size());
        for (size_t k = 0; k < x.animation->keys.size(); ++k) {
            const CameraKey &p = x.animation->keys[k], &q = y.animation->keys[k];
            EXPECT_TRUE(sameBits(p.time, q.time) && sameBits(p.camera.eye, q.camera.eye) &&
                        sameBits(p.camera.target, q.camera.target) && sameBits(p.camera.up, q.camera.up) &&
                        sameBits(p.camera.fovy, q.camera.fovy))
                << "animation key " << k;
        }
    }
    EXPECT_TRUE(sameBits(x.background, y.background));
    EXPECT_EQ(x.maxBounces, y.maxBounces);
    EXPECT_EQ(a.size, b.size);
}

void expectSameGrid(const UniformGrid& a, const UniformGrid& b) {
    EXPECT_EQ(a.resolution, b.resolution);
    EXPECT_TRUE(sameBits(a.min, b.min));
    EXPECT_TRUE(sameBits(a.max, b.max));
    EXPECT_TRUE(sameBits(a.cellSize, b.cellSize));
    EXPECT_EQ(a.cellStart, b.cellStart);
    EXPECT_EQ(a.cellTriangles, b.cellTriangles);
}

void expectSameTextures(const LoadedScene& a, const UniformGrid& gridA, const LoadedScene& b,
                        const UniformGrid& gridB) {
    const std::vector<TextureTexels> x = sceneTextureTexels(a.scene, gridA);
    const std::vector<TextureTexels> y = sceneTextureTexels(b.scene, gridB);
    ASSERT_EQ(x.size(), y.size());
    for (size_t k = 0; k < x.size(); ++k) {
        EXPECT_EQ(x[k].name, y[k].name);
        EXPECT_EQ(x[k].width, y[k].width) << x[k].name;
        EXPECT_EQ(x[k].rows, y[k].rows) << x[k].name;
        EXPECT_EQ(x[k].channels, y[k].channels) << x[k].name;
        EXPECT_EQ(x[k].uints, y[k].uints) << x[k].name;
        ASSERT_EQ(x[k].floats.size(), y[k].floats.size()) << x[k].name;
        if (!x[k].floats.empty()) {
            EXPECT_EQ(std::memcmp(x[k].floats.data(), y[k].floats.data(), x[k].floats.size() * 4),
                      0)
                << x[k].name;
        }
    }
}

void expectRoundTrip(const LoadedScene& source) {
    const UniformGrid grid = buildGrid(source.scene, {});
    const Bytes bytes = encodePackedScene(source, *makeStructure(grid), "source");
    const LoadedScene packed = decodePackedScene(bytes, "packed.gpscene");
    ASSERT_TRUE(gridOf(packed.accel));
    expectSameScene(source, packed);
    expectSameGrid(grid, *gridOf(packed.accel));
    expectSameTextures(source, grid, packed, *gridOf(packed.accel));
    // And again: packing what was read gives the same bytes.
    EXPECT_EQ(encodePackedScene(packed, *packed.accel, "again"), bytes);
}

// The message of the InputError that decoding `bytes` throws (Refusal.h).
std::string refusal(const Bytes& bytes) {
    return test::refusalOf([&] { decodePackedScene(bytes, "damaged.gpscene"); }, "damaged.gpscene: ");
}

class PackedSceneTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("gpurt-packed-" + std::to_string(::getpid()) + "-" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        source_ = unusualScene();
        grid_ = buildGrid(source_.scene, {});
        bytes_ = encodePackedScene(source_, *makeStructure(grid_), "source");
    }
    void TearDown() override { fs::remove_all(dir_); }

    // The packed source (or `b`) with `patch` applied and the checksum made right again.
    template <class Patch>
    static Bytes patched(Bytes b, Patch patch) {
        patch(b);
        reseal(b);
        return b;
    }
    template <class Patch>
    Bytes patched(Patch patch) const {
        return patched(bytes_, patch);
    }

    fs::path dir_;
    LoadedScene source_;
    UniformGrid grid_;
    Bytes bytes_;
};

// --- Round trip and determinism ------------------------------------------------------------

TEST_F(PackedSceneTest, RoundTripKeepsEveryFieldAndTexel) {
    expectRoundTrip(source_);
    for (const char* model : {"teapot.obj", "cornell_box.obj", "bunny_lo.obj"}) {
        SCOPED_TRACE(model);
        expectRoundTrip(objScene(model));
    }
    SCOPED_TRACE("scenes/highlow.json");
    expectRoundTrip(loadScene("scenes/highlow.json"));
}

TEST_F(PackedSceneTest, RoundTripOfAnEmptyScene) {
    LoadedScene empty;
    empty.scene.materials.push_back(Material{});
    expectRoundTrip(empty);
}

TEST_F(PackedSceneTest, HeaderFollowsTheDocumentedLayout) {
    EXPECT_EQ(std::string(bytes_.begin(), bytes_.begin() + 8), "GPRTSCN1");
    EXPECT_EQ(get32(bytes_, 8), 2u);
    EXPECT_EQ(get64(bytes_, 16), bytes_.size());
    EXPECT_EQ(get32(bytes_, 12), uint32_t(crc32(0L, bytes_.data() + 16, uInt(bytes_.size() - 16))));
    // Triangles: u64 count, 9 floats a triangle, then one u32 material id a triangle.
    const Entry tris = section(bytes_, "TRIS");
    const size_t n = source_.scene.triangles.size();
    EXPECT_EQ(tris.offset % 8, 0u);
    EXPECT_EQ(tris.size, 8 + 40 * n);
    EXPECT_EQ(get64(bytes_, tris.offset), n);
    EXPECT_EQ(std::bit_cast<float>(get32(bytes_, tris.offset + 8 + 4)),
              source_.scene.triangles[0].v0.y);
    EXPECT_EQ(get32(bytes_, tris.offset + 8 + 36 * n + 4 * 5), source_.scene.materialIds[5]);
    // The grid arrays, as UniformGrid holds them.
    const Entry cells = section(bytes_, "CELL"), list = section(bytes_, "LIST");
    EXPECT_EQ(cells.size, 4 * (grid_.cells() + 1));
    EXPECT_EQ(list.size, 4 * grid_.cellTriangles.size());
    EXPECT_EQ(get32(bytes_, cells.offset + 4 * grid_.cells()), grid_.cellTriangles.size());
    const Entry g = section(bytes_, "GRID");
    EXPECT_EQ(int(get32(bytes_, g.offset + 4)), grid_.resolution.y);
    EXPECT_EQ(std::bit_cast<float>(get32(bytes_, g.offset + 12 + 12)), grid_.max.x);
}

TEST_F(PackedSceneTest, FilesAreRecognisedByTheirMagicAndCarryTheirGrid) {
    // Named like an OBJ; the magic decides.
    const fs::path path = dir_ / "looks-like.obj";
    writePackedScene(path, source_, *makeStructure(grid_), "source");
    const LoadedScene loaded = loadScene(path);
    ASSERT_TRUE(gridOf(loaded.accel));
    expectSameScene(source_, loaded);
    expectSameGrid(grid_, *gridOf(loaded.accel));
    // Written atomically: nothing but the file in the folder.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
    std::ifstream in(path, std::ios::binary);
    EXPECT_EQ(Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()), bytes_);
}

TEST_F(PackedSceneTest, SameBytesForAnyThreadCount) {
    const LoadedScene bunny = objScene("bunny_lo.obj");
    GridOptions options;
    options.threads = 1;
    const Bytes one = encodePackedScene(bunny, *makeStructure(buildGrid(bunny.scene, options)), "bunny_lo");
    for (int threads : {2, 3, 8, 0}) {
        options.threads = threads;
        EXPECT_EQ(encodePackedScene(bunny, *makeStructure(buildGrid(bunny.scene, options)), "bunny_lo"), one)
            << threads << " threads";
    }
}

TEST_F(PackedSceneTest, CpuBackendRendersThePackedSceneExactlyAsItsSource) {
    const LoadedScene teapot = objScene("teapot.obj");
    const UniformGrid grid = buildGrid(teapot.scene, {});
    const LoadedScene packed =
        decodePackedScene(encodePackedScene(teapot, *makeStructure(grid), "teapot"), "teapot.gpscene");
    const CameraBasis camera = makeCamera({{20, 15, 40}, {0, 0, 0}, {0, 1, 0}, 45.0f}, 40, 30);
    RenderSettings settings;
    settings.width = 40;
    settings.height = 30;
    const RenderOutput a = CpuTracer(teapot.scene, grid).render(camera, settings);
    const RenderOutput b = CpuTracer(packed.scene, *gridOf(packed.accel)).render(camera, settings);
    auto bytesOf = [](const auto& v) { return v.size() * sizeof(v[0]); };
    ASSERT_EQ(a.color.size(), b.color.size());
    EXPECT_EQ(std::memcmp(a.color.data(), b.color.data(), bytesOf(a.color)), 0);
    EXPECT_EQ(std::memcmp(a.depth.data(), b.depth.data(), bytesOf(a.depth)), 0);
    EXPECT_EQ(std::memcmp(a.prim.data(), b.prim.data(), bytesOf(a.prim)), 0);
    EXPECT_EQ(std::memcmp(a.normal.data(), b.normal.data(), bytesOf(a.normal)), 0);
    EXPECT_EQ(std::memcmp(a.steps.data(), b.steps.data(), bytesOf(a.steps)), 0);
}

// --- The writer refuses what the reader would --------------------------------------------------

TEST_F(PackedSceneTest, WriterRefusesScenesItCannotPack) {
    LoadedScene bad = source_;
    bad.scene.materialIds[3] = uint32_t(bad.scene.materials.size());
    EXPECT_THROW(encodePackedScene(bad, *makeStructure(grid_), "source"), InputError);
    UniformGrid otherGrid = buildGrid(objScene("teapot.obj").scene, {});
    try {
        encodePackedScene(source_, *makeStructure(otherGrid), "source.obj");
        ADD_FAILURE() << "a grid of another scene was packed";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("source.obj: ", 0), 0u) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir_ / "x.gpscene"));
    EXPECT_THROW(writePackedScene(dir_ / "x.gpscene", bad, *makeStructure(grid_), "source"), InputError);
    EXPECT_FALSE(fs::exists(dir_ / "x.gpscene"));
}

// Material and light values outside the ranges a JSON scene allows (the shading relies on them;
// a negative shininess made NaN pixels, found by fuzz_packed) are refused by writer and reader.
TEST_F(PackedSceneTest, RefusesMaterialAndLightValuesOutOfRange) {
    const auto refused = [&](LoadedScene scene, const char* what) {
        try {
            encodePackedScene(scene, *makeStructure(grid_), "source");
            ADD_FAILURE() << what << " was packed";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("must be"), std::string::npos) << e.what();
        }
    };
    LoadedScene s = source_;
    s.scene.materials[0].shininess = -1.0f;
    refused(s, "negative shininess");
    s = source_;
    s.scene.materials[0].reflectivity = glm::vec3(0.5f, 1.5f, 0.5f);
    refused(s, "reflectivity above 1");
    s = source_;
    s.scene.materials[0].diffuse.y = -0.25f;
    refused(s, "negative diffuse");
    s = source_;
    s.scene.lights.push_back(Light{glm::vec3(0.0f), glm::vec3(1.0f), -2.0f});
    refused(s, "negative intensity");
    s = source_;
    s.scene.background = glm::vec3(-1.0f, 0.0f, 0.0f);
    refused(s, "negative background");
}

// --- Damage ------------------------------------------------------------------------------------

TEST_F(PackedSceneTest, RefusesAWrongMagic) {
    Bytes b = bytes_;
    b[3] = 'X';
    EXPECT_REFUSED(b, "wrong magic");
    EXPECT_REFUSED((Bytes{'h', 'e', 'l', 'l', 'o'}), "wrong magic");
}

TEST_F(PackedSceneTest, RefusesATruncatedFile) {
    for (size_t size :
         {size_t(0), size_t(5), size_t(8), size_t(11), size_t(12), size_t(31), size_t(32),
          size_t(100), bytes_.size() / 2, bytes_.size() - 8, bytes_.size() - 1}) {
        SCOPED_TRACE(size);
        EXPECT_REFUSED(Bytes(bytes_.begin(), bytes_.begin() + std::ptrdiff_t(size)), "truncated");
    }
}

TEST_F(PackedSceneTest, RefusesAFlippedByteByItsChecksum) {
    for (size_t at :
         {size_t(12), size_t(16), size_t(24), size_t(40), section(bytes_, "TRIS").offset + 20,
          section(bytes_, "LIST").offset, bytes_.size() - 1}) {
        SCOPED_TRACE(at);
        Bytes b = bytes_;
        b[at] ^= 0x10;
        // A flip in the file size field reads as a file of another length.
        EXPECT_REFUSED(b, at >= 16 && at < 24 ? "bytes" : "checksum mismatch");
    }
}

TEST_F(PackedSceneTest, RefusesAnUnknownVersionAndSaysWhichItKnows) {
    Bytes b = bytes_;
    put32(b, 8, 3);
    reseal(b);
    EXPECT_REFUSED(b, "unknown packed format version 3 (this gpurt reads version 2)");
    put32(b, 8, 1);  // version 1 had no emission in its materials
    reseal(b);
    EXPECT_REFUSED(b, "unknown packed format version 1 (this gpurt reads version 2)");
    put32(b, 8, 0xffffffffu);
    EXPECT_REFUSED(b, "version 4294967295");
}

TEST_F(PackedSceneTest, RefusesAFileSizeThatDisagreesWithTheHeader) {
    Bytes longer = bytes_;
    longer.resize(bytes_.size() + 8, 0);
    reseal(longer);
    EXPECT_REFUSED(longer, "trailing data");
    Bytes lying = bytes_;
    put64(lying, 16, uint64_t(1) << 40);
    reseal(lying);
    EXPECT_REFUSED(lying, "truncated");
}

// Patches with a correct checksum: only the reader's own checks stand between them and a crash.
TEST_F(PackedSceneTest, RefusesSizesThatLie) {
    const Entry tris = section(bytes_, "TRIS");
    const uint64_t n = source_.scene.triangles.size();
    EXPECT_REFUSED(patched([&](Bytes& b) { put64(b, tris.offset, n + 1); }), "do not fit");
    EXPECT_REFUSED(patched([&](Bytes& b) { put64(b, tris.offset, n - 1); }), "do not fit");
    EXPECT_REFUSED(patched([&](Bytes& b) { put64(b, tris.offset, uint64_t(1) << 62); }),
                   "triangles");
    // Beyond the GL backend's exact-id limit, refused before the section size is even looked at.
    EXPECT_REFUSED(patched([&](Bytes& b) { put64(b, tris.offset, uint64_t(1) << 24); }),
                   "16777216 triangles; at most 16777215");
    // Section sizes and offsets past the end, overflowing, misaligned or overlapping.
    EXPECT_REFUSED(patched([&](Bytes& b) { put64(b, tris.at + 16, ~uint64_t(0)); }),
                   "does not fit");
    EXPECT_REFUSED(patched([&](Bytes& b) { put64(b, tris.at + 16, b.size()); }), "does not fit");
    EXPECT_REFUSED(patched([&](Bytes& b) { put64(b, tris.at + 8, ~uint64_t(7)); }), "does not fit");
    EXPECT_REFUSED(patched([&](Bytes& b) { put64(b, tris.at + 8, tris.offset + 4); }),
                   "does not fit");
    EXPECT_REFUSED(patched([&](Bytes& b) { put64(b, section(b, "MATS").at + 8, tris.offset); }),
                   "does not fit");
    // The section table.
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, 24, 0xffffffffu); }), "section table");
    {  // the last section, when it is a required one (ANIM, TXCO, TEXS and LENS, optional, come
       // last when there are some)
        LoadedScene still = source_;
        still.scene.animation.reset();
        still.scene.camera->fstop = 0.0f;
        still.scene.lights.resize(2);  // the point lights alone: no LGTX
        still.scene.texcoords.clear();
        still.scene.textures.clear();
        for (Material& m : still.scene.materials) m.diffuseTexture = -1;
        Bytes b = encodePackedScene(still, *makeStructure(grid_), "still");
        put32(b, 24, get32(b, 24) - 1);
        reseal(b);
        EXPECT_REFUSED(b, "LIST");
    }
    EXPECT_REFUSED(patched([&](Bytes& b) { std::memcpy(b.data() + tris.at, "TRIX", 4); }),
                   "unknown section 'TRIX'");
    EXPECT_REFUSED(
        patched([&](Bytes& b) { std::memcpy(b.data() + section(b, "MATS").at, "TRIS", 4); }),
        "appears twice");
    // Counts of materials and lights, and a material name running past its section.
    const Entry mats = section(bytes_, "MATS");
    EXPECT_REFUSED(patched([&](Bytes& b) { put64(b, mats.offset, uint64_t(1) << 40); }),
                   "materials");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, mats.offset + 8 + 68, 0x7fffffffu); }),
                   "runs past");
    EXPECT_REFUSED(patched([&](Bytes& b) { put64(b, section(b, "LGTS").offset, 1000); }),
                   "do not fit");
}

// The texture section's sizes and indices, patched with a correct checksum.
TEST_F(PackedSceneTest, RefusesTexturesThatLie) {
    const Entry texs = section(bytes_, "TEXS");
    const Entry txco = section(bytes_, "TXCO");
    const size_t first = texs.offset + 8;  // texture 0: width, height, wrap s, wrap t, name length
    EXPECT_REFUSED(patched([&](Bytes& b) { put64(b, texs.offset, uint64_t(1) << 40); }), "textures");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, first, 20000); }), "texture 0: size 20000x2");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, first + 4, 0); }), "texture 0: size 3x0");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, first, 4000); }), "runs past the section's end");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, first + 8, 3); }), "wrap modes 3");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, first + 16, 1u << 30); }), "runs past the section's end");
    // The material textures at the end: one index out of range, a count that is not the materials'.
    const size_t indices = texs.offset + texs.size - 4 * source_.scene.materials.size();
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, indices + 4, 2); }), "texture 2 out of range (2 textures)");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, indices, uint32_t(-2)); }), "texture -2 out of range");
    EXPECT_REFUSED(patched([&](Bytes& b) { put64(b, indices - 8, source_.scene.materials.size() + 1); }),
                   "material textures");
    EXPECT_REFUSED(patched([&](Bytes& b) { put64(b, txco.offset, source_.scene.triangles.size() - 1); }), "do not fit");
}

// Vertex colours (VCOL, nine floats a triangle): written only for a scene that has them, so that
// other files stay as they were; kept bit for bit through the round trip (with their scene
// texture); a count that is not the triangles' and colours outside [0, 1] or not finite are
// refused by the reader, and the writer refuses to write them.
TEST_F(PackedSceneTest, VertexColoursTravelInTheirOwnSection) {
    EXPECT_FALSE(findSection(bytes_, "VCOL")) << "a scene without vertex colours";
    LoadedScene coloured = source_;
    const size_t n = coloured.scene.triangles.size();
    for (size_t t = 0; t < n; ++t)
        coloured.scene.colors.push_back({glm::vec3(float(t) / float(n), 0.0f, 1.0f),
                                         glm::vec3(-0.0f, std::numeric_limits<float>::denorm_min(), 0.5f), glm::vec3(1.0f)});
    const UniformGrid grid = buildGrid(coloured.scene, {});
    const Bytes b = encodePackedScene(coloured, *makeStructure(grid), "coloured");
    const Entry vcol = section(b, "VCOL");
    EXPECT_EQ(vcol.size, 8 + 36 * n);
    EXPECT_EQ(get64(b, vcol.offset), n);
    float first;  // triangle 1's c0.x, as the layout puts it
    const uint32_t bits = get32(b, vcol.offset + 8 + 36);
    std::memcpy(&first, &bits, 4);
    EXPECT_EQ(first, 1.0f / float(n));
    expectRoundTrip(coloured);
    auto withFloat = [&](size_t at, float v) {
        return patched(b, [&](Bytes& p) { put32(p, at, std::bit_cast<uint32_t>(v)); });
    };
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put64(p, vcol.offset, n - 1); }), "do not fit");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put64(p, vcol.offset, uint64_t(1) << 40); }), "vertex colours");
    EXPECT_REFUSED(withFloat(vcol.offset + 8 + 4, 1.5f), "triangle 0: vertex colours must be finite and in [0, 1]");
    EXPECT_REFUSED(withFloat(vcol.offset + 8 + 36 * 2 + 32, -0.25f), "triangle 2: vertex colours must be finite");
    EXPECT_REFUSED(withFloat(vcol.offset + 8 + 12, std::numeric_limits<float>::quiet_NaN()), "triangle 0: vertex colours");
    // A file shorter by a record: the section's size is not its count's.
    refusal(patched(b, [&](Bytes& p) { put64(p, vcol.at + 16, vcol.size - 36); }));
    LoadedScene bad = coloured;
    bad.scene.colors[3].c1.y = 2.0f;
    EXPECT_THROW(encodePackedScene(bad, *makeStructure(grid), "bad"), InputError);
    bad.scene.colors.pop_back();
    bad.scene.colors[3].c1.y = 0.0f;
    EXPECT_THROW(encodePackedScene(bad, *makeStructure(grid), "bad"), InputError);
}

// Vertex tangents (TANG, twelve floats a triangle: each corner's tangent and handedness): written
// only for a scene that has them, so that other files stay as they were; kept bit for bit through
// the round trip (with their scene texture, which only such a scene has); a count that is not the
// triangles', a record cut off, and tangents not finite or with a handedness other than -1, 0, 1
// are refused by the reader, and the writer refuses to write them.
TEST_F(PackedSceneTest, VertexTangentsTravelInTheirOwnSection) {
    EXPECT_FALSE(findSection(bytes_, "TANG")) << "a scene without vertex tangents";
    const std::vector<TextureTexels> plain = sceneTextureTexels(source_.scene, grid_);
    EXPECT_TRUE(std::none_of(plain.begin(), plain.end(), [](const TextureTexels& t) { return t.name == "vertexTangents"; }));
    LoadedScene tangent = source_;
    const size_t n = tangent.scene.triangles.size();
    for (size_t t = 0; t < n; ++t)
        tangent.scene.tangents.push_back({glm::vec4(float(t) / float(n), 0.6f, 0.8f, 1.0f),
                                          glm::vec4(0.0f, -1.0f, std::numeric_limits<float>::denorm_min(), -1.0f),
                                          glm::vec4(0.0f)});  // a corner without: all zero
    const UniformGrid grid = buildGrid(tangent.scene, {});
    const Bytes b = encodePackedScene(tangent, *makeStructure(grid), "tangent");
    const Entry tang = section(b, "TANG");
    EXPECT_EQ(tang.size, 8 + 48 * n);
    EXPECT_EQ(get64(b, tang.offset), n);
    EXPECT_EQ(std::bit_cast<float>(get32(b, tang.offset + 8 + 48)), 1.0f / float(n));  // triangle 1's t0.x
    EXPECT_EQ(std::bit_cast<float>(get32(b, tang.offset + 8 + 28)), -1.0f);             // triangle 0's t1.w
    const std::vector<TextureTexels> texels = sceneTextureTexels(tangent.scene, grid);
    ASSERT_EQ(texels.back().name, "vertexTangents");
    EXPECT_EQ(texels.back().floats[4 + 3], -1.0f);  // triangle 0's second corner: its w
    expectRoundTrip(tangent);
    auto withFloat = [&](size_t at, float v) {
        return patched(b, [&](Bytes& p) { put32(p, at, std::bit_cast<uint32_t>(v)); });
    };
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put64(p, tang.offset, n - 1); }), "do not fit");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put64(p, tang.offset, uint64_t(1) << 40); }), "vertex tangents");
    EXPECT_REFUSED(withFloat(tang.offset + 8 + 12, 0.5f), "triangle 0: vertex tangents must be finite with w -1, 0 or 1");
    EXPECT_REFUSED(withFloat(tang.offset + 8 + 48 * 2 + 4, std::numeric_limits<float>::quiet_NaN()),
                   "triangle 2: vertex tangents must be finite");
    EXPECT_REFUSED(withFloat(tang.offset + 8 + 48 + 40, std::numeric_limits<float>::infinity()), "triangle 1: vertex tangents");
    // A file shorter by a record: the section's size is not its count's.
    refusal(patched(b, [&](Bytes& p) { put64(p, tang.at + 16, tang.size - 48); }));
    LoadedScene bad = tangent;
    bad.scene.tangents[3].t1.w = 2.0f;
    EXPECT_THROW(encodePackedScene(bad, *makeStructure(grid), "bad"), InputError);
    bad.scene.tangents[3].t1.w = 1.0f;
    bad.scene.tangents.pop_back();
    EXPECT_THROW(encodePackedScene(bad, *makeStructure(grid), "bad"), InputError);
}

// Alpha coverage (ALPH, five words a material): written only when some material has alpha, so
// that other files stay as they were; kept through the round trip; a mode, factor or cutoff out
// of range is refused by reader and writer.
TEST_F(PackedSceneTest, AlphaCoverageTravelsInItsOwnSection) {
    EXPECT_FALSE(findSection(bytes_, "ALPH")) << "a scene without alpha";
    LoadedScene alpha = source_;
    alpha.scene.materials[1].alphaMode = 1;  // MASK
    alpha.scene.materials[1].alphaCutoff = 0.25f;
    alpha.scene.materials[2].alphaMode = 2;  // BLEND
    alpha.scene.materials[2].alphaFactor = 0.3f;
    const size_t materials = alpha.scene.materials.size();
    const Bytes b = encodePackedScene(alpha, *makeStructure(grid_), "alpha");
    const Entry alph = section(b, "ALPH");
    EXPECT_EQ(alph.size, 8 + 20 * materials);
    EXPECT_EQ(get64(b, alph.offset), materials);
    EXPECT_EQ(get32(b, alph.offset + 8 + 20 * 2), 2u);
    const LoadedScene packed = decodePackedScene(b, "alpha.gpscene");
    expectSameScene(alpha, packed);
    EXPECT_EQ(packed.scene.materials[2].alphaFactor, 0.3f);
    auto withFloat = [&](size_t at, float v) {
        return patched(b, [&](Bytes& p) { put32(p, at, std::bit_cast<uint32_t>(v)); });
    };
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, alph.offset + 8, 3); }), "alpha mode 3");
    EXPECT_REFUSED(withFloat(alph.offset + 8 + 20 + 8, 1.5f), "material 1: alpha mode");
    EXPECT_REFUSED(withFloat(alph.offset + 8 + 4, std::numeric_limits<float>::quiet_NaN()), "material 0: alpha mode");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, alph.offset + 8 + 12, 7); }), "texture 7 out of range");
    LoadedScene bad = alpha;
    bad.scene.materials[1].alphaCutoff = -1.0f;
    EXPECT_THROW(encodePackedScene(bad, *makeStructure(grid_), "bad"), InputError);
}

// Sides (SIDE, one u32 a material: 1 double-sided, 0 single-sided): written only when some
// material is single-sided, so that other files stay as they were; kept through the round trip;
// any other value is refused.
TEST_F(PackedSceneTest, SidesTravelInTheirOwnSection) {
    EXPECT_FALSE(findSection(bytes_, "SIDE")) << "a scene of double-sided materials";
    EXPECT_EQ(encodePackedScene(source_, *makeStructure(grid_), "again"), bytes_) << "unchanged without single-sided materials";
    LoadedScene sided = source_;
    sided.scene.materials[1].doubleSided = false;
    const size_t materials = sided.scene.materials.size();
    const Bytes b = encodePackedScene(sided, *makeStructure(grid_), "sided");
    const Entry side = section(b, "SIDE");
    EXPECT_EQ(side.size, 8 + 4 * materials);
    EXPECT_EQ(get64(b, side.offset), materials);
    for (size_t m = 0; m < materials; ++m) EXPECT_EQ(get32(b, side.offset + 8 + 4 * m), m == 1 ? 0u : 1u) << m;
    const LoadedScene packed = decodePackedScene(b, "sided.gpscene");
    expectSameScene(sided, packed);
    EXPECT_FALSE(packed.scene.materials[1].doubleSided);
    EXPECT_TRUE(packed.scene.materials[0].doubleSided);
    EXPECT_EQ(encodePackedScene(packed, *packed.accel, "again"), b);
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, side.offset + 8 + 4, 2); }), "material 1: double-sided 2");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, side.offset + 8, 0xffffffffu); }), "material 0: double-sided");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put64(p, side.offset, materials + 1); }), "section SIDE");
}

// Transmission maps (TRNS, texture and channel a material: glTF transmissionTexture): written only
// when some material has one, so that other files stay as they were; kept through the round trip;
// a texture out of range, a channel outside 0-3 and a count other than the materials' are refused.
TEST_F(PackedSceneTest, TransmissionMapsTravelInTheirOwnSection) {
    EXPECT_FALSE(findSection(bytes_, "TRNS")) << "a scene without transmission maps";
    LoadedScene mapped = source_;
    ASSERT_GE(mapped.scene.textures.size(), 2u);
    mapped.scene.materials[2].model = GPURT_MODEL_GLTF;
    mapped.scene.materials[2].ior = 1.5f;
    mapped.scene.materials[2].transmission = glm::vec3(0.75f);
    mapped.scene.materials[2].transmissionTexture = {1, 0};
    const size_t materials = mapped.scene.materials.size();
    const Bytes b = encodePackedScene(mapped, *makeStructure(grid_), "mapped");
    const Entry trns = section(b, "TRNS");
    EXPECT_EQ(trns.size, 8 + 8 * materials);
    EXPECT_EQ(get64(b, trns.offset), materials);
    for (size_t m = 0; m < materials; ++m) {
        EXPECT_EQ(get32(b, trns.offset + 8 + 8 * m), m == 2 ? 1u : 0xffffffffu) << m;
        EXPECT_EQ(get32(b, trns.offset + 12 + 8 * m), 0u) << m;
    }
    const LoadedScene packed = decodePackedScene(b, "mapped.gpscene");
    expectSameScene(mapped, packed);
    EXPECT_EQ(packed.scene.materials[2].transmissionTexture.texture, 1);
    EXPECT_FALSE(packed.scene.materials[1].transmissionTexture.given());
    EXPECT_EQ(encodePackedScene(packed, *packed.accel, "again"), b);
    const uint32_t textures = uint32_t(mapped.scene.textures.size());
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, trns.offset + 8 + 16, textures); }),
                   "material 2: texture " + std::to_string(textures) + " out of range");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, trns.offset + 8, uint32_t(-2)); }), "material 0: texture -2 out of range");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, trns.offset + 8 + 20, 4); }), "material 2: texture channel 4");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put64(p, trns.offset, materials + 1); }), "section TRNS");
    LoadedScene bad = mapped;
    bad.scene.materials[2].transmissionTexture.channel = -1;
    EXPECT_THROW(encodePackedScene(bad, *makeStructure(grid_), "bad"), InputError);
}

// The layers of glTF's extensions (LAYR: KHR_materials_specular, KHR_materials_clearcoat,
// KHR_materials_sheen, 88 bytes a material): written only when some material has one, so that other files stay as they were;
// kept through the round trip; factors outside [0, 1], a colour below 0, a map's texture or
// channel out of range and a count other than the materials' are refused.
TEST_F(PackedSceneTest, LayersTravelInTheirOwnSection) {
    EXPECT_FALSE(findSection(bytes_, "LAYR")) << "a scene without layers";
    LoadedScene layered = source_;
    ASSERT_GE(layered.scene.textures.size(), 2u);
    Material& m = layered.scene.materials[2];
    m.model = GPURT_MODEL_GLTF;
    m.specularFactor = 0.5f;
    m.specularColor = glm::vec3(1.0f, 0.25f, 2.0f);
    m.specularTexture = {1, 3};
    m.specularColorTexture = 0;
    m.clearcoat = 0.75f;
    m.clearcoatRoughness = 0.125f;
    m.clearcoatTexture = {1, 0};
    m.clearcoatRoughnessTexture = {0, 1};
    m.clearcoatNormalTexture = 1;
    m.clearcoatNormalScale = -0.5f;
    m.sheenColor = glm::vec3(0.5f, 1.0f, 0.25f);
    m.sheenRoughness = 0.75f;
    m.sheenColorTexture = 1;
    m.sheenRoughnessTexture = {0, 3};
    const size_t materials = layered.scene.materials.size();
    const Bytes b = encodePackedScene(layered, *makeStructure(grid_), "layered");
    const Entry layr = section(b, "LAYR");
    EXPECT_EQ(layr.size, 8 + 88 * materials);
    EXPECT_EQ(get64(b, layr.offset), materials);
    const size_t at = layr.offset + 8 + 88 * 2;  // material 2's record
    EXPECT_EQ(get32(b, at), 0x3f000000u);        // 0.5f
    EXPECT_EQ(get32(b, at + 16), 1u);            // specularTexture: texture 1,
    EXPECT_EQ(get32(b, at + 20), 3u);            // channel A
    const LoadedScene packed = decodePackedScene(b, "layered.gpscene");
    expectSameScene(layered, packed);
    EXPECT_EQ(packed.scene.materials[2].clearcoat, 0.75f);
    EXPECT_FALSE(packed.scene.materials[1].hasClearcoat());
    EXPECT_EQ(encodePackedScene(packed, *packed.accel, "again"), b);
    const uint32_t textures = uint32_t(layered.scene.textures.size());
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at, 0x40000000u); }), "material 2: specular factor, clearcoat");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at + 28, 0x3fc00000u); }), "material 2: specular factor, clearcoat");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at + 8, 0xbf800000u); }), "the specular colour finite and >= 0");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at + 52, textures); }),
                   "material 2: texture " + std::to_string(textures) + " out of range");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at + 40, 4); }), "material 2: texture channel 4");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at + 60, 0x3fc00000u); }), "sheen colour and roughness must be in [0, 1]");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at + 76, textures); }),
                   "material 2: texture " + std::to_string(textures) + " out of range");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put64(p, layr.offset, materials + 1); }), "section LAYR");
    LoadedScene bad = layered;
    bad.scene.materials[2].clearcoat = 2.0f;
    EXPECT_THROW(encodePackedScene(bad, *makeStructure(grid_), "bad"), InputError);
}

// KHR_materials_volume (VOLM, 20 bytes a material: thickness, attenuation colour and distance):
// written only when some material has a thickness; kept bit for bit through the round trip (an
// infinite distance too); bad values and a count that is not the materials' are refused.
TEST_F(PackedSceneTest, VolumesTravelInTheirOwnSection) {
    EXPECT_FALSE(findSection(bytes_, "VOLM")) << "a scene without volumes";
    LoadedScene glass = source_;
    Material& m = glass.scene.materials[2];
    m.model = GPURT_MODEL_GLTF;
    m.ior = 1.5f;
    m.transmission = glm::vec3(1.0f);
    m.thickness = 0.25f;
    m.attenuationColor = glm::vec3(0.5f, 0.75f, 1.0f);
    m.attenuationDistance = 2.0f;
    glass.scene.materials[1].thickness = 1.0f;  // a volume that absorbs nothing: the distance stays infinite
    const size_t materials = glass.scene.materials.size();
    const Bytes b = encodePackedScene(glass, *makeStructure(grid_), "glass");
    const Entry volm = section(b, "VOLM");
    EXPECT_EQ(volm.size, 8 + 20 * materials);
    EXPECT_EQ(get64(b, volm.offset), materials);
    const size_t at = volm.offset + 8 + 20 * 2;  // material 2's record
    EXPECT_EQ(get32(b, at), 0x3e800000u);        // 0.25f
    EXPECT_EQ(get32(b, at + 16), 0x40000000u);   // 2.0f
    const LoadedScene packed = decodePackedScene(b, "glass.gpscene");
    expectSameScene(glass, packed);
    EXPECT_TRUE(packed.scene.materials[2].hasVolume());
    EXPECT_EQ(packed.scene.materials[1].attenuationDistance, std::numeric_limits<float>::infinity());
    EXPECT_EQ(encodePackedScene(packed, *packed.accel, "again"), b);
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at, 0xbf800000u); }), "material 2: the volume's thickness");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at + 8, 0x3fc00000u); }), "its attenuation colour in [0, 1]");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at + 16, 0u); }), "its distance > 0");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put64(p, volm.offset, materials + 1); }), "section VOLM");
}

// KHR_materials_iridescence (IRID, 32 bytes a material: factor, index, thickness range, the
// factor's and the thickness's maps): written only when some material has a film; kept bit for
// bit through the round trip; bad values, maps out of range and a count that is not the
// materials' are refused.
TEST_F(PackedSceneTest, FilmsTravelInTheirOwnSection) {
    EXPECT_FALSE(findSection(bytes_, "IRID")) << "a scene without films";
    LoadedScene filmed = source_;
    ASSERT_GE(filmed.scene.textures.size(), 2u);
    Material& m = filmed.scene.materials[2];
    m.model = GPURT_MODEL_GLTF;
    m.iridescenceFactor = 0.5f;
    m.iridescenceIor = 1.75f;
    m.iridescenceThicknessMin = 150.0f;
    m.iridescenceThicknessMax = 650.0f;
    m.iridescenceTexture = {1, 0};
    m.iridescenceThicknessTexture = {0, 1};
    const size_t materials = filmed.scene.materials.size();
    const Bytes b = encodePackedScene(filmed, *makeStructure(grid_), "filmed");
    const Entry irid = section(b, "IRID");
    EXPECT_EQ(irid.size, 8 + 32 * materials);
    EXPECT_EQ(get64(b, irid.offset), materials);
    const size_t at = irid.offset + 8 + 32 * 2;  // material 2's record
    EXPECT_EQ(get32(b, at), 0x3f000000u);        // 0.5f
    EXPECT_EQ(get32(b, at + 16), 1u);            // iridescenceTexture: texture 1,
    EXPECT_EQ(get32(b, at + 28), 1u);            // the thickness's channel G
    const LoadedScene packed = decodePackedScene(b, "filmed.gpscene");
    expectSameScene(filmed, packed);
    EXPECT_TRUE(packed.scene.materials[2].hasIridescence());
    EXPECT_EQ(encodePackedScene(packed, *packed.accel, "again"), b);
    const uint32_t textures = uint32_t(filmed.scene.textures.size());
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at, 0x40000000u); }), "material 2: the iridescence factor must be in [0, 1]");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at + 4, 0x3f000000u); }), "its index in [1, 1000]");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at + 12, 0xbf800000u); }), "its thicknesses in [0, 1e6] nm");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at + 24, textures); }),
                   "material 2: texture " + std::to_string(textures) + " out of range");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at + 20, 4); }), "material 2: texture channel 4");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put64(p, irid.offset, materials + 1); }), "section IRID");
}

// KHR_materials_anisotropy (ANIS: strength, rotation, texture per material): only when some
// material has anisotropy; kept bit for bit; out of range values and textures refused.
TEST_F(PackedSceneTest, AnisotropyTravelsInItsOwnSection) {
    EXPECT_FALSE(findSection(bytes_, "ANIS")) << "a scene without anisotropy";
    LoadedScene brushed = source_;
    ASSERT_GE(brushed.scene.textures.size(), 2u);
    Material& m = brushed.scene.materials[2];
    m.model = GPURT_MODEL_GLTF;
    m.anisotropyStrength = 0.5f;
    m.anisotropyRotation = -2.0f;
    m.anisotropyTexture = 1;
    const size_t materials = brushed.scene.materials.size();
    const Bytes b = encodePackedScene(brushed, *makeStructure(grid_), "brushed");
    const Entry anis = section(b, "ANIS");
    EXPECT_EQ(anis.size, 8 + 12 * materials);
    EXPECT_EQ(get64(b, anis.offset), materials);
    const size_t at = anis.offset + 8 + 12 * 2;  // material 2's record
    EXPECT_EQ(get32(b, at), 0x3f000000u);        // 0.5f
    EXPECT_EQ(get32(b, at + 4), 0xc0000000u);    // -2.0f
    EXPECT_EQ(get32(b, at + 8), 1u);             // texture 1
    const LoadedScene packed = decodePackedScene(b, "brushed.gpscene");
    expectSameScene(brushed, packed);
    EXPECT_TRUE(packed.scene.materials[2].hasAnisotropy());
    EXPECT_EQ(encodePackedScene(packed, *packed.accel, "again"), b);
    const uint32_t textures = uint32_t(brushed.scene.textures.size());
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at, 0x40000000u); }), "material 2: the anisotropy strength must be in [0, 1]");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at + 4, 0x7f800000u); }), "its rotation finite");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at + 8, textures); }),
                   "material 2: texture " + std::to_string(textures) + " out of range");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put64(p, anis.offset, materials + 1); }), "section ANIS");
    // A glTF material's index is 0 or at least 1, as JSON and glTF have it (the fuzzer's find: a
    // transmissive one of index 1.6e-38 shaded NaN).
    LoadedScene thin = brushed;
    thin.scene.materials[2].ior = 1.6e-38f;
    const std::string message = test::refusalOf([&] { encodePackedScene(thin, *makeStructure(grid_), "thin"); }, "thin: ");
    EXPECT_NE(message.find("material 2: a glTF material's ior must be 0 or >= 1"), std::string::npos) << message;
}

// KHR_materials_dispersion (DISP, one f32 per material): only when some material has one; kept bit
// for bit; a negative value and a count that is not the materials' refused.
TEST_F(PackedSceneTest, DispersionTravelsInItsOwnSection) {
    EXPECT_FALSE(findSection(bytes_, "DISP")) << "a scene without dispersion";
    LoadedScene flint = source_;
    Material& m = flint.scene.materials[2];
    m.model = GPURT_MODEL_GLTF;
    m.ior = 1.7f;
    m.transmission = glm::vec3(1.0f);
    m.thickness = 1.0f;
    m.dispersion = 0.5f;
    const size_t materials = flint.scene.materials.size();
    const Bytes b = encodePackedScene(flint, *makeStructure(grid_), "flint");
    const Entry disp = section(b, "DISP");
    EXPECT_EQ(disp.size, 8 + 4 * materials);
    EXPECT_EQ(get64(b, disp.offset), materials);
    const size_t at = disp.offset + 8 + 4 * 2;  // material 2's record
    EXPECT_EQ(get32(b, at), 0x3f000000u);       // 0.5f
    const LoadedScene packed = decodePackedScene(b, "flint.gpscene");
    expectSameScene(flint, packed);
    EXPECT_TRUE(packed.scene.materials[2].disperses());
    EXPECT_EQ(encodePackedScene(packed, *packed.accel, "again"), b);
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at, 0xbf800000u); }), "material 2: the dispersion must be in [0, 1000]");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put64(p, disp.offset, materials + 1); }), "section DISP");
}

// Thin walls (THIN, one u32 per material: glTF's transmission without a volume): written only when
// some material is one (a file without keeps its solids, as before the section existed); kept
// through the round trip; a value other than 0 or 1 and a count that is not the materials' refused.
TEST_F(PackedSceneTest, ThinWallsTravelInTheirOwnSection) {
    EXPECT_FALSE(findSection(bytes_, "THIN")) << "a scene without thin walls";
    LoadedScene windows = source_;
    Material& m = windows.scene.materials[2];
    m.model = GPURT_MODEL_GLTF;
    m.ior = 1.5f;
    m.transmission = glm::vec3(0.8f);
    m.thinWalled = true;
    const size_t materials = windows.scene.materials.size();
    const Bytes b = encodePackedScene(windows, *makeStructure(grid_), "windows");
    const Entry thin = section(b, "THIN");
    EXPECT_EQ(thin.size, 8 + 4 * materials);
    EXPECT_EQ(get64(b, thin.offset), materials);
    const size_t at = thin.offset + 8 + 4 * 2;  // material 2's
    EXPECT_EQ(get32(b, at), 1u);
    EXPECT_EQ(get32(b, at - 4), 0u);
    const LoadedScene packed = decodePackedScene(b, "windows.gpscene");
    expectSameScene(windows, packed);
    EXPECT_TRUE(packed.scene.materials[2].thin());
    EXPECT_EQ(encodePackedScene(packed, *packed.accel, "again"), b);
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, at, 2u); }), "material 2: thin wall 2 (0 or 1)");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put64(p, thin.offset, materials + 1); }), "section THIN");
}

// Material models (MODL, one u32 per material): written only when some material is not of the
// classic model (0), so that today's files stay as they were; kept through the round trip; a
// count that is not the materials' and an unknown model are refused by reader and writer.
TEST_F(PackedSceneTest, MaterialModelsTravelInTheirOwnSection) {
    EXPECT_FALSE(findSection(bytes_, "MODL")) << "a scene of classic materials only";
    LoadedScene debug = source_;
    debug.scene.materials[2].model = 1;  // GPURT_MODEL_DEBUG_NORMAL
    const size_t materials = debug.scene.materials.size();
    const Bytes b = encodePackedScene(debug, *makeStructure(grid_), "debug");
    const Entry modl = section(b, "MODL");
    EXPECT_EQ(modl.size, 8 + 4 * materials);
    EXPECT_EQ(get64(b, modl.offset), materials);
    const LoadedScene packed = decodePackedScene(b, "debug.gpscene");
    ASSERT_EQ(packed.scene.materials.size(), materials);
    for (size_t m = 0; m < materials; ++m) {
        EXPECT_EQ(get32(b, modl.offset + 8 + 4 * m), m == 2 ? 1u : 0u) << m;
        EXPECT_EQ(packed.scene.materials[m].model, m == 2 ? 1 : 0) << m;
    }
    expectSameScene(debug, packed);
    EXPECT_EQ(encodePackedScene(packed, *packed.accel, "again"), b);

    // A count that does not fit the section, or (the section shortened to fit it) is not the
    // materials'; models this gpurt does not know.
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put64(p, modl.offset, materials + 1); }), "section MODL: ");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) {
                       put64(p, modl.offset, materials - 1);
                       put64(p, modl.at + 16, modl.size - 4);
                   }),
                   "section MODL: " + std::to_string(materials - 1) + " material models for " +
                       std::to_string(materials) + " materials");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, modl.offset + 8 + 4 * 3, GPURT_MODEL_COUNT); }),
                   "section MODL: material 3: unknown material model " + std::to_string(GPURT_MODEL_COUNT));
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, modl.offset + 8, 0xffffffffu); }),
                   "material 0: unknown material model 4294967295");
    for (const int model : {GPURT_MODEL_COUNT, -1}) {
        LoadedScene unknown = debug;
        unknown.scene.materials[4].model = model;
        const std::string message =
            test::refusalOf([&] { encodePackedScene(unknown, *makeStructure(grid_), "unknown"); }, "unknown: ");
        EXPECT_NE(message.find("material 4: unknown material model " + std::to_string(model)), std::string::npos)
            << message;
    }
}

// A classic material's normal and emissive maps (MTL `norm`, `map_Ke` without `Pr`/`Pm`) travel in
// PBRM too: the section is written for them although no material is of glTF's model.
TEST_F(PackedSceneTest, ClassicMaterialsKeepTheirNormalAndEmissiveMaps) {
    EXPECT_FALSE(findSection(bytes_, "PBRM")) << "no maps, no glTF material";
    LoadedScene mapped = source_;
    mapped.scene.materials[2].normalTexture = 1;
    mapped.scene.materials[2].normalScale = 0.5f;
    mapped.scene.materials[3].emissiveTexture = 0;
    ASSERT_EQ(mapped.scene.materials[2].model, 0);
    const Bytes b = encodePackedScene(mapped, *makeStructure(grid_), "mapped");
    EXPECT_TRUE(findSection(b, "PBRM"));
    const LoadedScene packed = decodePackedScene(b, "mapped.gpscene");
    EXPECT_EQ(packed.scene.materials[2].normalTexture, 1);
    EXPECT_EQ(packed.scene.materials[2].normalScale, 0.5f);
    EXPECT_EQ(packed.scene.materials[3].emissiveTexture, 0);
    expectSameScene(mapped, packed);
}

TEST_F(PackedSceneTest, RefusesAnInconsistentGrid) {
    const Entry g = section(bytes_, "GRID"), cells = section(bytes_, "CELL"),
                list = section(bytes_, "LIST");
    const glm::ivec3 r = grid_.resolution;
    // Resolution: the product must match the cell starts and stay within kMaxGridCells.
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, g.offset, uint32_t(r.x + 1)); }),
                   "cells of the grid");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, g.offset, 0); }), "resolution");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, g.offset, 0x80000000u); }), "resolution");
    EXPECT_REFUSED(patched([&](Bytes& b) {
                       put32(b, g.offset, 1 << 13);
                       put32(b, g.offset + 4, 1 << 13);
                       put32(b, g.offset + 8, 1 << 13);
                   }),
                   "cells");
    // Bounds and cell size: finite, ordered, consistent, containing the triangles.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_REFUSED(
        patched([&](Bytes& b) { put32(b, g.offset + 12, std::bit_cast<uint32_t>(nan)); }),
        "not finite");
    EXPECT_REFUSED(patched([&](Bytes& b) {
                       put32(b, g.offset + 36, std::bit_cast<uint32_t>(grid_.cellSize.x * 1.5f));
                   }),
                   "cell size");
    EXPECT_REFUSED(patched([&](Bytes& b) {
                       // Both the box and the cell size moved: consistent, but the scene sticks
                       // out.
                       const float maxX = grid_.min.x + 0.5f * (grid_.max.x - grid_.min.x);
                       put32(b, g.offset + 24, std::bit_cast<uint32_t>(maxX));
                       put32(b, g.offset + 36,
                             std::bit_cast<uint32_t>((maxX - grid_.min.x) / float(r.x)));
                   }),
                   "do not contain");
    // Cell starts: from 0, never decreasing, ending at the list's size.
    const size_t cellCount = grid_.cells();
    size_t nonEmpty = 0;
    while (grid_.cellStart[nonEmpty + 1] == grid_.cellStart[nonEmpty]) ++nonEmpty;
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, cells.offset, 1); }), "first cell");
    // Cell nonEmpty + 1 starts after 0, so a 0 after it is a decrease.
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, cells.offset + 4 * (nonEmpty + 2), 0); }),
                   "decrease");
    ASSERT_LT(grid_.cellStart[cellCount - 1], grid_.cellTriangles.size())
        << "the last cell is empty";
    EXPECT_REFUSED(patched([&](Bytes& b) {
                       put32(b, cells.offset + 4 * cellCount,
                             uint32_t(grid_.cellTriangles.size() - 1));
                   }),
                   "last cell ends");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, cells.offset + 4 * cellCount, 0xffffffffu); }),
                   "past the");
    // Triangle ids: in range and ascending within a cell.
    EXPECT_REFUSED(
        patched([&](Bytes& b) { put32(b, list.offset, uint32_t(source_.scene.triangles.size())); }),
        "lists triangle");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, list.offset + list.size - 4, 0xffffffffu); }),
                   "lists triangle");
    const uint32_t begin = grid_.cellStart[nonEmpty];
    ASSERT_GE(grid_.cellStart[nonEmpty + 1] - begin, 2u);
    EXPECT_REFUSED(patched([&](Bytes& b) {
                       put32(b, list.offset + 4 * begin, grid_.cellTriangles[begin + 1]);
                       put32(b, list.offset + 4 * (begin + 1), grid_.cellTriangles[begin]);
                   }),
                   "not strictly ascending");
}

TEST_F(PackedSceneTest, CarriesABvhInsteadOfTheGrid) {
    const Bvh bvh = buildBvh(source_.scene);
    const Bytes b = encodePackedScene(source_, *makeStructure(bvh), "source");
    const LoadedScene packed = decodePackedScene(b, "source.gpscene");
    EXPECT_FALSE(gridOf(packed.accel));
    ASSERT_TRUE(bvhOf(packed.accel));
    EXPECT_EQ(bvhOf(packed.accel)->triangles, bvh.triangles);
    ASSERT_EQ(bvhOf(packed.accel)->nodes.size(), bvh.nodes.size());
    for (size_t n = 0; n < bvh.nodes.size(); ++n)
        for (int c = 0; c < 2; ++c) {
            EXPECT_EQ(bvhOf(packed.accel)->nodes[n].child[c].min, bvh.nodes[n].child[c].min);
            EXPECT_EQ(bvhOf(packed.accel)->nodes[n].child[c].max, bvh.nodes[n].child[c].max);
            EXPECT_EQ(bvhOf(packed.accel)->nodes[n].child[c].ref, bvh.nodes[n].child[c].ref);
            EXPECT_EQ(bvhOf(packed.accel)->nodes[n].child[c].count, bvh.nodes[n].child[c].count);
        }
    EXPECT_EQ(bvhOf(packed.accel)->min, bvh.min);
    EXPECT_EQ(bvhOf(packed.accel)->max, bvh.max);
    EXPECT_EQ(bvhOf(packed.accel)->depth, bvh.depth);
    EXPECT_EQ(encodePackedScene(packed, *packed.accel, "again"), b);
    // The grid's sections are absent, the BVH's present; a grid file has none of the BVH's.
    EXPECT_EQ(section(b, "BVHN").size % 64, 8u);
    for (const char* tag : {"GRID", "CELL", "LIST"}) EXPECT_FALSE(findSection(b, tag)) << tag;
    for (const char* tag : {"BVHN", "BVHL"}) EXPECT_FALSE(findSection(bytes_, tag)) << tag;
}

TEST_F(PackedSceneTest, RefusesADamagedBvh) {
    const Bvh bvh = buildBvh(source_.scene);
    const Bytes b = encodePackedScene(source_, *makeStructure(bvh), "source");
    const Entry nodes = section(b, "BVHN"), list = section(b, "BVHL");
    const size_t n = source_.scene.triangles.size();
    // Child k of node j: (min, max, ref, count) at 8 + 64 j + 32 k.
    auto child = [&](size_t node, int c) { return nodes.offset + 8 + 64 * node + 32 * size_t(c); };
    size_t inner = 0, innerChild = 0, leaf = 0, leafChild = 0;
    for (size_t j = 0; j < bvh.nodes.size(); ++j)
        for (int c = 0; c < 2; ++c) {
            if (bvh.nodes[j].child[c].count == 0 && bvh.nodes[j].child[c].ref > 0 && inner == 0)
                inner = j, innerChild = size_t(c);
            if (bvh.nodes[j].child[c].count > 0) leaf = j, leafChild = size_t(c);
        }
    ASSERT_GT(bvh.nodes.size(), 1u);
    // Bad child indices: past the end, backwards (a cycle), the root.
    EXPECT_REFUSED(patched(b, [&](Bytes& x) { put32(x, child(inner, int(innerChild)) + 24, uint32_t(bvh.nodes.size())); }),
                   "not a later node");
    EXPECT_REFUSED(patched(b, [&](Bytes& x) {
                       put32(x, child(bvh.nodes.size() - 1, 0) + 24, 1);
                       put32(x, child(bvh.nodes.size() - 1, 0) + 28, 0);
                   }),
                   "bvh:");
    EXPECT_REFUSED(patched(b, [&](Bytes& x) { put32(x, child(inner, int(innerChild)) + 24, 0); }), "not a later node");
    // Counts past the end, over the most a leaf holds; a list of another length.
    EXPECT_REFUSED(patched(b, [&](Bytes& x) { put32(x, child(leaf, int(leafChild)) + 24, uint32_t(n - 1)); }), "bvh:");
    EXPECT_REFUSED(patched(b, [&](Bytes& x) { put32(x, child(leaf, int(leafChild)) + 28, 200); }), "at most");
    EXPECT_REFUSED(patched(b, [&](Bytes& x) { put32(x, list.offset, uint32_t(n)); }), "out of range");
    EXPECT_REFUSED(patched(b, [&](Bytes& x) { put32(x, list.offset, get32(x, list.offset + 4)); }), "bvh:");
    EXPECT_REFUSED(patched(b, [&](Bytes& x) { put64(x, nodes.offset, uint64_t(1) << 40); }), "BVH nodes");
    // Boxes: finite, holding their triangles.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_REFUSED(patched(b, [&](Bytes& x) { put32(x, child(0, 0), std::bit_cast<uint32_t>(nan)); }), "not finite");
    EXPECT_REFUSED(patched(b, [&](Bytes& x) {
                       for (int a = 0; a < 3; ++a)
                           put32(x, child(leaf, int(leafChild)) + 12 + 4 * size_t(a), get32(x, child(leaf, int(leafChild)) + 4 * size_t(a)));
                   }),
                   "bvh:");
    // A grid and a BVH, or half of one, are refused.
    const size_t gridEntry = section(bytes_, "GRID").at;
    EXPECT_REFUSED(patched([&](Bytes& x) { std::memcpy(&x[gridEntry], "BVHN", 4); }), "acceleration structure");
    EXPECT_EQ(relaidOut(bytes_, sectionTags(bytes_)), bytes_);  // the rebuilder lays a file out as the writer does
    for (const char* tag : {"BVHN", "BVHL"}) {
        // The grid file with one or both of the BVH's sections after its own.
        std::vector<std::pair<const Bytes*, std::string>> parts;
        for (const std::string& t : sectionTags(bytes_)) parts.emplace_back(&bytes_, t);
        parts.emplace_back(&b, tag);
        EXPECT_NE(refusal(relaidOut(bytes_, parts)).find("not one accelerator's"), std::string::npos) << tag;
        parts.emplace_back(&b, std::string(tag) == "BVHN" ? "BVHL" : "BVHN");
        EXPECT_NE(refusal(relaidOut(bytes_, parts)).find("not one accelerator's"), std::string::npos) << tag;
    }
}

// An accelerator's sections are read wherever the table puts them: a BVH file written before the
// registry stored BVHN and BVHL after ENVM, and one with them last reads the same.
TEST_F(PackedSceneTest, ReadsTheStructureWhereverTheTablePutsIt) {
    LoadedScene lit = source_;
    auto image = std::make_shared<EnvironmentImage>();
    image->width = 2;
    image->height = 1;
    image->texels = {glm::vec3(1.0f), glm::vec3(0.5f)};
    Environment env;
    env.image = image;
    lit.scene.environment = env;
    const Bytes b = encodePackedScene(lit, *makeStructure(buildBvh(lit.scene)), "source");
    std::vector<std::string> tags = sectionTags(b), old, last;
    // The writer's order: the structure right after RNDR.
    const auto render = std::find(tags.begin(), tags.end(), "RNDR");
    ASSERT_NE(render, tags.end());
    ASSERT_LT(size_t(render - tags.begin()) + 2, tags.size());
    EXPECT_EQ(*(render + 1), "BVHN");
    EXPECT_EQ(*(render + 2), "BVHL");
    for (const std::string& t : tags)
        if (t != "BVHN" && t != "BVHL") {
            old.push_back(t);
            last.push_back(t);
            if (t == "ENVM") old.insert(old.end(), {"BVHN", "BVHL"});
        }
    last.insert(last.end(), {"BVHL", "BVHN"});  // and in the other order
    ASSERT_NE(std::find(old.begin(), old.end(), "BVHN"), old.end());
    const LoadedScene want = decodePackedScene(b, "new.gpscene");
    for (const auto& order : {old, last}) {
        const LoadedScene got = decodePackedScene(relaidOut(b, order), "old.gpscene");
        expectSameScene(want, got);
        ASSERT_TRUE(bvhOf(got.accel));
        EXPECT_EQ(bvhOf(got.accel)->triangles, bvhOf(want.accel)->triangles);
        EXPECT_EQ(bvhOf(got.accel)->nodes.size(), bvhOf(want.accel)->nodes.size());
        // Written again, it is the writer's layout.
        EXPECT_EQ(encodePackedScene(got, *got.accel, "source"), b);
    }
}

TEST_F(PackedSceneTest, RefusesBadValues) {
    const Entry tris = section(bytes_, "TRIS");
    const size_t n = source_.scene.triangles.size();
    const uint32_t inf = std::bit_cast<uint32_t>(std::numeric_limits<float>::infinity());
    const uint32_t nan = std::bit_cast<uint32_t>(std::numeric_limits<float>::quiet_NaN());
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, tris.offset + 8 + 36 * 2 + 4, nan); }),
                   "triangle 2: vertex coordinates are not finite");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, tris.offset + 8 + 36 * n + 4 * 9, 99); }),
                   "triangle 9: material id 99 out of range");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, section(b, "MATS").offset + 8 + 24, inf); }),
                   "material 0");
    EXPECT_REFUSED(
        patched([&](Bytes& b) { put32(b, section(b, "LGTS").offset + 8 + 28 + 24, nan); }),
        "light 1");
    const Entry cam = section(bytes_, "CAMR");
    EXPECT_REFUSED(
        patched([&](Bytes& b) { put32(b, cam.offset + 36, std::bit_cast<uint32_t>(180.0f)); }),
        "fovy");
    EXPECT_REFUSED(patched([&](Bytes& b) {
                       for (int k = 0; k < 3; ++k)
                           put32(b, cam.offset + 12 + 4 * size_t(k),
                                 get32(b, cam.offset + 4 * size_t(k)));
                   }),
                   "target - eye");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, section(b, "BKGD").offset, inf); }),
                   "background");
    const Entry render = section(bytes_, "RNDR");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, render.offset, 65); }), "max bounces 65");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, render.offset + 8, 0); }), "image size 0x123");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, render.offset + 12, 16385); }), "image size");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, render.offset + 4, 2); }), "flag");
    // The animation: its key count against its size, then its values.
    const Entry anim = section(bytes_, "ANIM");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, anim.offset, 3); }), "keys of 44 bytes do not fill");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, anim.offset, 0); }), "ANIM");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, anim.offset + 8 + 44, get32(b, anim.offset + 8)); }),
                   "animation key 1: time is not after the key before");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, anim.offset + 8 + 44 + 40, std::bit_cast<uint32_t>(0.0f)); }),
                   "animation key 1: fovy 0");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, anim.offset + 8 + 2 * 44, std::bit_cast<uint32_t>(-24.0f)); }),
                   "animation: fps -24");
    EXPECT_REFUSED(patched([&](Bytes& b) { put32(b, anim.offset + 8 + 4, nan); }), "animation key 0: values are not finite");
}

// Every truncation and, at every offset, flipped bits both as they are (the checksum catches
// them) and resealed (the section and content checks must): each outcome is a clean InputError
// or a scene that loads and renders.
TEST_F(PackedSceneTest, FuzzedFilesNeverCrash) {
    LoadedScene small = objScene("cornell_box.obj");
    small.scene.lights.push_back({{1, 2, 3}, {1, 1, 1}, 5.0f});
    small.scene.camera = CameraSpec{{278, 273, -800}, {278, 273, 0}, {0, 1, 0}, 39.3f};
    small.size = glm::ivec2(16, 16);
    GridOptions options;
    options.resolution = glm::ivec3(3, 2, 3);
    const Bytes bytes = encodePackedScene(small, *makeStructure(buildGrid(small.scene, options)), "cornell");
    size_t refused = 0, loaded = 0;
    auto attempt = [&](const Bytes& b) {
        try {
            const LoadedScene scene = decodePackedScene(b, "fuzz.gpscene");
            ++loaded;
            const CameraBasis camera = makeCamera(*scene.scene.camera, 4, 4);
            RenderSettings settings;
            settings.width = settings.height = 4;
            settings.threads = 1;
            CpuTracer(scene.scene, *gridOf(scene.accel)).render(camera, settings);
        } catch (const InputError& e) {
            ++refused;
            const std::string message = e.what();
            ASSERT_EQ(message.rfind("fuzz.gpscene: ", 0), 0u) << message;
            ASSERT_EQ(message.find('\n'), std::string::npos) << message;
        }
    };
    for (size_t size = 0; size < bytes.size(); ++size)
        attempt(Bytes(bytes.begin(), bytes.begin() + std::ptrdiff_t(size)));
    EXPECT_EQ(refused, bytes.size());
    std::mt19937 rng(4);
    for (size_t at = 0; at < bytes.size(); ++at) {
        for (const unsigned mask : {0x01u, 0x80u, 0xffu, unsigned(rng() % 255 + 1)}) {
            Bytes b = bytes;
            b[at] ^= static_cast<unsigned char>(mask);
            const size_t before = refused;
            attempt(b);
            EXPECT_EQ(refused, before + 1) << "unsealed flip at " << at;
            reseal(b);
            attempt(b);
        }
    }
    // Most resealed flips hit floats and names, which may load; the rest are refused.
    EXPECT_GT(loaded, 0u);
    EXPECT_GT(refused, bytes.size() * 4);
}

}  // namespace
}  // namespace gpurt

namespace gpurt {
namespace {

// The environment light (ENVM: flags, strength, rotation, size, name, texels): written only for a
// scene with an environment or a background of its own, so that other files stay as they were;
// kept through the round trip with the flag that the background was given (which decides the
// default light); sizes and texels that lie are refused.
TEST_F(PackedSceneTest, EnvironmentTravelsInItsOwnSection) {
    EXPECT_FALSE(findSection(bytes_, "ENVM")) << "a scene without environment or background of its own";
    LoadedScene lit = source_;
    auto image = std::make_shared<EnvironmentImage>();
    image->width = 4;
    image->height = 2;
    for (int k = 0; k < 8; ++k) image->texels.push_back(glm::vec3(float(k), 0.5f, 2.0f * float(k)));
    Environment env;
    env.image = image;
    env.strength = 1.5f;
    env.rotation = -30.0f;
    env.file = "sky.hdr";
    lit.scene.environment = env;
    lit.scene.backgroundGiven = true;
    const Bytes b = encodePackedScene(lit, *makeStructure(grid_), "lit");
    const Entry envm = section(b, "ENVM");
    EXPECT_EQ(envm.size, 24 + 7 + 12 * 8);
    const LoadedScene packed = decodePackedScene(b, "lit.gpscene");
    ASSERT_TRUE(packed.scene.environment);
    EXPECT_TRUE(packed.scene.backgroundGiven);
    EXPECT_EQ(packed.scene.environment->image->texels, image->texels);
    EXPECT_EQ(packed.scene.environment->strength, 1.5f);
    EXPECT_EQ(packed.scene.environment->rotation, -30.0f);
    EXPECT_EQ(packed.scene.environment->file, "sky.hdr");
    EXPECT_EQ(encodePackedScene(packed, *packed.accel, "again"), b);

    LoadedScene background = source_;  // the flag alone
    background.scene.backgroundGiven = true;
    const Bytes g = encodePackedScene(background, *makeStructure(grid_), "background");
    EXPECT_EQ(section(g, "ENVM").size, 4u);
    EXPECT_TRUE(decodePackedScene(g, "g.gpscene").scene.backgroundGiven);
    EXPECT_FALSE(decodePackedScene(g, "g.gpscene").scene.environment);

    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, envm.offset, 7); }), "section ENVM: unknown flags 7");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, envm.offset + 12, 5); }), "section ENVM: ");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, envm.offset + 16, 0); }), "environment map of 4x0");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, envm.offset + 12, 100000); }), "environment map of 100000x2");
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, envm.offset + 4, 0xff800000u); }), "strength");  // -inf
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, envm.offset + 24 + 7, 0x7fc00000u); }), "not finite");  // NaN texel
    EXPECT_REFUSED(patched(b, [&](Bytes& p) { put32(p, envm.offset + 20, 1u << 30); }), "section ENVM: ");
}

}  // namespace
}  // namespace gpurt
