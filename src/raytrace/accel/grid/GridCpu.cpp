// The grid on the CPU. traceRay() is the per-ray algorithm the GL kernels run as a chain of passes
// (Christen 2005, chapter 5): a ray that misses the grid's box is INACTIVE; otherwise the voxel
// precalculation (ddaSetup) makes it ACTIVE, and it alternates between traversal (ddaStep to the
// next cell) and intersection (WAIT: all triangles of a non-empty cell) until it is DEAD. A hit
// is accepted in a cell only if it lies before the cell's exit (plus a small tolerance), because
// a triangle spanning several cells may be hit farther along, behind triangles of later cells.
#include "raytrace/accel/grid/GridCpu.h"

#include <limits>

#include "raytrace/RayMath.h"

namespace gpurt {

using namespace raymath;

GridCpu::GridCpu(const Scene& scene, const UniformGrid& grid)
    : grid_(grid), hitTolerance_(grid.hitTolerance()), maxSteps_(grid.maxCellSteps()),
      coverage_(AlphaCoverage::of(scene)) {
    triangles_.reserve(scene.triangles.size());
    for (const Triangle& t : scene.triangles) triangles_.push_back({t.v0, t.v1, t.v2});
}

// glsl/accel/grid/trace.frag is this function as one kernel.
template <bool AnyHit>
TraceHit GridCpu::traceRay(glm::vec3 o, glm::vec3 d, float tLimit, uint32_t coverageKey) const {
    TraceHit hit{std::numeric_limits<float>::infinity(), -1, 0.0f, 0.0f, 0, 0, RAY_INACTIVE};

    // Ray generation: clip against the grid's box.
    const float tEnter = boxEntry(o, d, tLimit, grid_.min, grid_.max);
    if (tEnter < 0.0f) return hit;

    // Voxel precalculation.
    glm::ivec3 voxel;
    glm::vec3 tMax;
    ddaSetup(o, d, tEnter, grid_.min, grid_.cellSize, grid_.resolution, voxel, tMax);
    const WatertightRay ray = watertightRay(o, d);  // the triangle test's per-ray part
    hit.state = RAY_ACTIVE;

    while (true) {
        if (hit.steps >= maxSteps_) {
            hit.state = RAY_OVERFLOW;
            return hit;
        }
        hit.steps += 1;
        const float cellExit = ddaCellExit(tMax);
        const int cell = grid_.cellIndex(voxel);
        const uint32_t begin = grid_.cellStart[cell], end = grid_.cellStart[cell + 1];
        if (begin != end) {
            // Intersection (state WAIT): the closest accepted hit among the cell's triangles;
            // strict < keeps the lowest id on ties, as ids are ascending.
            hit.state = RAY_WAIT;
            for (uint32_t k = begin; k < end; ++k) {
                const uint32_t id = grid_.cellTriangles[k];
                hit.tests += 1;
                const PreparedTriangle& tri = triangles_[id];
                float t, u, v;
                if (!intersectTriangle(ray, tri.v0, tri.v1, tri.v2, t, u, v)) continue;
                if (t > 0.0f && t < tLimit && (AnyHit || t <= cellExit + hitTolerance_) && t < hit.t &&
                    hitCovered(coverage_.get(), int(id), u, v, coverageKey, d, tri.v1 - tri.v0, tri.v2 - tri.v0)) {
                    hit.t = t;
                    hit.prim = static_cast<int>(id);
                    hit.u = u;
                    hit.v = v;
                    if (AnyHit) break;
                }
            }
            if (hit.prim >= 0) {
                hit.state = RAY_DEAD;
                return hit;
            }
            hit.state = RAY_ACTIVE;
        }
        // Traversal: stop when the next cell starts beyond the ray's limit or outside the grid.
        const int skip = begin == end ? grid_.skipDistance(size_t(cell)) : 1;
        if (cellExit > tLimit ||
            !ddaAdvance(o, d, grid_.min, grid_.cellSize, grid_.resolution, skip, voxel, tMax)) {
            hit.state = RAY_DEAD;
            return hit;
        }
    }
}

template TraceHit GridCpu::traceRay<false>(glm::vec3, glm::vec3, float, uint32_t) const;
template TraceHit GridCpu::traceRay<true>(glm::vec3, glm::vec3, float, uint32_t) const;

}  // namespace gpurt
