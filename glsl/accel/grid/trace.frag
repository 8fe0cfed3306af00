// Fused traverser and intersector: the per-ray loop of the CPU backend (GridCpu::traceRay) as one
// kernel. Each pass takes every ACTIVE ray through up to TRACE_STEPS grid cells, intersecting the
// triangles of each non-empty cell as it reaches it (the Purcell/Christen intersector test, with
// the same cell-exit rule), so a ray needs no WAIT state and no second kernel. The split
// traverse.frag / intersect.frag pair is the other end of the same range; docs/PERFORMANCE.md
// measures both. With FROM_START the kernel also does the voxel precalculation and takes the
// whole traversal in one pass (TRACE_STEPS is then unlimited). With ANY_HIT (shadow rays) the first
// triangle hit before the ray's limit ends the ray: whether it is blocked is all a shadow ray asks.
// With CAMERA (and FROM_START) the kernel generates the camera's primary rays itself, as
// raygen.frag does, and reads no ray stream: the primary trace when only the hits are wanted.
#include "grid.glsl"
// Outside the #ifdefs: a file is included once, so the first #include of it must not be skipped.
#include "common/sampling.h"
// Some material has alpha or culls its back faces: candidate hits are tested (scene/alpha.glsl).
#if defined(SCENE_ALPHA) || defined(SCENE_CULL_BACK)
#include "scene/alpha.glsl"
#define GRID_COVERED(id, flags, u, v, d, e1, e2) hitCovered(id, flags, u, v, elementCoverageKey(), d, e1, e2)
#else
#define GRID_COVERED(id, flags, u, v, d, e1, e2) true
#endif
#ifdef CAMERA
#include "scene/camera.glsl"
#endif

#ifndef TRACE_STEPS
#define TRACE_STEPS 1
#endif

#ifndef CAMERA
uniform sampler2D rayOrigin;
uniform sampler2D rayDir;
#endif
#ifndef FROM_START
uniform sampler2D ddaState;  // in place: (tMax, state)
uniform isampler2D voxel;    // in place: (cell, cells visited)
#endif

#ifdef FROM_START
// No ray state out: after this pass every ray is done (nothing reads ddaState again).
layout(location = 0) out ivec4 voxelOut;
layout(location = 1) out vec4 hitOut;  // (t, u, v, triangle | -1)
#else
layout(location = 0) out vec4 ddaOut;
layout(location = 1) out ivec4 voxelOut;
layout(location = 2) out vec4 hitOut;  // (t, u, v, triangle | -1)
#endif

void main() {
#ifdef CAMERA
    vec3 o = eye;
    vec3 d = primaryDirection();
    float tLimit = GPURT_FAR;
    float tEnter = gridEntry(o, d, tLimit);
#else
    vec4 origin = readStream(rayOrigin);
    vec3 o = origin.xyz;
    float tLimit = origin.w;
    vec4 dir = readStream(rayDir);
    vec3 d = dir.xyz;
#ifdef FROM_START
    if (dir.w == GPURT_NO_RAY) discard;
    float tEnter = gridEntry(o, d, tLimit);
#endif
#endif
#ifdef FROM_START
    // The whole traversal in this pass, so the voxel precalculation (precalc.frag) is done here
    // and needs no pass of its own.
    if (tEnter == GPURT_MISSED_BOX) {
        voxelOut = ivec4(0);
        hitOut = vec4(GPURT_FAR, 0.0f, 0.0f, -1.0f);
        return;
    }
    ivec3 cell;
    vec3 tMax;
    ddaSetup(o, d, tEnter, gridMin, cellSize, gridRes, cell, tMax);
    int steps = 0;
#else
    vec4 dda = readStream(ddaState);
    if (int(dda.w) != RAY_ACTIVE) discard;  // masking usually removed these already
    ivec4 v = readStream(voxel);
    ivec3 cell = v.xyz;
    int steps = v.w;
    vec3 tMax = dda.xyz;
#endif

    int state = RAY_ACTIVE;
    float bestT = tLimit;
    int bestId = -1;
    float bestU = 0.0f, bestV = 0.0f;
    for (int i = 0; i < TRACE_STEPS; ++i) {
        if (steps >= maxCellSteps) {
            state = RAY_OVERFLOW;
            break;
        }
        steps += 1;  // this cell is visited
        float tExit = ddaCellExit(tMax);
        uvec2 range = cellRange(cell);
        for (uint k = range.x; k < range.x + range.y; ++k) {
            vec3 v0, e1, e2;
            float flags;
            int id = fetchListTriangle(k, v0, e1, e2, flags);
            float t, u, w;
            if (intersectTriangle(o, d, v0, e1, e2, t, u, w) && t > 0.0f && t < bestT && GRID_COVERED(id, flags, u, w, d, e1, e2)
#ifndef ANY_HIT
                && t <= tExit + cellTolerance
#endif
            ) {
                bestT = t;
                bestId = id;
                bestU = u;
                bestV = w;
#ifdef ANY_HIT
                break;
#endif
            }
        }
        int skip = range.y == 0u ? int(range.x) : 1;  // an empty cell's skip distance
        if (bestId >= 0 || tExit > tLimit || !ddaAdvance(o, d, gridMin, cellSize, gridRes, skip, cell, tMax)) {
            state = RAY_DEAD;
            break;
        }
    }
#ifndef FROM_START
    ddaOut = vec4(tMax, float(state));
#endif
    voxelOut = ivec4(cell, steps);
    hitOut = vec4(bestId >= 0 ? bestT : GPURT_FAR, bestU, bestV, float(bestId));
}
