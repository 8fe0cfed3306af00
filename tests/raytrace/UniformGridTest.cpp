// Uniform grid construction: no (triangle, cell) overlap may be missing (checked against an
// independent brute force that clips each triangle to each cell), the lists are well formed and
// the same for any thread count, and the box and resolution follow the stated rules.
#include "raytrace/accel/grid/UniformGrid.h"
#include "raytrace/accel/grid/GridAccelerator.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "image/InputError.h"
#include "scene/ObjLoader.h"

namespace gpurt {
namespace {

using Polygon = std::vector<glm::dvec3>;

// Sutherland-Hodgman: keeps the part of `poly` with sign * (p[axis] - value) >= 0.
Polygon clip(const Polygon& poly, int axis, double value, double sign) {
    Polygon out;
    for (size_t k = 0; k < poly.size(); ++k) {
        const glm::dvec3& a = poly[k];
        const glm::dvec3& b = poly[(k + 1) % poly.size()];
        const double da = sign * (a[axis] - value), db = sign * (b[axis] - value);
        if (da >= 0) out.push_back(a);
        if ((da >= 0) != (db >= 0)) out.push_back(a + (b - a) * (da / (da - db)));
    }
    return out;
}

// Whether the triangle has a point inside the box [lo, hi] (by clipping, not by separating axes).
bool clipOverlaps(const Triangle& t, glm::dvec3 lo, glm::dvec3 hi) {
    Polygon poly = {glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2)};
    for (int a = 0; a < 3 && !poly.empty(); ++a) {
        poly = clip(poly, a, lo[a], +1.0);
        if (!poly.empty()) poly = clip(poly, a, hi[a], -1.0);
    }
    return !poly.empty();
}

bool cellHas(const UniformGrid& grid, int cell, uint32_t id) {
    auto begin = grid.cellTriangles.begin() + grid.cellStart[size_t(cell)];
    auto end = grid.cellTriangles.begin() + grid.cellStart[size_t(cell) + 1];
    return std::binary_search(begin, end, id);
}

void expectWellFormed(const UniformGrid& grid, size_t triangleCount) {
    ASSERT_GE(grid.resolution.x, 1);
    ASSERT_GE(grid.resolution.y, 1);
    ASSERT_GE(grid.resolution.z, 1);
    ASSERT_EQ(grid.cellStart.size(), grid.cells() + 1);
    EXPECT_EQ(grid.cellStart.front(), 0u);
    EXPECT_EQ(grid.cellStart.back(), grid.cellTriangles.size());
    for (int a = 0; a < 3; ++a) {
        EXPECT_GT(grid.cellSize[a], 0.0f);
        EXPECT_LT(grid.min[a], grid.max[a]);
        EXPECT_NEAR(grid.cellSize[a], (grid.max[a] - grid.min[a]) / float(grid.resolution[a]),
                    1e-6f * grid.cellSize[a]);
    }
    for (size_t c = 0; c < grid.cells(); ++c) {
        ASSERT_LE(grid.cellStart[c], grid.cellStart[c + 1]);
        for (uint32_t k = grid.cellStart[c]; k < grid.cellStart[c + 1]; ++k) {
            ASSERT_LT(grid.cellTriangles[k], triangleCount);
            if (k > grid.cellStart[c]) {
                ASSERT_LT(grid.cellTriangles[k - 1], grid.cellTriangles[k]) << "cell " << c;
            }
        }
    }
}

// Random triangles of all sizes in [0, 10]^3, some axis-aligned, some slivers.
Scene randomScene(int count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(0.0f, 10.0f), unit(-1.0f, 1.0f);
    std::uniform_int_distribution<int> kind(0, 5);
    Scene scene;
    for (int k = 0; k < count; ++k) {
        const glm::vec3 base(pos(rng), pos(rng), pos(rng));
        const float size = std::pow(10.0f, unit(rng) * 1.2f);  // 0.06 .. 16
        glm::vec3 a = base, b = base + size * glm::vec3(unit(rng), unit(rng), unit(rng)),
                  c = base + size * glm::vec3(unit(rng), unit(rng), unit(rng));
        switch (kind(rng)) {
            case 0:
                b.z = c.z = a.z;
                break;  // in a z plane
            case 1:
                b.x = c.x = a.x;
                break;  // in an x plane
            case 2:
                c = a + 0.999f * (b - a);
                break;  // sliver
            default:
                break;
        }
        auto inside = [](glm::vec3 p) { return glm::clamp(p, glm::vec3(0.0f), glm::vec3(10.0f)); };
        scene.triangles.push_back({inside(a), inside(b), inside(c)});
        scene.materialIds.push_back(0);
    }
    scene.materials.push_back(Material{});
    return scene;
}

void expectNoMissingReferences(const Scene& scene, const UniformGrid& grid) {
    size_t pairs = 0, extra = 0;
    for (int z = 0; z < grid.resolution.z; ++z)
        for (int y = 0; y < grid.resolution.y; ++y)
            for (int x = 0; x < grid.resolution.x; ++x) {
                const glm::dvec3 cell(grid.cellSize);
                const glm::dvec3 lo = glm::dvec3(grid.min) + glm::dvec3(x, y, z) * cell;
                const glm::dvec3 hi = lo + cell;
                const int c = grid.cellIndex({x, y, z});
                for (uint32_t id = 0; id < scene.triangles.size(); ++id) {
                    // Must be referenced: overlaps the cell shrunk by a hair (rounding of the box).
                    if (clipOverlaps(scene.triangles[id], lo + 1e-6 * cell, hi - 1e-6 * cell)) {
                        ++pairs;
                        ASSERT_TRUE(cellHas(grid, c, id))
                            << "triangle " << id << " missing from cell " << x << "," << y << ","
                            << z;
                    } else if (cellHas(grid, c, id)) {
                        ++extra;
                        // An extra reference must at least be near the cell.
                        EXPECT_TRUE(
                            clipOverlaps(scene.triangles[id], lo - 0.01 * cell, hi + 0.01 * cell))
                            << "triangle " << id << " is far from cell " << x << "," << y << ","
                            << z;
                    }
                }
            }
    EXPECT_GT(pairs, scene.triangles.size());
    EXPECT_LE(extra, pairs / 20) << "too many references to cells the triangle does not overlap";
}

TEST(UniformGridTest, ReferencesEveryOverlappedCellAutomaticResolution) {
    const Scene scene = randomScene(400, 7);
    const UniformGrid grid = buildGrid(scene, {});
    expectWellFormed(grid, scene.triangles.size());
    expectNoMissingReferences(scene, grid);
}

TEST(UniformGridTest, ReferencesEveryOverlappedCellExplicitResolution) {
    const Scene scene = randomScene(300, 11);
    GridOptions options;
    options.resolution = glm::ivec3(7, 5, 9);
    const UniformGrid grid = buildGrid(scene, options);
    EXPECT_EQ(grid.resolution, glm::ivec3(7, 5, 9));
    expectWellFormed(grid, scene.triangles.size());
    expectNoMissingReferences(scene, grid);
}

TEST(UniformGridTest, TriangleOnACellBoundaryIsInBothCells) {
    Scene scene;
    scene.materials.push_back(Material{});
    scene.triangles.push_back({{0, 0, 0}, {8, 0, 8}, {0, 8, 8}});  // spans the box
    scene.materialIds.push_back(0);
    GridOptions options;
    options.resolution = glm::ivec3(4);
    const UniformGrid before = buildGrid(scene, options);
    // A small triangle in the plane between cell layers 1 and 2 (z) and one between columns 2 and
    // 3 (x), both inside the box so that the grid does not change.
    const float zPlane = before.min.z + before.cellSize.z * 2.0f;
    const float xPlane = before.min.x + before.cellSize.x * 3.0f;
    const glm::vec3 c = before.min + before.cellSize * glm::vec3(1.5f, 1.5f, 1.5f);
    scene.triangles.push_back({{c.x - 0.3f, c.y - 0.3f, zPlane},
                               {c.x + 0.3f, c.y - 0.3f, zPlane},
                               {c.x, c.y + 0.3f, zPlane}});
    scene.triangles.push_back({{xPlane, c.y - 0.3f, c.z - 0.3f},
                               {xPlane, c.y + 0.3f, c.z - 0.3f},
                               {xPlane, c.y, c.z + 0.3f}});
    scene.materialIds.resize(3, 0);
    const UniformGrid grid = buildGrid(scene, options);
    ASSERT_EQ(grid.min, before.min);
    ASSERT_EQ(grid.max, before.max);
    EXPECT_TRUE(cellHas(grid, grid.cellIndex({1, 1, 1}), 1));
    EXPECT_TRUE(cellHas(grid, grid.cellIndex({1, 1, 2}), 1));
    EXPECT_TRUE(cellHas(grid, grid.cellIndex({2, 1, 1}), 2));
    EXPECT_TRUE(cellHas(grid, grid.cellIndex({3, 1, 1}), 2));
}

// One thread is the serial build (one list of references, one pass of the counting sort); more
// threads count and fill in parallel and must give the same arrays, skip distances too.
TEST(UniformGridTest, SameGridForAnyThreadCount) {
    {
        const Scene scene = randomScene(6000, 3);
        GridOptions options;
        options.threads = 1;
        const UniformGrid one = buildGrid(scene, options);
        for (int threads : {2, 3, 7}) {
            options.threads = threads;
            const UniformGrid many = buildGrid(scene, options);
            EXPECT_EQ(many.resolution, one.resolution);
            EXPECT_EQ(many.cellStart, one.cellStart) << threads << " threads";
            EXPECT_EQ(many.cellTriangles, one.cellTriangles) << threads << " threads";
            EXPECT_EQ(many.skip, one.skip) << threads << " threads";
        }
    }
}

TEST(UniformGridTest, BoxIsPaddedBoundsAndResolutionFollowsTheBoxShape) {
    const Scene scene = loadObj("../shared/models/bunny_lo.obj");
    const Bounds b = scene.bounds();
    const UniformGrid grid = buildGrid(scene, {});
    expectWellFormed(grid, scene.triangles.size());
    const glm::vec3 extent = b.max - b.min;
    const float largest = std::max({extent.x, extent.y, extent.z});
    for (int a = 0; a < 3; ++a) {
        EXPECT_LT(grid.min[a], b.min[a]);
        EXPECT_GT(grid.max[a], b.max[a]);
        EXPECT_NEAR(b.min[a] - grid.min[a], 1e-4f * largest, 1e-6f * largest);
        EXPECT_NEAR(grid.max[a] - b.max[a], 1e-4f * largest, 1e-6f * largest);
    }
    // lambda * N^(1/3) cells along the longest axis (x for bunny_lo); the others in proportion.
    const double alongLongest = double(GridOptions{}.lambda) * std::cbrt(double(scene.triangles.size()));
    const glm::dvec3 boxExtent = glm::dvec3(grid.max) - glm::dvec3(grid.min);
    const double longest = std::max({boxExtent.x, boxExtent.y, boxExtent.z});
    for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(grid.resolution[a], alongLongest * boxExtent[a] / longest, 0.5 + 1e-9)
            << "axis " << a;
}

TEST(UniformGridTest, DegenerateScenes) {
    // No triangles: a valid 1x1x1 grid with nothing in it.
    Scene empty;
    empty.materials.push_back(Material{});
    const UniformGrid none = buildGrid(empty, {});
    expectWellFormed(none, 0);
    EXPECT_EQ(none.resolution, glm::ivec3(1));
    EXPECT_TRUE(none.cellTriangles.empty());

    // A flat scene (z = 5 everywhere) and a single point still get a box with volume.
    Scene flat = empty;
    flat.triangles.push_back({{0, 0, 5}, {4, 0, 5}, {0, 2, 5}});
    flat.materialIds.push_back(0);
    const UniformGrid flatGrid = buildGrid(flat, {});
    expectWellFormed(flatGrid, 1);
    EXPECT_EQ(flatGrid.resolution.z, 1);
    EXPECT_LT(flatGrid.min.z, 5.0f);
    EXPECT_GT(flatGrid.max.z, 5.0f);

    Scene point = empty;
    point.triangles.push_back({{1e6f, 2, 3}, {1e6f, 2, 3}, {1e6f, 2, 3}});
    point.materialIds.push_back(0);
    expectWellFormed(buildGrid(point, {}), 1);
}

TEST(UniformGridTest, RejectsBadResolution) {
    const Scene scene = randomScene(10, 1);
    GridOptions options;
    options.resolution = glm::ivec3(4, 0, 4);
    EXPECT_THROW(buildGrid(scene, options), InputError);
    options.resolution = glm::ivec3(100000, 100000, 100000);
    EXPECT_THROW(buildGrid(scene, options), InputError);
}

}  // namespace
}  // namespace gpurt

namespace gpurt {
namespace {

// computeSkip against a brute force: each empty cell's chessboard distance to the nearest
// non-empty cell (255 when there is none), 0 for non-empty cells.
TEST(UniformGridTest, SkipIsTheChessboardDistanceToTheNearestNonEmptyCell) {
    std::mt19937 rng(11);
    for (int trial = 0; trial < 16; ++trial) {
        UniformGrid grid;
        // The last trials big enough for many cells away from the faces (their unchecked path).
        grid.resolution = trial < 12 ? glm::ivec3(3 + int(rng() % 9), 2 + int(rng() % 7), 1 + int(rng() % 8))
                                     : glm::ivec3(14 + int(rng() % 4), 12 + int(rng() % 4), 10 + int(rng() % 4));
        std::vector<uint32_t> counts(grid.cells(), 0);
        for (int k = 0; k < trial % 5; ++k) counts[size_t(rng() % grid.cells())] = 2;
        grid.cellStart.assign(grid.cells() + 1, 0);
        for (size_t c = 0; c < grid.cells(); ++c) grid.cellStart[c + 1] = grid.cellStart[c] + counts[c];
        computeSkip(grid);
        const glm::ivec3 r = grid.resolution;
        for (int z = 0; z < r.z; ++z)
            for (int y = 0; y < r.y; ++y)
                for (int x = 0; x < r.x; ++x) {
                    int best = 255;
                    for (int zz = 0; zz < r.z; ++zz)
                        for (int yy = 0; yy < r.y; ++yy)
                            for (int xx = 0; xx < r.x; ++xx)
                                if (counts[size_t(grid.cellIndex({xx, yy, zz}))])
                                    best = std::min(best, std::max({std::abs(x - xx), std::abs(y - yy), std::abs(z - zz)}));
                    ASSERT_EQ(int(grid.skip[size_t(grid.cellIndex({x, y, z}))]), best)
                        << "trial " << trial << " cell " << x << "," << y << "," << z;
                }
    }
}

// A packed grid turns with its scene (--up-axis): the turned grid is the one built for the turned
// scene, cell for cell (the box pads alike on every side and the resolution follows the extents).
TEST(UniformGrid, TurnedGridIsTheGridOfTheTurnedScene) {
    const Scene scene = loadObj("../shared/models/bunny_lo.obj");
    const std::shared_ptr<const AccelStructure> packed = gridAccelerator().build(scene, {});
    for (const UpAxis axis : {UpAxis::PosX, UpAxis::NegX, UpAxis::NegY, UpAxis::PosZ, UpAxis::NegZ}) {
        SCOPED_TRACE(int(axis));
        Scene turned = scene;
        rotateUpToY(turned, axis);
        const UniformGrid built = buildGrid(turned, {});
        const std::shared_ptr<const AccelStructure> t = packed->turnedUp(axis);
        ASSERT_TRUE(gridOf(t));
        const UniformGrid& grid = *gridOf(t);
        EXPECT_EQ(grid.resolution, built.resolution);
        EXPECT_EQ(grid.min, built.min);
        EXPECT_EQ(grid.max, built.max);
        EXPECT_EQ(grid.cellSize, built.cellSize);
        EXPECT_EQ(grid.cellStart, built.cellStart);
        EXPECT_EQ(grid.cellTriangles, built.cellTriangles);
        EXPECT_EQ(grid.skip, built.skip);
    }
}

}  // namespace
}  // namespace gpurt
