// The grid on the CPU: traceRay() runs glsl/common/grid.h, the per-ray algorithm the GL kernels
// run in one pass (trace.frag, the megakernels) or as a chain of passes (Christen 2005, chapter 5:
// precalc, traverse, intersect).
#include "raytrace/accel/grid/GridCpu.h"

#include <limits>

#include "raytrace/common/RayMath.h"

namespace gpurt {

using namespace raymath;

GridCpu::GridCpu(const Scene& scene, const UniformGrid& grid)
    : grid_(grid), hitTolerance_(grid.hitTolerance()), maxSteps_(grid.maxCellSteps()),
      coverage_(AlphaCoverage::of(scene)) {
    triangles_.reserve(scene.triangles.size());
    for (const Triangle& t : scene.triangles) triangles_.push_back({t.v0, t.v1, t.v2});
}

namespace {

// How glsl/common/grid.h reads the grid on the cpu.
struct GridCells {
    const UniformGrid& grid;
    const GridCpu::PreparedTriangle* triangles;
    float tolerance;
    const AlphaCoverage* coverage;
    uint32_t coverageKey;

    // (first entry, count), or for an empty cell (skip distance, 0), as the kernels' voxel index.
    uvec2 range(ivec3 cell) const {
        const size_t c = size_t(grid.cellIndex(cell));
        const uint32_t begin = grid.cellStart[c], end = grid.cellStart[c + 1];
        return begin == end ? uvec2(uint32_t(grid.skipDistance(c)), 0u) : uvec2(begin, end - begin);
    }
    int triangle(uint32_t k, vec3& v0, vec3& v1, vec3& v2, float& flags) const {
        const uint32_t id = grid.cellTriangles[k];
        v0 = triangles[id].v0;
        v1 = triangles[id].v1;
        v2 = triangles[id].v2;
        flags = 1.0f;  // hitCovered asks the coverage of every triangle (none: all count)
        return int(id);
    }
};

#define GPURT_GRID_PARAMS const GridCells &cells,
#define GPURT_GRID_ARGS cells,
#define GPURT_GRID_MIN cells.grid.min
#define GPURT_GRID_BOX_MAX cells.grid.max
#define GPURT_GRID_CELL cells.grid.cellSize
#define GPURT_GRID_RES cells.grid.resolution
#define GPURT_GRID_TOLERANCE cells.tolerance
#define GPURT_GRID_RANGE(cell) cells.range(cell)
#define GPURT_GRID_SKIP(cell, range) int((range).x)
#define GPURT_GRID_TRI(k, v0, v1, v2, flags) cells.triangle(k, v0, v1, v2, flags)
#define GPURT_GRID_COVERED(id, flags, u, v, d, e1, e2, anyHit) \
    hitCovered(cells.coverage, id, u, v, cells.coverageKey, d, e1, e2, anyHit)
#include "../../../../glsl/common/grid.h"

}  // namespace

// The traversal of glsl/common/grid.h, which the kernels run too (glsl/accel/grid/).
template <bool AnyHit>
TraceHit GridCpu::traceRay(glm::vec3 o, glm::vec3 d, float tLimit, uint32_t coverageKey) const {
    const GridCells cells{grid_, triangles_.data(), hitTolerance_, coverage_.get(), coverageKey};
    TraceHit hit{};
    hit.prim = gridTrace(cells, o, d, tLimit, AnyHit, maxSteps_, hit.t, hit.u, hit.v, hit.steps, hit.tests, hit.state);
    if (hit.prim < 0) hit.t = std::numeric_limits<float>::infinity();
    return hit;
}

template TraceHit GridCpu::traceRay<false>(glm::vec3, glm::vec3, float, uint32_t) const;
template TraceHit GridCpu::traceRay<true>(glm::vec3, glm::vec3, float, uint32_t) const;

}  // namespace gpurt
