// CpuTracer::trace against a brute-force closest hit over all triangles (Moller-Trumbore in
// double, no grid) on random rays through real meshes, from outside and inside the grid, with
// and without a ray limit; and render() bookkeeping (AOVs on misses, ray counts).
#include "raytrace/render/CpuTracer.h"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "scene/ObjLoader.h"
#include "raytrace/common/RayMath.h"

namespace gpurt {
namespace {

struct BruteHit {
    double t = std::numeric_limits<double>::infinity();
    int prim = -1;
};

// Moller & Trumbore (1997) in double, written out separately from raymath.h.
bool intersectDouble(glm::dvec3 o, glm::dvec3 d, const Triangle& tri, double& t) {
    const glm::dvec3 v0(tri.v0), e1 = glm::dvec3(tri.v1) - v0, e2 = glm::dvec3(tri.v2) - v0;
    const glm::dvec3 p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0) return false;
    const glm::dvec3 s = o - v0;
    const double u = glm::dot(s, p) / det;
    if (u < 0.0 || u > 1.0) return false;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(d, q) / det;
    if (v < 0.0 || u + v > 1.0) return false;
    t = glm::dot(e2, q) / det;
    return true;
}

BruteHit bruteForce(const Scene& scene, glm::vec3 o, glm::vec3 d, double tLimit) {
    BruteHit best;
    for (size_t k = 0; k < scene.triangles.size(); ++k) {
        double t;
        if (intersectDouble(o, d, scene.triangles[k], t) && t > 0.0 && t < tLimit && t < best.t) {
            best.t = t;
            best.prim = int(k);
        }
    }
    return best;
}

struct Agreement {
    int rays = 0, hitMissDisagree = 0, primDisagree = 0, depthDisagree = 0, bothHit = 0;
};

Agreement compareRandomRays(const char* model, int count, unsigned seed, bool insideOrigins) {
    const Scene scene = loadObj(std::string("../shared/models/") + model);
    const UniformGrid grid = buildGrid(scene, {});
    const CpuTracer tracer(scene, grid);
    const Bounds b = scene.bounds();
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Agreement a;
    for (int k = 0; k < count; ++k) {
        // Origins around the model (or inside its box), aimed at random points of the box.
        const glm::vec3 span = b.max - b.min;
        const glm::vec3 lo = insideOrigins ? b.min : b.min - span,
                        hi = insideOrigins ? b.max : b.max + span;
        const glm::vec3 o = lo + (hi - lo) * glm::vec3(u(rng), u(rng), u(rng));
        const glm::vec3 target = b.min + span * glm::vec3(u(rng), u(rng), u(rng));
        const glm::vec3 d = raymath::contractNormalize(target - o);
        const TraceHit hit = tracer.trace(o, d, GPURT_FAR);
        const BruteHit ref = bruteForce(scene, o, d, 1e30);
        EXPECT_NE(hit.state, RAY_OVERFLOW);
        ++a.rays;
        if ((hit.prim >= 0) != (ref.prim >= 0)) {
            ++a.hitMissDisagree;
            continue;
        }
        if (hit.prim < 0) continue;
        ++a.bothHit;
        if (hit.prim != ref.prim) ++a.primDisagree;
        if (std::abs(hit.t - ref.t) > 1e-4 * ref.t) ++a.depthDisagree;
    }
    return a;
}

void expectAgreement(const Agreement& a, const char* what) {
    ASSERT_GT(a.bothHit, a.rays / 5) << what << ": too few hits to mean anything";
    EXPECT_LE(a.hitMissDisagree + a.primDisagree, a.rays / 1000) << what;
    EXPECT_LE(a.depthDisagree, a.bothHit / 1000) << what;
    std::printf(
        "[ stats    ] %s: %d rays, %d hit both, hit/miss differ %d, prim differs %d, depth differs "
        "%d\n",
        what, a.rays, a.bothHit, a.hitMissDisagree, a.primDisagree, a.depthDisagree);
}

TEST(CpuTracerTest, MatchesBruteForceOnTeapot) {
    expectAgreement(compareRandomRays("teapot.obj", 20000, 1, false), "teapot, outside");
    expectAgreement(compareRandomRays("teapot.obj", 10000, 2, true), "teapot, inside");
}

TEST(CpuTracerTest, MatchesBruteForceOnBunnyLo) {
    expectAgreement(compareRandomRays("bunny_lo.obj", 12000, 3, false), "bunny_lo, outside");
    expectAgreement(compareRandomRays("bunny_lo.obj", 6000, 4, true), "bunny_lo, inside");
}

TEST(CpuTracerTest, RayLimitActsLikeAShadowRay) {
    const Scene scene = loadObj("../shared/models/teapot.obj");
    const UniformGrid grid = buildGrid(scene, {});
    const CpuTracer tracer(scene, grid);
    const Bounds b = scene.bounds();
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int disagree = 0, occluded = 0;
    const int count = 10000;
    for (int k = 0; k < count; ++k) {
        const glm::vec3 span = b.max - b.min;
        const glm::vec3 from =
            b.min - 0.5f * span + 2.0f * span * glm::vec3(u(rng), u(rng), u(rng));
        const glm::vec3 to = b.min - 0.5f * span + 2.0f * span * glm::vec3(u(rng), u(rng), u(rng));
        const glm::vec3 d = raymath::contractNormalize(to - from);
        const float limit = glm::length(to - from);
        const TraceHit hit = tracer.trace(from, d, limit);
        const BruteHit ref = bruteForce(scene, from, d, limit);
        if (hit.prim >= 0) {
            EXPECT_LT(hit.t, limit);
            ++occluded;
        }
        if ((hit.prim >= 0) != (ref.prim >= 0)) ++disagree;
    }
    EXPECT_GT(occluded, count / 10);
    EXPECT_LE(disagree, count / 1000);
}

TEST(CpuTracerTest, MissesAndStepCounts) {
    const Scene scene = loadObj("../shared/models/teapot.obj");
    const UniformGrid grid = buildGrid(scene, {});
    const CpuTracer tracer(scene, grid);
    // Pointing away from the grid: no cell visited.
    const TraceHit away =
        tracer.trace(grid.max + 1.0f, raymath::contractNormalize(glm::vec3(1, 1, 1)), GPURT_FAR);
    EXPECT_EQ(away.prim, -1);
    EXPECT_EQ(away.steps, 0);
    EXPECT_EQ(away.state, RAY_INACTIVE);
    EXPECT_TRUE(std::isinf(away.t));
    // Straight through the middle: a hit after at least one cell.
    const TraceHit through = tracer.trace(glm::vec3(0, 0, 100), glm::vec3(0, 0, -1), GPURT_FAR);
    EXPECT_GE(through.prim, 0);
    EXPECT_GE(through.steps, 1);
    EXPECT_EQ(through.state, RAY_DEAD);
    // Along an edge of the box, outside every triangle: a miss that crosses the whole row of cells,
    // in at most one visit per cell (empty-space skipping visits fewer).
    const glm::vec3 o(grid.min.x + 0.5f * grid.cellSize.x, grid.min.y + 0.5f * grid.cellSize.y,
                      grid.max.z + 1.0f);
    const TraceHit edge = tracer.trace(o, glm::vec3(0, 0, -1), GPURT_FAR);
    EXPECT_EQ(edge.prim, -1);
    EXPECT_GE(edge.steps, 1);
    EXPECT_LE(edge.steps, grid.resolution.z);
    EXPECT_EQ(edge.state, RAY_DEAD);
}

TEST(CpuTracerTest, RenderOfEmptySceneIsBackground) {
    Scene scene;
    scene.materials.push_back(Material{});
    const UniformGrid grid = buildGrid(scene, {});
    const CpuTracer tracer(scene, grid);
    const CameraBasis camera = makeCamera(defaultCamera(scene.bounds(), 16, 8), 16, 8);
    RenderSettings settings;
    settings.threads = 2;
    const RenderOutput out = tracer.render(camera, settings);
    ASSERT_EQ(out.width, 16);
    ASSERT_EQ(out.height, 8);
    ASSERT_EQ(out.color.size(), 128u);
    for (size_t k = 0; k < out.color.size(); ++k) {
        EXPECT_EQ(out.color[k], scene.background);
        EXPECT_TRUE(std::isinf(out.depth[k]) && out.depth[k] > 0);
        EXPECT_EQ(out.prim[k], -1.0f);
        EXPECT_EQ(out.normal[k], glm::vec3(0.0f));
    }
    EXPECT_EQ(out.stats.primaryRays, 128u);
    EXPECT_EQ(out.stats.shadowRays, 0u);
    EXPECT_EQ(out.stats.secondaryRays, 0u);
}

TEST(CpuTracerTest, RenderAovsMatchTraceAndThreadCountDoesNotMatter) {
    const Scene scene = loadObj("../shared/models/teapot.obj");
    const UniformGrid grid = buildGrid(scene, {});
    const CpuTracer tracer(scene, grid);
    const CameraBasis camera = makeCamera({{0, 0, 52.68f}, {0, 0, 0}, {0, 1, 0}, 45.0f}, 96, 64);
    RenderSettings one;
    one.threads = 1;
    RenderSettings three;
    three.threads = 3;
    const RenderOutput a = tracer.render(camera, one);
    const RenderOutput b = tracer.render(camera, three);
    EXPECT_EQ(a.color, b.color);
    EXPECT_EQ(a.prim, b.prim);
    EXPECT_EQ(a.stats.primaryRays, 96u * 64u);
    EXPECT_EQ(a.stats.overflowRays, 0u);
    EXPECT_EQ(a.stats.shadowRays, b.stats.shadowRays);
    int hits = 0;
    for (int j = 0; j < camera.height; ++j)
        for (int i = 0; i < camera.width; ++i) {
            const size_t k = size_t(j) * 96 + size_t(i);
            const TraceHit hit =
                tracer.trace(camera.eye, primaryDirection(camera, i, j), GPURT_FAR);
            ASSERT_EQ(a.prim[k], float(hit.prim));
            ASSERT_EQ(a.steps[k], float(hit.steps));
            if (hit.prim < 0) continue;
            ++hits;
            ASSERT_EQ(a.depth[k], hit.t);
            const glm::vec3 n = a.normal[k];
            EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
            EXPECT_LE(glm::dot(n, primaryDirection(camera, i, j)), 0.0f);  // faces the eye
        }
    EXPECT_GT(hits, 96 * 64 / 20);
    // Headlight: one shadow ray per hit whose surface faces the light at most.
    EXPECT_LE(a.stats.shadowRays, uint64_t(hits));
    EXPECT_GT(a.stats.shadowRays, uint64_t(hits) / 2);
}

}  // namespace
}  // namespace gpurt
