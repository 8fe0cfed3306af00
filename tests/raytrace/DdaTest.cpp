// The 3D-DDA of raymath.h (ddaSetup / ddaStep / ddaCellExit) against a brute force that computes,
// in double, the interval of the ray inside every cell: the DDA must visit every cell the ray
// really passes through, in order, and only cells the ray touches. Covers oblique rays, rays
// parallel to one or two axes, rays starting on a cell boundary, and origins inside the grid.
#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "raytrace/common/RayMath.h"
#include "raytrace/accel/grid/UniformGrid.h"

namespace gpurt {
namespace {

struct TestGrid {
    glm::vec3 min{-1.3f, 0.2f, 2.0f};
    glm::vec3 cellSize{0.37f, 0.51f, 0.29f};
    glm::ivec3 res{7, 5, 6};
    glm::vec3 max() const { return min + cellSize * glm::vec3(res); }
};

struct CellInterval {
    glm::ivec3 cell;
    double tIn, tOut;
};

// The ray's parameter interval inside each cell (closed boxes), clipped to t >= tStart.
std::vector<CellInterval> bruteForceIntervals(const TestGrid& g, glm::vec3 o, glm::vec3 d,
                                              double tStart) {
    std::vector<CellInterval> out;
    for (int z = 0; z < g.res.z; ++z)
        for (int y = 0; y < g.res.y; ++y)
            for (int x = 0; x < g.res.x; ++x) {
                const glm::ivec3 c(x, y, z);
                double tIn = tStart, tOut = 1e30;
                for (int a = 0; a < 3; ++a) {
                    // The cell's faces where the float grid puts them (min + k * size in float),
                    // so that an origin placed on a face is on it here too.
                    const double lo = g.min[a] + float(c[a]) * g.cellSize[a];
                    const double hi = g.min[a] + float(c[a] + 1) * g.cellSize[a];
                    if (d[a] == 0.0f) {
                        if (o[a] < lo || o[a] > hi) tIn = 1e31;
                        continue;
                    }
                    double t0 = (lo - o[a]) / double(d[a]), t1 = (hi - o[a]) / double(d[a]);
                    tIn = std::max(tIn, std::min(t0, t1));
                    tOut = std::min(tOut, std::max(t0, t1));
                }
                if (tIn <= tOut) out.push_back({c, tIn, tOut});
            }
    return out;
}

struct DdaWalk {
    std::vector<glm::ivec3> cells;
    std::vector<float> exits;
    bool entered = false;
};

DdaWalk walk(const TestGrid& g, glm::vec3 o, glm::vec3 d, float& tEnter) {
    DdaWalk w;
    const glm::vec2 box = raymath::intersectBox(o, d, g.min, g.max());
    tEnter = std::max(box.x, 0.0f);
    if (tEnter > box.y) return w;
    w.entered = true;
    glm::ivec3 voxel;
    glm::vec3 tMax;
    raymath::ddaSetup(o, d, tEnter, g.min, g.cellSize, g.res, voxel, tMax);
    for (int guard = 0; guard < 1000; ++guard) {
        w.cells.push_back(voxel);
        w.exits.push_back(raymath::ddaCellExit(tMax));
        if (!raymath::ddaStep(o, d, g.min, g.cellSize, g.res, voxel, tMax)) break;
    }
    return w;
}

// Compares one ray; `label` names it in failures.
void checkRay(const TestGrid& g, glm::vec3 o, glm::vec3 d, const std::string& label) {
    float tEnter = 0.0f;
    const DdaWalk w = walk(g, o, d, tEnter);
    const std::vector<CellInterval> truth =
        bruteForceIntervals(g, o, d, std::max(0.0, double(tEnter)) - 1e-6);
    const double tol =
        1e-4;  // in t; cells are ~0.3 wide and coordinates ~1, so float error is ~1e-6

    auto key = [&](glm::ivec3 c) { return c.x + g.res.x * (c.y + g.res.y * c.z); };
    std::set<int> visited;
    for (glm::ivec3 c : w.cells) visited.insert(key(c));
    ASSERT_EQ(visited.size(), w.cells.size()) << label << ": a cell was visited twice";
    ASSERT_LE(int(w.cells.size()), g.res.x + g.res.y + g.res.z + 3) << label;

    // Every cell the ray crosses for a non-negligible length is visited.
    size_t significant = 0;
    for (const CellInterval& c : truth) {
        if (c.tOut - c.tIn <= tol) continue;
        ++significant;
        EXPECT_TRUE(visited.count(key(c.cell)))
            << label << ": cell " << c.cell.x << "," << c.cell.y << "," << c.cell.z << " [" << c.tIn
            << ", " << c.tOut << "] not visited";
    }
    if (!w.entered) {
        EXPECT_EQ(significant, 0u) << label << ": intersectBox missed a ray that crosses the grid";
        return;
    }
    // Every visited cell is touched by the ray, in order of entry, with its exit where the ray
    // really leaves it, and consecutive cells share a face.
    double lastIn = -1e30;
    for (size_t k = 0; k < w.cells.size(); ++k) {
        const glm::ivec3 c = w.cells[k];
        auto it = std::find_if(truth.begin(), truth.end(),
                               [&](const CellInterval& t) { return t.cell == c; });
        if (it == truth.end()) {
            // Only acceptable for a zero-length touch the double test rounds away: the exit must
            // then equal the previous one.
            ASSERT_GT(k, 0u) << label;
            EXPECT_NEAR(w.exits[k], w.exits[k - 1], tol)
                << label << ": visited a cell the ray does not touch";
            continue;
        }
        EXPECT_GE(it->tIn, lastIn - tol) << label << ": cells out of order at step " << k;
        lastIn = it->tIn;
        EXPECT_NEAR(w.exits[k], it->tOut, tol) << label << ": exit of step " << k;
        if (k > 0) {
            const glm::ivec3 step = glm::abs(c - w.cells[k - 1]);
            EXPECT_EQ(step.x + step.y + step.z, 1)
                << label << ": step " << k << " is not to a face neighbour";
        }
    }
}

glm::vec3 normalized(glm::vec3 d) { return raymath::contractNormalize(d); }

TEST(DdaTest, RandomObliqueRaysFromOutsideAndInside) {
    const TestGrid g;
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const glm::vec3 lo = g.min - 1.0f, hi = g.max() + 1.0f;
    for (int k = 0; k < 3000; ++k) {
        const glm::vec3 o = lo + (hi - lo) * glm::vec3(u(rng), u(rng), u(rng));
        const glm::vec3 through = g.min + (g.max() - g.min) * glm::vec3(u(rng), u(rng), u(rng));
        const glm::vec3 d = normalized(through - o);
        checkRay(g, o, d, "oblique ray " + std::to_string(k));
        checkRay(g, o, normalized(-d), "reversed ray " + std::to_string(k));
    }
}

TEST(DdaTest, RaysParallelToAxes) {
    const TestGrid g;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const glm::vec3 dirs[] = {
        {1, 0, 0},  {-1, 0, 0},      {0, 1, 0},        {0, -1, 0},        {0, 0, 1},
        {0, 0, -1}, {0.6f, 0.8f, 0}, {0, -0.6f, 0.8f}, {-0.8f, 0, -0.6f}, {0.28f, 0.96f, 0}};
    for (int k = 0; k < 400; ++k) {
        for (const glm::vec3& d : dirs) {
            // Origins off the cell boundaries (a ray lying in a boundary plane belongs to either
            // side).
            glm::vec3 o =
                g.min - 0.5f + (g.max() - g.min + 1.0f) * glm::vec3(u(rng), u(rng), u(rng));
            checkRay(g, o, normalized(d), "axis-parallel ray " + std::to_string(k));
        }
    }
}

TEST(DdaTest, RaysStartingOnCellBoundaries) {
    const TestGrid g;
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::uniform_int_distribution<int> layer(0, 4);
    for (int k = 0; k < 2000; ++k) {
        glm::vec3 o = g.min + (g.max() - g.min) * glm::vec3(u(rng), u(rng), u(rng));
        // Put the origin on a boundary plane of one or two axes (corners and edges included).
        const int axis = k % 3;
        o[axis] = g.min[axis] + float(layer(rng)) * g.cellSize[axis];
        if (k % 5 == 0)
            o[(axis + 1) % 3] =
                g.min[(axis + 1) % 3] + float(layer(rng)) * g.cellSize[(axis + 1) % 3];
        glm::vec3 d(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f);
        if (k % 7 == 0) d[(axis + 2) % 3] = 0.0f;  // and parallel to another axis
        checkRay(g, o, normalized(d), "boundary ray " + std::to_string(k));
    }
    // Starting exactly on the grid's box faces, pointing in and out.
    checkRay(g, g.min + glm::vec3(0.0f, 0.3f, 0.2f), normalized({1.0f, 0.2f, 0.1f}),
             "min face, inwards");
    checkRay(g, g.min + glm::vec3(0.0f, 0.3f, 0.2f), normalized({-1.0f, 0.2f, 0.1f}),
             "min face, outwards");
    checkRay(g, g.max() - glm::vec3(0.0f, 0.3f, 0.2f), normalized({-1.0f, -0.2f, -0.1f}),
             "max face, inwards");
}

TEST(DdaTest, RayMissingTheBox) {
    const TestGrid g;
    float tEnter = 0.0f;
    EXPECT_FALSE(walk(g, g.min - 1.0f, normalized({-1, 0.3f, 0.2f}), tEnter).entered);
    EXPECT_FALSE(
        walk(g, g.min - 1.0f, glm::vec3(1, 0, 0), tEnter).entered);  // parallel, beside the box
    EXPECT_FALSE(
        walk(g, g.max() + 1.0f, normalized({1, 1, 1}), tEnter).entered);  // box behind the origin
}

}  // namespace
}  // namespace gpurt

namespace gpurt {
namespace {

// Empty-space skipping (ddaAdvance with the chessboard distances of computeSkip): on grids with a
// few random non-empty cells, a skipping walk must visit exactly the non-empty cells that the
// plain walk (ddaStep) visits, in the same order, in no more steps.
TEST(DdaTest, SkippingVisitsEveryNonEmptyCellOfThePlainWalk) {
    const TestGrid g;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int trial = 0; trial < 20; ++trial) {
        UniformGrid grid;
        grid.resolution = g.res;
        grid.min = g.min;
        grid.max = g.max();
        grid.cellSize = g.cellSize;
        std::vector<uint32_t> counts(grid.cells(), 0);
        for (int k = 0; k < 1 + trial % 6; ++k) counts[size_t(rng() % grid.cells())] = 1;
        grid.cellStart.assign(grid.cells() + 1, 0);
        for (size_t c = 0; c < grid.cells(); ++c) grid.cellStart[c + 1] = grid.cellStart[c] + counts[c];
        computeSkip(grid);
        const glm::vec3 lo = g.min - 1.0f, hi = g.max() + 1.0f;
        for (int k = 0; k < 500; ++k) {
            const glm::vec3 o = lo + (hi - lo) * glm::vec3(u(rng), u(rng), u(rng));
            const glm::vec3 through = g.min + (g.max() - g.min) * glm::vec3(u(rng), u(rng), u(rng));
            const glm::vec3 d = normalized(through - o);
            float tEnter = 0.0f;
            const DdaWalk plain = walk(g, o, d, tEnter);
            if (!plain.entered) continue;
            std::vector<glm::ivec3> plainFull;
            for (glm::ivec3 c : plain.cells)
                if (counts[size_t(grid.cellIndex(c))]) plainFull.push_back(c);
            for (const bool kernelsForm : {false, true}) {  // ddaAdvance as the cpu runs it, as llvmpipe does
                glm::ivec3 voxel;
                glm::vec3 tMax;
                raymath::ddaSetup(o, d, tEnter, g.min, g.cellSize, g.res, voxel, tMax);
                std::vector<glm::ivec3> skipFull;
                size_t steps = 0;
                for (; steps < 1000; ++steps) {
                    const size_t c = size_t(grid.cellIndex(voxel));
                    if (counts[c]) skipFull.push_back(voxel);
                    const int skip = counts[c] ? 1 : grid.skipDistance(c);
                    const bool inside = kernelsForm
                                            ? raymath::ddaLeaveCube(o, d, g.min, g.cellSize, g.res, skip, voxel, tMax)
                                            : raymath::ddaAdvance(o, d, g.min, g.cellSize, g.res, skip, voxel, tMax);
                    if (!inside) break;
                }
                ASSERT_EQ(skipFull, plainFull) << "trial " << trial << " ray " << k << " kernels' form " << kernelsForm;
                EXPECT_LE(steps + 1, plain.cells.size()) << "trial " << trial << " ray " << k;
            }
        }
    }
}

// Leaving a cube of distance 1 is exactly one ddaStep: the kernels' form of a step (ddaLeaveCube for
// every k) and the cpu's (ddaStep for k = 1) visit the same cells with the same tMax.
TEST(DdaTest, AdvanceByOneIsDdaStep) {
    const TestGrid g;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int k = 0; k < 2000; ++k) {
        const glm::vec3 o = g.min + (g.max() - g.min) * glm::vec3(u(rng), u(rng), u(rng));
        const glm::vec3 d = normalized(glm::vec3(u(rng), u(rng), u(rng)) - 0.5f);
        glm::ivec3 a, b;
        glm::vec3 ta, tb;
        raymath::ddaSetup(o, d, 0.0f, g.min, g.cellSize, g.res, a, ta);
        b = a, tb = ta;
        for (int s = 0; s < 30; ++s) {
            const bool okA = raymath::ddaStep(o, d, g.min, g.cellSize, g.res, a, ta);
            const bool okB = raymath::ddaLeaveCube(o, d, g.min, g.cellSize, g.res, 1, b, tb);
            ASSERT_EQ(okA, okB);
            if (!okA) break;
            ASSERT_EQ(a, b);
            ASSERT_EQ(ta, tb);
        }
    }
}

}  // namespace
}  // namespace gpurt
