// Uniform grid construction: each triangle is entered into every cell it overlaps, found by
// walking the cells of its bounding box and keeping those that pass the triangle/box separating
// axis test (Akenine-Moller 2001, "Fast 3D Triangle-Box Overlap Testing"). Unlike the paper we
// test in double precision against cells enlarged by a small fraction of the cell size, so a
// triangle on or near a cell boundary is entered into both cells: an extra reference costs one
// intersection test, a missing one is a hole in the image.
#include "raytrace/accel/grid/UniformGrid.h"
#include "raytrace/accel/SceneBox.h"

#include <algorithm>
#include <atomic>
#include <tuple>
#include <cmath>
#include <exception>
#include <string>
#include <thread>
#include <utility>

#include "base/Parallel.h"
#include "image/InputError.h"

namespace gpurt {
namespace {

// Each cell is enlarged by this fraction of its size on every side before the overlap test.
constexpr double kCellEnlarge = 1e-3;

// Separating axis test of a triangle against an axis-aligned box (centre, half size): the 9
// edge x box-axis cross products, the box's 3 face normals, then the triangle's plane.
bool triangleOverlapsBox(const glm::dvec3& center, const glm::dvec3& half,
                         const glm::dvec3 (&tri)[3]) {
    const glm::dvec3 v[3] = {tri[0] - center, tri[1] - center, tri[2] - center};
    const glm::dvec3 edges[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
    const glm::dvec3 boxAxes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (const glm::dvec3& e : edges) {
        for (const glm::dvec3& u : boxAxes) {
            const glm::dvec3 axis = glm::cross(e, u);
            const double p0 = glm::dot(axis, v[0]), p1 = glm::dot(axis, v[1]),
                         p2 = glm::dot(axis, v[2]);
            const double r =
                half.x * std::abs(axis.x) + half.y * std::abs(axis.y) + half.z * std::abs(axis.z);
            if (std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r) return false;
        }
    }
    for (int a = 0; a < 3; ++a) {
        if (std::min({v[0][a], v[1][a], v[2][a]}) > half[a] ||
            std::max({v[0][a], v[1][a], v[2][a]}) < -half[a])
            return false;
    }
    // Plane through the triangle vs the box centred at the origin. A degenerate triangle has a
    // zero normal and passes, which is harmless (its bounding box already matched).
    const glm::dvec3 normal = glm::cross(edges[0], edges[1]);
    const double r =
        half.x * std::abs(normal.x) + half.y * std::abs(normal.y) + half.z * std::abs(normal.z);
    return std::abs(glm::dot(normal, v[0])) <= r;
}

glm::ivec3 automaticResolution(size_t triangleCount, glm::vec3 extent, float lambda) {
    if (triangleCount == 0) return glm::ivec3(1);
    const double longest = std::max({extent.x, extent.y, extent.z});
    const double alongLongest =
        std::min(double(lambda) * std::cbrt(double(triangleCount)), double(1 << 20));
    glm::ivec3 res;
    for (int a = 0; a < 3; ++a)
        res[a] =
            std::max(1, static_cast<int>(std::lround(alongLongest * double(extent[a]) / longest)));
    auto total = [&] { return size_t(res.x) * size_t(res.y) * size_t(res.z); };
    if (total() > kMaxGridCells) {
        const double scale = std::cbrt(double(kMaxGridCells) / double(total()));
        for (int a = 0; a < 3; ++a)
            res[a] = std::max(1, static_cast<int>(std::floor(res[a] * scale)));
        while (total() > kMaxGridCells) {
            int a = (res.x >= res.y && res.x >= res.z) ? 0 : (res.y >= res.z ? 1 : 2);
            res[a] -= 1;
        }
    }
    return res;
}

// The (cell, triangle) pairs of triangles [first, last), in ascending triangle order.
void collectReferences(const Scene& scene, const UniformGrid& grid, size_t first, size_t last,
                       std::vector<std::pair<uint32_t, uint32_t>>& out) {
    const glm::dvec3 gridMin(grid.min), cellSize(grid.cellSize);
    const glm::dvec3 half = cellSize * (0.5 + kCellEnlarge);
    for (size_t id = first; id < last; ++id) {
        const Triangle& t = scene.triangles[id];
        const glm::dvec3 tri[3] = {glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2)};
        const glm::dvec3 lo = (glm::min(tri[0], glm::min(tri[1], tri[2])) - gridMin) / cellSize;
        const glm::dvec3 hi = (glm::max(tri[0], glm::max(tri[1], tri[2])) - gridMin) / cellSize;
        glm::ivec3 c0, c1;
        for (int a = 0; a < 3; ++a) {
            c0[a] = static_cast<int>(
                std::clamp(std::floor(lo[a] - kCellEnlarge), 0.0, double(grid.resolution[a] - 1)));
            c1[a] = static_cast<int>(
                std::clamp(std::floor(hi[a] + kCellEnlarge), 0.0, double(grid.resolution[a] - 1)));
        }
        const bool singleCell = c0 == c1;
        for (int z = c0.z; z <= c1.z; ++z)
            for (int y = c0.y; y <= c1.y; ++y)
                for (int x = c0.x; x <= c1.x; ++x) {
                    const glm::dvec3 center = gridMin + (glm::dvec3(x, y, z) + 0.5) * cellSize;
                    if (singleCell || triangleOverlapsBox(center, half, tri))
                        out.emplace_back(static_cast<uint32_t>(grid.cellIndex({x, y, z})),
                                         static_cast<uint32_t>(id));
                }
    }
}

// (cell, triangle) pairs, one list per thread.
using References = std::vector<std::vector<std::pair<uint32_t, uint32_t>>>;

// The resolution the options give (checked), or the automatic one for the box's extent.
glm::ivec3 chooseResolution(const Scene& scene, const GridOptions& options, glm::vec3 extent) {
    if (options.resolution) {
        const glm::ivec3 r = *options.resolution;
        if (r.x < 1 || r.y < 1 || r.z < 1)
            throw InputError("--grid: every resolution must be at least 1, got " +
                             std::to_string(r.x) + "," + std::to_string(r.y) + "," +
                             std::to_string(r.z));
        if (size_t(r.x) * size_t(r.y) * size_t(r.z) > kMaxGridCells)
            throw InputError("--grid: " + std::to_string(r.x) + "," + std::to_string(r.y) + "," +
                             std::to_string(r.z) + " has more than " +
                             std::to_string(kMaxGridCells) + " cells");
        return r;
    }
    if (!(options.lambda > 0.0f) || !std::isfinite(options.lambda))
        throw InputError("grid: lambda must be a positive number, got " +
                         std::to_string(options.lambda));
    return automaticResolution(scene.triangles.size(), extent, options.lambda);
}

// The (cell, triangle) pairs of all triangles, collected on `threadOption` threads (0: all
// cores), each thread a contiguous ascending range of triangles; concatenating the threads' lists
// in order keeps every cell's ids ascending.
References collectAllReferences(const Scene& scene, const UniformGrid& grid, int threadOption) {
    const size_t n = scene.triangles.size();
    size_t threads =
        threadOption > 0 ? size_t(threadOption) : size_t(std::thread::hardware_concurrency());
    threads = std::clamp<size_t>(threads, 1, std::max<size_t>(1, n / 256));
    References references(threads);
    std::vector<std::exception_ptr> errors(threads);
    {
        std::vector<std::thread> workers;
        for (size_t t = 0; t < threads; ++t) {
            workers.emplace_back([&, t] {
                try {
                    collectReferences(scene, grid, n * t / threads, n * (t + 1) / threads,
                                      references[t]);
                } catch (...) {
                    errors[t] = std::current_exception();
                }
            });
        }
        for (std::thread& w : workers) w.join();
    }
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);
    return references;
}

// cellStart and cellTriangles from the pairs: a counting sort by cell, on `threadOption` threads.
// The counts are added up by all threads at once (atomic increments); the fill gives each thread a
// range of cells with about as many references as the others, and each thread goes through all
// the lists in order, writing the pairs of its cells: each cell's ids stay in the lists' order
// (ascending), as in a serial pass.
void sortByCell(const References& references, UniformGrid& grid, int threadOption) {
    size_t total = 0;
    for (const auto& list : references) total += list.size();
    if (total >= UINT32_MAX)
        throw InputError("scene: the grid would need more than 2^32 triangle references");
    const size_t cells = grid.cells();
    grid.cellStart.assign(cells + 1, 0);
    uint32_t* start = grid.cellStart.data();
    parallelChunks(references.size(), 1, threadOption, [&](size_t l, size_t, size_t) {
        for (const auto& [cell, id] : references[l]) std::atomic_ref<uint32_t>(start[cell + 1]).fetch_add(1, std::memory_order_relaxed);
    });
    for (size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
    grid.cellTriangles.resize(total);
    const size_t threads = std::clamp<size_t>(size_t(resolveThreads(threadOption)), 1, std::max<size_t>(1, total / 4096));
    std::vector<size_t> firstCell(threads + 1, cells);
    for (size_t t = 0; t < threads; ++t)  // the first cell whose references start at or after t/threads of them
        firstCell[t] = size_t(std::lower_bound(start, start + cells, uint32_t(total * t / threads)) - start);
    firstCell[0] = 0;
    std::vector<uint32_t> cursor(grid.cellStart.begin(), grid.cellStart.end() - 1);
    parallelChunks(threads, 1, int(threads), [&](size_t t, size_t, size_t) {
        const uint32_t lo = uint32_t(firstCell[t]), hi = uint32_t(firstCell[t + 1]);
        for (const auto& list : references)
            for (const auto& [cell, id] : list)
                if (cell >= lo && cell < hi) grid.cellTriangles[cursor[cell]++] = id;
    });
}

}  // namespace

size_t UniformGrid::cells() const {
    return size_t(resolution.x) * size_t(resolution.y) * size_t(resolution.z);
}

float UniformGrid::rayOffset() const { return sceneRayOffset(min, max); }

float UniformGrid::hitTolerance() const {
    return 1e-4f * std::min(cellSize.x, std::min(cellSize.y, cellSize.z));
}

UniformGrid buildGrid(const Scene& scene, const GridOptions& options) {
    if (scene.triangles.size() >= UINT32_MAX)
        throw InputError("scene: too many triangles for 32-bit ids");
    UniformGrid grid;
    std::tie(grid.min, grid.max) = sceneBox(scene);
    grid.resolution = chooseResolution(scene, options, grid.max - grid.min);
    grid.cellSize = (grid.max - grid.min) / glm::vec3(grid.resolution);
    sortByCell(collectAllReferences(scene, grid, options.threads), grid, options.threads);
    if (options.skip) computeSkip(grid);
    return grid;
}

glm::ivec3 gridResolution(const Scene& scene, const GridOptions& options) {
    const auto [lo, hi] = sceneBox(scene);
    return chooseResolution(scene, options, hi - lo);
}

void computeSkip(UniformGrid& grid) {
    const glm::ivec3 r = grid.resolution;
    std::vector<uint8_t>& skip = grid.skip;
    skip.assign(grid.cells(), 255);
    for (size_t c = 0; c < grid.cells(); ++c)
        if (grid.cellStart[c + 1] != grid.cellStart[c]) skip[c] = 0;
    // The 13 neighbours before a cell in raster order (after it, negated).
    std::vector<glm::ivec3> before;
    for (int dz = -1; dz <= 0; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                if (!(dz == 0 && (dy > 0 || (dy == 0 && dx >= 0)))) before.push_back({dx, dy, dz});
    const ptrdiff_t row = r.x, slab = ptrdiff_t(r.x) * r.y;
    // Forward pass: the 13 neighbours before a cell in raster order; backward: the 13 after. A
    // cell away from the grid's faces reads its neighbours at fixed offsets, unchecked; the result
    // is the checked loop's, in the same order.
    auto pass = [&](int sign) {
        ptrdiff_t offsets[13];
        for (size_t k = 0; k < before.size(); ++k)
            offsets[k] = sign * (before[k].x + before[k].y * row + before[k].z * slab);
        const int z0 = sign > 0 ? 0 : r.z - 1, y0 = sign > 0 ? 0 : r.y - 1, x0 = sign > 0 ? 0 : r.x - 1;
        for (int z = z0; z >= 0 && z < r.z; z += sign)
            for (int y = y0; y >= 0 && y < r.y; y += sign) {
                const bool innerRow = z > 0 && z < r.z - 1 && y > 0 && y < r.y - 1;
                for (int x = x0; x >= 0 && x < r.x; x += sign) {
                    const size_t index = size_t(grid.cellIndex({x, y, z}));
                    uint8_t& d = skip[index];
                    if (d == 0) continue;
                    int best = d;
                    if (innerRow && x > 0 && x < r.x - 1) {
                        const uint8_t* at = skip.data() + index;
                        for (const ptrdiff_t o : offsets) best = std::min(best, at[o] + 1);
                    } else {
                        for (const glm::ivec3& n : before) {
                            const glm::ivec3 v(x + sign * n.x, y + sign * n.y, z + sign * n.z);
                            if (v.x < 0 || v.y < 0 || v.z < 0 || v.x >= r.x || v.y >= r.y || v.z >= r.z)
                                continue;
                            best = std::min(best, skip[size_t(grid.cellIndex(v))] + 1);
                        }
                    }
                    d = uint8_t(std::min(best, 255));
                }
            }
    };
    pass(1);
    pass(-1);
}

}  // namespace gpurt
