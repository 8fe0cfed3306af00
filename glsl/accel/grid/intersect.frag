// Intersector (Purcell et al. 2002, 4.3; Christen 2005, 5.4.4): the watertight triangle test
// (common/raymath.h intersectTriangle) against every triangle of the WAIT ray's cell
// (common/grid.h gridCellHits). A hit counts only inside the current cell (up to its exit
// parameter plus a small tolerance): a triangle that spans several cells must not end the ray
// before a nearer triangle in a later cell is tested. The closest hit wins; ties keep the lower
// triangle id (lists are ascending). No hit: one DDA step and back to ACTIVE.
#include "grid.glsl"
// Some material has alpha or culls its back faces: candidate hits are tested (scene/alpha.glsl).
#if defined(SCENE_ALPHA) || defined(SCENE_CULL_BACK) || defined(SCENE_SHADOWLESS)
#include "scene/alpha.glsl"
uniform int shadowRays;  // 1 while the rays are shadow rays (GridGl::traceLoop's any-hit traces)
#define GRID_COVERED(id, flags, u, v, d, e1, e2, anyHit) \
    hitCovered(id, flags, u, v, elementCoverageKey(), d, e1, e2, shadowRays != 0)
#else
#define GRID_COVERED(id, flags, u, v, d, e1, e2, anyHit) true
#endif
#include "common/grid.h"

uniform sampler2D rayOrigin;
uniform sampler2D rayDir;
uniform sampler2D ddaState;  // in place
uniform isampler2D voxel;    // in place
uniform sampler2D hitState;  // in place: (t, u, v, triangle | -1)

layout(location = 0) out vec4 ddaOut;
layout(location = 1) out ivec4 voxelOut;
layout(location = 2) out vec4 hitOut;

void main() {
    vec4 dda = readStream(ddaState);
    if (int(dda.w) != RAY_WAIT) discard;
    vec4 origin = readStream(rayOrigin);
    vec3 o = origin.xyz;
    float tLimit = origin.w;
    vec3 d = readStream(rayDir).xyz;
    ivec4 v = readStream(voxel);
    ivec3 cell = v.xyz;
    vec3 tMax = dda.xyz;
    float tExit = ddaCellExit(tMax);

    uvec2 range = cellRange(cell);
    float bestT = tLimit;
    int bestId = -1;
    float bestU = 0.0f, bestV = 0.0f;
    int tests = 0;  // unused here (the cpu's cost estimate)
    gridCellHits(range, watertightRay(o, d), d, tExit, false, bestT, bestId, bestU, bestV, tests);

    int state = RAY_ACTIVE;
    if (bestId >= 0) {
        state = RAY_DEAD;
        hitOut = vec4(bestT, bestU, bestV, float(bestId));
    } else {
        hitOut = readStream(hitState);
        if (tExit > tLimit || !ddaStep(o, d, gridMin, cellSize, gridRes, cell, tMax)) state = RAY_DEAD;
    }
    ddaOut = vec4(tMax, float(state));
    voxelOut = ivec4(cell, v.w);
}
