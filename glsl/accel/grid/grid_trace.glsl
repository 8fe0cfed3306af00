// The grid's traversal of one ray (GridCpu::traceRay word for word) as functions, for its own
// trace kernel (trace.frag) and for the integrators' megakernels, which trace inside their own
// passes (accel/trace.glsl). A cell's triangles are tested with the Purcell/Christen intersector
// rule (a hit counts in the cell it lies in, up to the cell's exit plus a tolerance); anyHit
// (shadow rays) takes the first hit before the ray's limit, wherever it lies.
#include "grid.glsl"
// Outside the #ifdefs: a file is included once, so the first #include of it must not be skipped.
#include "common/sampling.h"
// Some material has alpha or culls its back faces: candidate hits are tested (scene/alpha.glsl)
// with the coverage key of the ray being traced, which the caller sets.
uint rayCoverageKey = 0u;
#if defined(SCENE_ALPHA) || defined(SCENE_CULL_BACK)
#include "scene/alpha.glsl"
#define GRID_COVERED(id, flags, u, v, d, e1, e2) hitCovered(id, flags, u, v, rayCoverageKey, d, e1, e2)
#else
#define GRID_COVERED(id, flags, u, v, d, e1, e2) true
#endif

// The triangles of the cell of list range `range` (exit parameter tExit) against the ray o + t d
// (ray: its watertightRay): the closest hit in the cell nearer than bestT replaces (bestT, bestId,
// bestU, bestV); with anyHit the first hit nearer than bestT.
void gridCellHits(uvec2 range, WatertightRay ray, vec3 d, float tExit, bool anyHit, inout float bestT,
                  inout int bestId, inout float bestU, inout float bestV) {
    for (uint k = range.x; k < range.x + range.y; ++k) {
        vec3 v0, v1, v2;
        float flags;
        int id = fetchListTriangle(k, v0, v1, v2, flags);
        float t, u, w;
        if (intersectTriangle(ray, v0, v1, v2, t, u, w) && t > 0.0f && t < bestT &&
            (anyHit || t <= tExit + cellTolerance) && GRID_COVERED(id, flags, u, w, d, v1 - v0, v2 - v0)) {
            bestT = t;
            bestId = id;
            bestU = u;
            bestV = w;
            if (anyHit) break;
        }
    }
}

// The closest hit of o + t d with 0 < t < tLimit (any hit with anyHit), from the start: the
// triangle id or -1, with t, u, v; steps counts the cells visited, state is RAY_DEAD or
// RAY_OVERFLOW (maxCellSteps cells visited).
int gridTrace(vec3 o, vec3 d, float tLimit, bool anyHit, out float bestT, out float bestU, out float bestV,
              out int steps, out int state) {
    bestT = tLimit;
    bestU = 0.0f;
    bestV = 0.0f;
    steps = 0;
    state = RAY_DEAD;
    float tEnter = gridEntry(o, d, tLimit);
    if (tEnter == GPURT_MISSED_BOX) return -1;
    ivec3 cell;
    vec3 tMax;
    ddaSetup(o, d, tEnter, gridMin, cellSize, gridRes, cell, tMax);
    WatertightRay ray = watertightRay(o, d);
    int bestId = -1;
    while (true) {
        if (steps >= maxCellSteps) {
            state = RAY_OVERFLOW;
            break;
        }
        steps += 1;  // this cell is visited
        float tExit = ddaCellExit(tMax);
        uvec2 range = cellRange(cell);
        gridCellHits(range, ray, d, tExit, anyHit, bestT, bestId, bestU, bestV);
        int skip = range.y == 0u ? int(range.x) : 1;  // an empty cell's skip distance
        if (bestId >= 0 || tExit > tLimit || !ddaAdvance(o, d, gridMin, cellSize, gridRes, skip, cell, tMax)) break;
    }
    return bestId;
}

// The cells a ray may visit (accel/trace.glsl).
int accelStepLimit() { return maxCellSteps; }

// The accelerator's trace for accel/trace.glsl.
int accelTrace(vec3 o, vec3 d, float tLimit, bool anyHit, out float t, out float u, out float v, out int steps,
               out int state) {
    return gridTrace(o, d, tLimit, anyHit, t, u, v, steps, state);
}
