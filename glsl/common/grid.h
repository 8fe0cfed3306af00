// The uniform grid's traversal (accel/grid/UniformGrid.h; Christen 2005, chapter 5), shared word
// for word by the kernels (glsl/accel/grid/grid_trace.glsl: the fused trace.frag and the
// megakernels) and the cpu backend (accel/grid/GridCpu.cpp), after raymath.h. The split
// traverse.frag / intersect.frag pair runs the same steps as two kernels.
// The includer defines how the grid is read:
//   GPURT_GRID_PARAMS      leading parameters of the functions (empty in GLSL: the samplers are
//                          uniforms), GPURT_GRID_ARGS the matching arguments
//   GPURT_GRID_MIN, GPURT_GRID_CELL (vec3), GPURT_GRID_RES (ivec3), GPURT_GRID_TOLERANCE (float):
//                          the box's corner, a cell's size, the cells on each axis, and how far
//                          beyond a cell's exit a hit still counts in it
//   GPURT_GRID_BOX_MAX     the box's far corner
//   GPURT_GRID_RANGE(cell) (first list entry, count) of the cell (ivec3) as uvec2, count 0 when
//                          it is empty
//   GPURT_GRID_SKIP(cell, range)  an empty cell's skip distance (the cells nearer than it along
//                          every axis are empty; at least 1)
//   GPURT_GRID_TRI(k, v0, v1, v2, flags)  entry k of the cells' lists: its triangle's vertices and
//                          coverage flags (GPURT_COVER_*, 0 when it counts everywhere); the id
//   GPURT_GRID_COVERED(id, flags, u, v, d, e1, e2, anyHit)  whether a candidate hit counts (common/alpha.h)
// A ray that misses the box is RAY_INACTIVE; otherwise the voxel precalculation (ddaSetup) makes
// it active, and at each cell it visits the cell's triangles are tested with the Purcell/Christen
// rule (a hit counts in the cell it lies in, up to the cell's exit plus the tolerance, because a
// triangle spanning several cells may be hit farther along, behind triangles of later cells);
// anyHit (shadow rays) takes the first hit before the ray's limit, wherever it lies.
#ifndef GPURT_GRID_H
#define GPURT_GRID_H

// The triangles of the cell of list range `range` (exit parameter tExit) against the ray o + t d
// (ray: its watertightRay): the closest hit in the cell nearer than bestT replaces (bestT, bestId,
// bestU, bestV); with anyHit the first hit nearer than bestT. tests counts the triangle tests.
// Entries are in ascending id order and the test is strict, so the lowest id wins a tie.
GPURT_INLINE_FN void gridCellHits(GPURT_GRID_PARAMS uvec2 range, WatertightRay ray, vec3 d, float tExit, bool anyHit,
                                  GPURT_INOUT(float) bestT, GPURT_INOUT(int) bestId, GPURT_INOUT(float) bestU,
                                  GPURT_INOUT(float) bestV, GPURT_INOUT(int) tests) {
    for (uint k = range.x; k < range.x + range.y; ++k) {
        vec3 v0;
        vec3 v1;
        vec3 v2;
        float flags;
        int id = GPURT_GRID_TRI(k, v0, v1, v2, flags);
        float t;
        float u;
        float w;
        tests += 1;
        if (intersectTriangle(ray, v0, v1, v2, t, u, w) && t > 0.0f && t < bestT &&
            (anyHit || t <= tExit + GPURT_GRID_TOLERANCE) && GPURT_GRID_COVERED(id, flags, u, w, d, v1 - v0, v2 - v0, anyHit)) {
            bestT = t;
            bestId = id;
            bestU = u;
            bestV = w;
            if (anyHit) break;
        }
    }
}

// One cell of the traversal of o + t d (limit tLimit): its triangles, then the step to the next
// cell (cell and tMax, the DDA's state). False when the ray is done: it hit (bestId >= 0), the
// next cell starts beyond its limit, or it left the grid.
GPURT_INLINE_FN bool gridVisit(GPURT_GRID_PARAMS vec3 o, vec3 d, WatertightRay ray, float tLimit, bool anyHit,
                               GPURT_INOUT(ivec3) cell, GPURT_INOUT(vec3) tMax, GPURT_INOUT(float) bestT,
                               GPURT_INOUT(int) bestId, GPURT_INOUT(float) bestU, GPURT_INOUT(float) bestV,
                               GPURT_INOUT(int) tests) {
    float tExit = ddaCellExit(tMax);
    uvec2 range = GPURT_GRID_RANGE(cell);
    gridCellHits(GPURT_GRID_ARGS range, ray, d, tExit, anyHit, bestT, bestId, bestU, bestV, tests);
    int skip = range.y == 0u ? GPURT_GRID_SKIP(cell, range) : 1;
    return bestId < 0 && !(tExit > tLimit) &&
           ddaAdvance(o, d, GPURT_GRID_MIN, GPURT_GRID_CELL, GPURT_GRID_RES, skip, cell, tMax);
}

// The closest hit of o + t d with 0 < t < tLimit (any hit with anyHit), from the start: the
// triangle id or -1, with t (tLimit when none), u, v; steps counts the cells visited (at most
// maxSteps), tests the triangle tests, state is RAY_INACTIVE (the ray misses the box), RAY_DEAD,
// or RAY_OVERFLOW (maxSteps cells visited: a bug or a damaged grid, reported, never a hang).
GPURT_INLINE_FN int gridTrace(GPURT_GRID_PARAMS vec3 o, vec3 d, float tLimit, bool anyHit, int maxSteps,
                              GPURT_OUT(float) bestT, GPURT_OUT(float) bestU, GPURT_OUT(float) bestV,
                              GPURT_OUT(int) steps, GPURT_OUT(int) tests, GPURT_OUT(int) state) {
    bestT = tLimit;
    bestU = 0.0f;
    bestV = 0.0f;
    steps = 0;
    tests = 0;
    state = RAY_INACTIVE;
    float tEnter = boxEntry(o, d, tLimit, GPURT_GRID_MIN, GPURT_GRID_BOX_MAX);
    if (tEnter < 0.0f) return -1;
    ivec3 cell;
    vec3 tMax;
    ddaSetup(o, d, tEnter, GPURT_GRID_MIN, GPURT_GRID_CELL, GPURT_GRID_RES, cell, tMax);
    WatertightRay ray = watertightRay(o, d);
    int bestId = -1;
    state = RAY_DEAD;
    while (true) {
        if (steps >= maxSteps) {
            state = RAY_OVERFLOW;
            break;
        }
        steps += 1;  // this cell is visited
        if (!gridVisit(GPURT_GRID_ARGS o, d, ray, tLimit, anyHit, cell, tMax, bestT, bestId, bestU, bestV, tests))
            break;
    }
    return bestId;
}

#endif
