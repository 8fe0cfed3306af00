// Smooth normals on many threads (SmoothNormals.h) against the serial pass they replaced, kept
// here word for word as the reference: a position map of corner lists in triangle order. The
// meshes share positions across triangles (as a scanned model does), have -0 beside +0,
// degenerate and non-finite triangles, and normals from the file on some triangles; the normals
// must be bit for bit the reference's on 1, 2, 3 and 8 threads.
#include "scene/SmoothNormals.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <unordered_map>
#include <vector>

namespace gpurt {
namespace {

struct PositionHash {
    size_t operator()(const glm::vec3& p) const {
        size_t h = 0;
        for (int i = 0; i < 3; ++i) {
            uint32_t bits;
            const float c = p[i] == 0.0f ? 0.0f : p[i];
            std::memcpy(&bits, &c, 4);
            h = h * 0x9e3779b97f4a7c15ull + bits;
        }
        return h;
    }
};

bool usable(const TriangleNormals& n) {
    for (const glm::vec3& v : {n.n0, n.n1, n.n2})
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z) || v == glm::vec3(0.0f)) return false;
    return true;
}

// The serial implementation as it was before it ran on threads.
void referenceSmoothNormals(Scene& scene, float creaseDegrees) {
    const size_t n = scene.triangles.size();
    scene.normals.resize(n);
    std::vector<bool> fromFile(n);
    bool anyMissing = false;
    for (size_t t = 0; t < n; ++t) {
        fromFile[t] = usable(scene.normals[t]);
        if (!fromFile[t]) {
            scene.normals[t] = TriangleNormals{};
            anyMissing = true;
        }
    }
    if (!anyMissing) return;
    std::vector<glm::dvec3> face(n);
    std::vector<glm::dvec3> angle(n);
    for (size_t t = 0; t < n; ++t) {
        const Triangle& tri = scene.triangles[t];
        const glm::dvec3 p[3] = {tri.v0, tri.v1, tri.v2};
        const glm::dvec3 c = glm::cross(p[1] - p[0], p[2] - p[0]);
        const double len = glm::length(c);
        if (!(len > 0.0) || !std::isfinite(len)) continue;
        face[t] = c / len;
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
            const double la = glm::length(a), lb = glm::length(b);
            angle[t][k] = la > 0.0 && lb > 0.0 ? std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0, 1.0)) : 0.0;
        }
    }
    std::unordered_map<glm::vec3, std::vector<uint32_t>, PositionHash> corners;
    for (size_t t = 0; t < n; ++t) {
        if (face[t] == glm::dvec3(0.0)) continue;
        const Triangle& tri = scene.triangles[t];
        const glm::vec3 p[3] = {tri.v0, tri.v1, tri.v2};
        for (uint32_t k = 0; k < 3; ++k) corners[p[k]].push_back(uint32_t(3 * t + k));
    }
    const double cosCrease = std::cos(double(creaseDegrees) * M_PI / 180.0);
    for (size_t t = 0; t < n; ++t) {
        if (fromFile[t] || face[t] == glm::dvec3(0.0)) continue;
        const Triangle& tri = scene.triangles[t];
        const glm::vec3 p[3] = {tri.v0, tri.v1, tri.v2};
        glm::vec3 out[3];
        for (int k = 0; k < 3; ++k) {
            glm::dvec3 sum(0.0);
            for (uint32_t corner : corners[p[k]]) {
                const size_t other = corner / 3;
                const double c = glm::dot(face[other], face[t]);
                if (std::fabs(c) < cosCrease && other != t) continue;
                sum += (c < 0.0 ? -1.0 : 1.0) * angle[other][corner % 3] * face[other];
            }
            const double len = glm::length(sum);
            out[k] = glm::vec3(len > 0.0 ? sum / len : face[t]);
        }
        scene.normals[t] = {out[0], out[1], out[2]};
    }
}

// A bumpy height field of `side` x `side` quads (positions shared by up to 6 triangles), its
// triangles shuffled, with -0 for some zero coordinates, a few degenerate and non-finite
// triangles, random windings, and the file's normals on some triangles.
Scene testMesh(int side, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> bump(-0.3f, 0.3f);
    std::vector<float> height(size_t((side + 1) * (side + 1)));
    for (float& h : height) h = bump(rng);
    auto at = [&](int i, int j) {
        return glm::vec3(float(i - side / 2), height[size_t(j * (side + 1) + i)], float(j - side / 2));
    };
    Scene scene;
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
            scene.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            scene.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    scene.triangles.push_back({at(0, 0), at(0, 0), at(1, 1)});                    // degenerate
    scene.triangles.push_back({at(0, 0), glm::vec3(INFINITY, 0, 0), at(1, 1)});  // not finite
    scene.triangles.push_back({at(2, 2), at(2, 2) + glm::vec3(1, 0, 0), at(2, 2) + glm::vec3(2, 0, 0)});  // a line
    std::shuffle(scene.triangles.begin(), scene.triangles.end(), rng);
    for (Triangle& t : scene.triangles) {
        if (rng() % 2) std::swap(t.v1, t.v2);
        for (glm::vec3* p : {&t.v0, &t.v1, &t.v2})  // -0 for some of a position's zeros: the same position
            for (int a = 0; a < 3; a += 2)
                if ((*p)[a] == 0.0f && rng() % 2) (*p)[a] = -0.0f;
    }
    scene.normals.assign(scene.triangles.size(), TriangleNormals{});
    for (size_t t = 0; t < scene.triangles.size(); t += 7)
        scene.normals[t] = {glm::vec3(0, 1, 0), glm::vec3(0, 0.6f, 0.8f), glm::vec3(1, 0, 0)};
    scene.normals[3] = {glm::vec3(NAN, 1, 0), glm::vec3(0, 1, 0), glm::vec3(0, 1, 0)};  // unusable: smoothed
    scene.materialIds.assign(scene.triangles.size(), 0);
    scene.materials.push_back(Material{});
    return scene;
}

bool sameBits(const glm::vec3& a, const glm::vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(SmoothNormals, ThreadsGiveTheSerialPassesNormalsBitForBit) {
    for (const float crease : {kDefaultCreaseDegrees, 20.0f, 180.0f})
        for (const int threads : {1, 2, 3, 8}) {
            const Scene mesh = testMesh(150, 7u + uint32_t(threads));  // 45,000 triangles: many chunks
            Scene expected = mesh, got = mesh;
            referenceSmoothNormals(expected, crease);
            smoothNormals(got, crease, threads);
            ASSERT_EQ(got.normals.size(), expected.normals.size());
            size_t differ = 0;
            for (size_t t = 0; t < got.normals.size(); ++t) {
                const TriangleNormals& g = got.normals[t];
                const TriangleNormals& e = expected.normals[t];
                if (!sameBits(g.n0, e.n0) || !sameBits(g.n1, e.n1) || !sameBits(g.n2, e.n2)) ++differ;
            }
            EXPECT_EQ(differ, 0u) << "crease " << crease << ", " << threads << " threads";
        }
}

// A triangle soup (no position shared): three times as many positions as a mesh of as many
// triangles, past the tables' first size.
TEST(SmoothNormals, ATriangleSoupAsTheSerialPass) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> pos(-1.0f, 1.0f);
    Scene soup;
    for (int t = 0; t < 20000; ++t) soup.triangles.push_back({{pos(rng), pos(rng), pos(rng)}, {pos(rng), pos(rng), pos(rng)}, {pos(rng), pos(rng), pos(rng)}});
    soup.materialIds.assign(soup.triangles.size(), 0);
    soup.materials.push_back(Material{});
    for (const int threads : {1, 2, 5}) {
        Scene expected = soup, got = soup;
        referenceSmoothNormals(expected, kDefaultCreaseDegrees);
        smoothNormals(got, kDefaultCreaseDegrees, threads);
        ASSERT_EQ(got.normals.size(), expected.normals.size());
        for (size_t t = 0; t < got.normals.size(); ++t)
            ASSERT_TRUE(sameBits(got.normals[t].n0, expected.normals[t].n0) && sameBits(got.normals[t].n2, expected.normals[t].n2))
                << "triangle " << t << ", " << threads << " threads";
    }
}

TEST(SmoothNormals, AMeshWithEveryNormalGivenKeepsThem) {
    Scene mesh = testMesh(4, 1);
    for (TriangleNormals& n : mesh.normals) n = {glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), glm::vec3(0, 0, 1)};
    const Scene before = mesh;
    smoothNormals(mesh, kDefaultCreaseDegrees, 2);
    for (size_t t = 0; t < mesh.normals.size(); ++t) EXPECT_TRUE(sameBits(mesh.normals[t].n1, before.normals[t].n1));
}

}  // namespace
}  // namespace gpurt
