// Packed sections of the geometry: triangles and their material ids (TRIS), vertex normals (NRML),
// texture coordinates (TXCO), vertex colours (VCOL) and tangents (TANG).
#include "raytrace/scene/packed/Sections.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "image/EnvironmentImage.h"
#include "raytrace/common/RayMath.h"
#include "raytrace/textures/SceneTextureLayout.h"

namespace gpurt::packed {

namespace {

constexpr size_t kNormalsBytes = 9 * 4;
constexpr size_t kTexcoordsBytes = 6 * 4;
constexpr size_t kColorsBytes = 9 * 4;
constexpr size_t kTangentsBytes = 12 * 4;
constexpr size_t kTriangleBytes = 9 * 4 + 4;      // three vertices, then (separately) the id

void readTriangles(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
    const uint64_t n = s.count(in, kTriangleBytes, true, kMaxTextureTriangles, "triangles");
    scene.triangles.resize(size_t(n));
    for (Triangle& t : scene.triangles) {
        t.v0 = in.vec3();
        t.v1 = in.vec3();
        t.v2 = in.vec3();
    }
    scene.materialIds.resize(size_t(n));
    for (uint32_t& id : scene.materialIds) id = in.u32();
}

void writeTriangles(ByteWriter& out, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    out.u64(scene.triangles.size());
    for (const Triangle& t : scene.triangles) {
        out.vec3(t.v0);
        out.vec3(t.v1);
        out.vec3(t.v2);
    }
    out.u32s(scene.materialIds);
}

void readNormals(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
    const uint64_t n = perTriangle(in, s, kNormalsBytes, "normals", scene);
    scene.normals.resize(size_t(n));
    for (TriangleNormals& t : scene.normals) {
        t.n0 = in.vec3();
        t.n1 = in.vec3();
        t.n2 = in.vec3();
    }
}

void writeNormals(ByteWriter& out, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    out.u64(scene.normals.size());
    for (const TriangleNormals& n : scene.normals) {
        out.vec3(n.n0);
        out.vec3(n.n1);
        out.vec3(n.n2);
    }
}

// Per triangle t0, t1, t2.
void readTexcoords(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
    const uint64_t n = perTriangle(in, s, kTexcoordsBytes, "texture coordinates", scene);
    scene.texcoords.resize(size_t(n));
    for (TriangleTexcoords& t : scene.texcoords) {
        const glm::vec2 c[3] = {{in.f32(), in.f32()}, {in.f32(), in.f32()}, {in.f32(), in.f32()}};
        t = {c[0], c[1], c[2]};
    }
}

void writeTexcoords(ByteWriter& out, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    out.u64(scene.texcoords.size());
    for (const TriangleTexcoords& t : scene.texcoords)
        for (const glm::vec2 c : {t.t0, t.t1, t.t2}) {
            out.f32(c.x);
            out.f32(c.y);
        }
}

// Per triangle c0, c1, c2.
void readColors(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
    const uint64_t n = perTriangle(in, s, kColorsBytes, "vertex colours", scene);
    scene.colors.resize(size_t(n));
    for (TriangleColors& t : scene.colors) {
        t.c0 = in.vec3();
        t.c1 = in.vec3();
        t.c2 = in.vec3();
    }
}

void writeColors(ByteWriter& out, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    out.u64(scene.colors.size());
    for (const TriangleColors& c : scene.colors) {
        out.vec3(c.c0);
        out.vec3(c.c1);
        out.vec3(c.c2);
    }
}

// Per triangle t0, t1, t2, each (x, y, z, w).
void readTangents(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
    const uint64_t n = perTriangle(in, s, kTangentsBytes, "vertex tangents", scene);
    scene.tangents.resize(size_t(n));
    for (TriangleTangents& t : scene.tangents)
        for (glm::vec4* c : {&t.t0, &t.t1, &t.t2}) {
            const glm::vec3 xyz = in.vec3();
            *c = glm::vec4(xyz, in.f32());
        }
}

void writeTangents(ByteWriter& out, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    out.u64(scene.tangents.size());
    for (const TriangleTangents& t : scene.tangents)
        for (const glm::vec4 c : {t.t0, t.t1, t.t2}) {
            out.vec3(glm::vec3(c));
            out.f32(c.w);
        }
}

}  // namespace

const SceneSection kTriangleSection{"TRIS", [](const LoadedScene&) { return true; }, true, writeTriangles,
                                     [](const PackedSection& s, LoadedScene& l) { readTriangles(s, l.scene); }};
const SceneSection kNormalSection{"NRML", [](const LoadedScene& l) { return !l.scene.normals.empty(); }, false,
                                   writeNormals, [](const PackedSection& s, LoadedScene& l) { readNormals(s, l.scene); }};
const SceneSection kTexcoordSection{"TXCO", [](const LoadedScene& l) { return !l.scene.texcoords.empty(); }, false,
                                     writeTexcoords,
                                     [](const PackedSection& s, LoadedScene& l) { readTexcoords(s, l.scene); }};
// Only for a scene with vertex colours: other files stay as they were before the section existed.
const SceneSection kColorSection{"VCOL", [](const LoadedScene& l) { return !l.scene.colors.empty(); }, false,
                                  writeColors, [](const PackedSection& s, LoadedScene& l) { readColors(s, l.scene); }};
// Only for a scene with vertex tangents (glTF TANGENT): likewise.
const SceneSection kTangentSection{"TANG", [](const LoadedScene& l) { return !l.scene.tangents.empty(); }, false,
                                    writeTangents,
                                    [](const PackedSection& s, LoadedScene& l) { readTangents(s, l.scene); }};

// The triangle and material counts the GL backend can carry, and each triangle's vertices and
// material id.
void checkTriangles(const FileLoc& file, const Scene& scene) {
    const size_t n = scene.triangles.size();
    if (n > kMaxTextureTriangles)
        failAt(file, std::to_string(n) + " triangles; at most " + std::to_string(kMaxTextureTriangles) +
                         " fit the GL backend (triangle ids travel as float32, exact below 2^24)");
    if (scene.materials.empty()) failAt(file, "no materials (a scene has at least the default material)");
    if (scene.materials.size() > kMaxTextureMaterials)
        failAt(file, std::to_string(scene.materials.size()) + " materials; at most " +
                         std::to_string(kMaxTextureMaterials) +
                         " fit the GL backend (material ids travel as float32, exact below 2^24)");
    if (scene.materialIds.size() != n)
        failAt(file, std::to_string(scene.materialIds.size()) + " material ids for " + std::to_string(n) +
                         " triangles");
    for (size_t t = 0; t < n; ++t) {
        const Triangle& tri = scene.triangles[t];
        if (!isFinite(tri.v0) || !isFinite(tri.v1) || !isFinite(tri.v2))
            failAt(file, "triangle " + std::to_string(t) + ": vertex coordinates are not finite");
        if (scene.materialIds[t] >= scene.materials.size())
            failAt(file, "triangle " + std::to_string(t) + ": material id " +
                             std::to_string(scene.materialIds[t]) + " out of range (" +
                             std::to_string(scene.materials.size()) + " materials)");
    }
}

// One colour record per triangle, each corner's linear RGB finite and in [0, 1].
void checkColors(const FileLoc& file, const Scene& scene) {
    const size_t n = scene.triangles.size();
    if (!scene.colors.empty() && scene.colors.size() != n)
        failAt(file, std::to_string(scene.colors.size()) + " vertex colours for " + std::to_string(n) + " triangles");
    for (size_t t = 0; t < scene.colors.size(); ++t)
        for (const glm::vec3 c : {scene.colors[t].c0, scene.colors[t].c1, scene.colors[t].c2})
            if (!isFinite(c) || !nonNegative(c) || glm::any(glm::greaterThan(c, glm::vec3(1.0f))))
                failAt(file, "triangle " + std::to_string(t) + ": vertex colours must be finite and in [0, 1]");
}

// One tangent record per triangle, each corner's four numbers finite and its handedness w -1, 0
// (a corner without a tangent) or 1. The tangent's length is not checked: a zero or tiny one
// falls back to the generated frame where it is used (glsl/common/shading.h normalMappedTangent).
void checkTangents(const FileLoc& file, const Scene& scene) {
    const size_t n = scene.triangles.size();
    if (!scene.tangents.empty() && scene.tangents.size() != n)
        failAt(file, std::to_string(scene.tangents.size()) + " vertex tangents for " + std::to_string(n) + " triangles");
    for (size_t t = 0; t < scene.tangents.size(); ++t)
        for (const glm::vec4 c : {scene.tangents[t].t0, scene.tangents[t].t1, scene.tangents[t].t2})
            if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z) ||
                (c.w != -1.0f && c.w != 0.0f && c.w != 1.0f))
                failAt(file, "triangle " + std::to_string(t) + ": vertex tangents must be finite with w -1, 0 or 1");
}

}  // namespace gpurt::packed
