// The BVH (accel/bvh): its invariants on random and degenerate inputs (every triangle in exactly one
// leaf, child boxes holding their triangles and inside their parents), the same tree for any
// thread count, checkBvh refusing damaged trees, and its traversal finding the same closest hits
// as an independent brute force over all triangles (and the grid) and the same occlusion.
#include "raytrace/accel/bvh/BvhAccelerator.h"
#include "raytrace/accel/grid/GridAccelerator.h"
#include "raytrace/accel/bvh/Bvh.h"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "raytrace/common/RayMath.h"
#include "raytrace/accel/Acceleration.h"
#include "raytrace/accel/bvh/BvhCpu.h"
#include "raytrace/accel/grid/GridCpu.h"
#include "scene/ObjLoader.h"

namespace gpurt {
namespace {

// Triangles of mixed sizes (0.001 to 100) and shapes (axis planes, slivers, general) in a box.
Scene randomScene(int count, unsigned seed, float spread = 10.0f) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(0.0f, spread), unit(-1.0f, 1.0f);
    std::uniform_int_distribution<int> kind(0, 4);
    Scene scene;
    scene.materials.push_back(Material{});
    for (int k = 0; k < count; ++k) {
        const glm::vec3 a(pos(rng), pos(rng), pos(rng));
        const float size = std::pow(10.0f, unit(rng) * 2.0f);
        glm::vec3 b = a + size * glm::vec3(unit(rng), unit(rng), unit(rng));
        glm::vec3 c = a + size * glm::vec3(unit(rng), unit(rng), unit(rng));
        switch (kind(rng)) {
            case 0: b.y = c.y = a.y; break;          // in a y plane
            case 1: c = a + 0.999f * (b - a); break;  // sliver
            default: break;
        }
        scene.triangles.push_back({a, b, c});
        scene.materialIds.push_back(0);
    }
    return scene;
}

void expectValid(const Scene& scene, const Bvh& bvh) {
    EXPECT_EQ(checkBvh(bvh, scene.triangles.size(), &scene), "");
    EXPECT_LE(bvh.depth, kBvhMaxDepth);
    EXPECT_EQ(bvh.depth, bvhDepth(bvh));
}

TEST(BvhTest, InvariantsOnRandomScenes) {
    for (unsigned seed : {1u, 2u, 3u}) {
        const Scene scene = randomScene(int(500 * seed), seed);
        for (int leaf : {1, 4, kBvhMaxLeafSize}) {
            const Bvh bvh = buildBvh(scene, {0, leaf});
            expectValid(scene, bvh);
            for (const Bvh::Node& n : bvh.nodes)
                for (const Bvh::Child& c : n.child) EXPECT_LE(c.count, uint32_t(leaf));
        }
    }
}

TEST(BvhTest, InvariantsOnDegenerateScenes) {
    Scene point;  // every triangle in one point: split at the middle of the range
    point.materials.push_back(Material{});
    for (int k = 0; k < 1000; ++k) {
        point.triangles.push_back({glm::vec3(1, 2, 3), glm::vec3(1, 2, 3), glm::vec3(1, 2, 3)});
        point.materialIds.push_back(0);
    }
    Scene plane = randomScene(2000, 5);  // every triangle in the plane y = 0
    for (Triangle& t : plane.triangles) t.v0.y = t.v1.y = t.v2.y = 0.0f;
    Scene mixed = randomScene(300, 9, 1e-3f);  // tiny triangles beside huge ones far away
    const Scene huge = randomScene(50, 10, 1e5f);
    for (const Triangle& t : huge.triangles) {
        mixed.triangles.push_back({t.v0 * 100.0f, t.v1 * 100.0f, t.v2 * 100.0f});
        mixed.materialIds.push_back(0);
    }
    Scene one = randomScene(1, 4);
    Scene none;
    for (const Scene* scene : {&point, &plane, &mixed, &one, &none}) {
        const Bvh bvh = buildBvh(*scene);
        expectValid(*scene, bvh);
    }
}

TEST(BvhTest, SameTreeForAnyThreadCount) {
    const Scene scene = randomScene(100000, 8);  // big enough for the parallel halves
    const Bvh one = buildBvh(scene, {1, 4});
    const Bvh two = buildBvh(scene, {2, 4});
    const Bvh many = buildBvh(scene, {7, 4});
    for (const Bvh* other : {&two, &many}) {
        ASSERT_EQ(one.nodes.size(), other->nodes.size());
        EXPECT_EQ(one.triangles, other->triangles);
        for (size_t n = 0; n < one.nodes.size(); ++n)
            for (int c = 0; c < 2; ++c) {
                EXPECT_EQ(one.nodes[n].child[c].ref, other->nodes[n].child[c].ref);
                EXPECT_EQ(one.nodes[n].child[c].count, other->nodes[n].child[c].count);
                EXPECT_EQ(one.nodes[n].child[c].min, other->nodes[n].child[c].min);
            }
    }
}

TEST(BvhTest, CheckRefusesDamagedTrees) {
    const Scene scene = randomScene(200, 3);
    const Bvh good = buildBvh(scene);
    ASSERT_EQ(checkBvh(good, scene.triangles.size(), &scene), "");
    auto firstInner = [](const Bvh& b) -> Bvh::Child& {
        for (const Bvh::Node& n : b.nodes)
            for (const Bvh::Child& c : n.child)
                if (c.count == 0 && c.ref > 0) return const_cast<Bvh::Child&>(c);
        throw std::runtime_error("no inner child");
    };
    Bvh bad = good;
    firstInner(bad).ref = int32_t(bad.nodes.size());  // past the end
    EXPECT_NE(checkBvh(bad, scene.triangles.size()), "");
    bad = good;
    bad.nodes.back().child[0] = {glm::vec3(0), glm::vec3(1), 1, 0};  // a cycle back to node 1
    EXPECT_NE(checkBvh(bad, scene.triangles.size()), "");
    bad = good;
    firstInner(bad).ref = 0;  // the root again
    EXPECT_NE(checkBvh(bad, scene.triangles.size()), "");
    bad = good;
    for (Bvh::Node& n : bad.nodes)
        for (Bvh::Child& c : n.child)
            if (c.count > 0) c.count += uint32_t(scene.triangles.size());  // counts past the end
    EXPECT_NE(checkBvh(bad, scene.triangles.size()), "");
    bad = good;
    bad.triangles[0] = bad.triangles[1];  // a triangle twice, another in no leaf
    EXPECT_NE(checkBvh(bad, scene.triangles.size()), "");
    bad = good;
    bad.nodes[0].child[0].max = bad.nodes[0].child[0].min;  // triangles outside their box
    EXPECT_NE(checkBvh(bad, scene.triangles.size(), &scene), "");
    bad = good;
    bad.nodes[0].child[1].min.x = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(checkBvh(bad, scene.triangles.size()), "");
}

// The closest hit by testing every triangle, in double precision for the order of hits, with
// the same triangle test: (t, id).
std::pair<float, int> bruteForce(const Scene& scene, glm::vec3 o, glm::vec3 d, float tLimit) {
    float best = tLimit;
    int id = -1;
    const raymath::WatertightRay ray = raymath::watertightRay(o, d);
    for (size_t k = 0; k < scene.triangles.size(); ++k) {
        const Triangle& tr = scene.triangles[k];
        float t, u, v;
        if (raymath::intersectTriangle(ray, tr.v0, tr.v1, tr.v2, t, u, v) && t > 0.0f && t < best) {
            best = t;
            id = int(k);
        }
    }
    return {best, id};
}

TEST(BvhTest, ClosestAndAnyHitAgreeWithBruteForceAndTheGrid) {
    const Scene scene = loadObj("../shared/models/bunny_lo.obj");
    const Bvh bvh = buildBvh(scene);
    const UniformGrid grid = buildGrid(scene, {});
    const BvhCpu tracer(scene, bvh);
    const GridCpu gridTracer(scene, grid);
    std::mt19937 rng(17);
    const Bounds b = scene.bounds();
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    int rays = 0, hits = 0, same = 0, sameAsGrid = 0, occlusionSame = 0;
    for (int k = 0; k < 4000; ++k) {
        // From a sphere around the model toward a point inside its box, or from inside.
        const glm::vec3 target = b.center() + b.halfExtent() * glm::vec3(unit(rng), unit(rng), unit(rng));
        const glm::vec3 o = k % 4 == 0 ? b.center() + 0.3f * b.halfExtent() * glm::vec3(unit(rng), unit(rng), unit(rng))
                                       : b.center() + 3.0f * glm::length(b.halfExtent()) *
                                                          glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng)));
        if (glm::length(target - o) == 0.0f) continue;
        const glm::vec3 d = raymath::contractNormalize(target - o);
        const float tLimit = k % 3 == 0 ? 0.5f * glm::length(target - o) : 1e30f;
        const auto [t, id] = bruteForce(scene, o, d, tLimit);
        const TraceHit hit = tracer.closestHit(o, d, tLimit, 0u);
        const TraceHit gridHit = gridTracer.closestHit(o, d, tLimit, 0u);
        const TraceHit any = tracer.anyHit(o, d, tLimit, 0u);
        ++rays;
        hits += id >= 0;
        // The same t (the same triangle, or another at exactly the same distance: a shared edge).
        same += hit.prim == id || (id >= 0 && hit.prim >= 0 && hit.t == t);
        sameAsGrid += hit.prim == gridHit.prim || (hit.prim >= 0 && gridHit.prim >= 0 && hit.t == gridHit.t);
        occlusionSame += (any.prim >= 0) == (id >= 0);
        EXPECT_NE(hit.state, RAY_OVERFLOW);
    }
    EXPECT_GT(hits, rays / 4);
    EXPECT_EQ(same, rays);
    EXPECT_GE(double(sameAsGrid) / rays, 0.999);
    EXPECT_EQ(occlusionSame, rays);
}

TEST(BvhTest, AutoPicksByTheEstimateAndKeepsOnlyTheChosenStructure) {
    const Scene scene = loadObj("../shared/models/bunny_lo.obj");
    const CameraBasis camera = makeCamera(defaultCamera(scene.bounds(), 64, 64), 64, 64);
    const Acceleration a = chooseAcceleration(scene, "auto", nullptr, {}, camera);
    // Every registered accelerator estimated, as each one built alone estimates; the cheapest kept.
    ASSERT_EQ(a.estimate.size(), accelerators().size());
    std::string cheapest;
    double best = 0;
    for (size_t k = 0; k < accelerators().size(); ++k) {
        const AcceleratorInfo& info = *accelerators()[k];
        EXPECT_EQ(a.estimate[k].first, info.name);
        EXPECT_EQ(a.estimate[k].second, estimateCost(scene, *info.build(scene, {}), camera)) << info.name;
        if (cheapest.empty() || a.estimate[k].second < best) {
            cheapest = info.name;
            best = a.estimate[k].second;
        }
    }
    EXPECT_EQ(a.name(), cheapest);
    EXPECT_EQ(gridOf(a.structure) != nullptr, a.name() == "grid");
    EXPECT_EQ(bvhOf(a.structure) != nullptr, a.name() == "bvh");
    EXPECT_EQ(a.source, "auto");
    // A given structure stands under auto (a packed scene's).
    const Acceleration packed = chooseAcceleration(scene, "auto", makeStructure(buildBvh(scene)), {}, camera);
    EXPECT_EQ(packed.name(), "bvh");
    EXPECT_EQ(packed.source, "packed");
    EXPECT_TRUE(packed.estimate.empty());
    // Both structures offset secondary rays alike: the same images.
    const Acceleration grid = chooseAcceleration(scene, "grid", nullptr, {}, camera);
    EXPECT_EQ(grid.rayOffset(), packed.rayOffset());
}

}  // namespace
}  // namespace gpurt
