// Fused traverser and intersector: the per-ray loop of the CPU backend (common/grid.h, GridCpu) as
// one kernel (grid_trace.glsl). Each pass takes every ACTIVE ray through up to TRACE_STEPS grid cells,
// intersecting the triangles of each non-empty cell as it reaches it (the Purcell/Christen
// intersector test, with the same cell-exit rule), so a ray needs no WAIT state and no second
// kernel. The split traverse.frag / intersect.frag pair is the other end of the same range;
// docs/PERFORMANCE.md measures both. With FROM_START the kernel also does the voxel precalculation
// and takes the whole traversal in one pass (gridTrace). With ANY_HIT (shadow rays) the first
// triangle hit before the ray's limit ends the ray: whether it is blocked is all a shadow ray asks.
// With CAMERA (and FROM_START) the kernel generates the camera's primary rays itself, as
// raygen.frag does, and reads no ray stream: the primary trace when only the hits are wanted.
#include "grid_trace.glsl"
#ifdef CAMERA
#include "scene/camera.glsl"
#endif

#ifndef TRACE_STEPS
#define TRACE_STEPS 1
#endif

#ifdef ANY_HIT
#define TRACE_ANY_HIT true
#else
#define TRACE_ANY_HIT false
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
#else
    vec4 origin = readStream(rayOrigin);
    vec3 o = origin.xyz;
    float tLimit = origin.w;
    vec4 dir = readStream(rayDir);
    vec3 d = dir.xyz;
#endif
#ifdef SCENE_ALPHA
    rayCoverageKey = elementCoverageKey();
#endif
#ifdef FROM_START
#ifndef CAMERA
    if (dir.w == GPURT_NO_RAY) discard;
#endif
    // The whole traversal in this pass, so the voxel precalculation (precalc.frag) is done here
    // and needs no pass of its own.
    float t, u, v;
    int steps, tests, state;
    int id = gridTrace(o, d, tLimit, TRACE_ANY_HIT, maxCellSteps, t, u, v, steps, tests, state);
    voxelOut = ivec4(0, 0, 0, steps);
    hitOut = vec4(id >= 0 ? t : GPURT_FAR, u, v, float(id));
#else
    vec4 dda = readStream(ddaState);
    if (int(dda.w) != RAY_ACTIVE) discard;  // masking usually removed these already
    ivec4 vx = readStream(voxel);
    ivec3 cell = vx.xyz;
    int steps = vx.w;
    vec3 tMax = dda.xyz;

    int state = RAY_ACTIVE;
    float bestT = tLimit;
    int bestId = -1;
    float bestU = 0.0f, bestV = 0.0f;
    int tests = 0;  // unused here (the cpu's cost estimate)
    WatertightRay ray = watertightRay(o, d);
    for (int i = 0; i < TRACE_STEPS; ++i) {
        if (steps >= maxCellSteps) {
            state = RAY_OVERFLOW;
            break;
        }
        steps += 1;  // this cell is visited
        if (!gridVisit(o, d, ray, tLimit, TRACE_ANY_HIT, cell, tMax, bestT, bestId, bestU, bestV, tests)) {
            state = RAY_DEAD;
            break;
        }
    }
    ddaOut = vec4(tMax, float(state));
    voxelOut = ivec4(cell, steps);
    hitOut = vec4(bestId >= 0 ? bestT : GPURT_FAR, bestU, bestV, float(bestId));
#endif
}
