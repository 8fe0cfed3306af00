// The grid's traversal of one ray (common/grid.h, the cpu backend's GridCpu word for word), for its
// own trace kernel (trace.frag) and for the integrators' megakernels, which trace inside their own
// passes (accel/trace.glsl).
#include "grid.glsl"
// Outside the #ifdefs: a file is included once, so the first #include of it must not be skipped.
#include "common/sampling.h"
// Some material has alpha or culls its back faces: candidate hits are tested (scene/alpha.glsl)
// with the coverage key of the ray being traced, which the caller sets.
uint rayCoverageKey = 0u;
#if defined(SCENE_ALPHA) || defined(SCENE_CULL_BACK) || defined(SCENE_SHADOWLESS)
#include "scene/alpha.glsl"
#define GRID_COVERED(id, flags, u, v, d, e1, e2, anyHit) hitCovered(id, flags, u, v, rayCoverageKey, d, e1, e2, anyHit)
#else
#define GRID_COVERED(id, flags, u, v, d, e1, e2, anyHit) true
#endif

#include "common/grid.h"

// The cells a ray may visit (accel/trace.glsl).
int accelStepLimit() { return maxCellSteps; }

// The accelerator's trace for accel/trace.glsl.
int accelTrace(vec3 o, vec3 d, float tLimit, bool anyHit, out float t, out float u, out float v, out int steps,
               out int state) {
    int tests;  // unused here (the cpu's cost estimate)
    return gridTrace(o, d, tLimit, anyHit, maxCellSteps, t, u, v, steps, tests, state);
}
