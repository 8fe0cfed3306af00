// The BVH's scene textures (accel/bvh/BvhGl binds them) and its traversal of one ray
// (common/bvh.h, the cpu backend's BvhCpu word for word), for its own trace kernel (trace.frag)
// and for the integrators' megakernels, which trace inside their own passes (accel/trace.glsl).
#include "scene/pixel.glsl"
// Outside the #ifdefs: a file is included once, so the first #include of it must not be skipped.
#include "common/sampling.h"
// Some material has alpha or culls its back faces: candidate hits are tested (scene/alpha.glsl)
// with the coverage key of the ray being traced, which the caller sets.
uint rayCoverageKey = 0u;
#if defined(SCENE_ALPHA) || defined(SCENE_CULL_BACK) || defined(SCENE_SHADOWLESS)
#include "scene/alpha.glsl"
#define GPURT_BVH_COVERED(id, flags, u, v, d, e1, e2, anyHit) hitCovered(id, flags, u, v, rayCoverageKey, d, e1, e2, anyHit)
#else
#define GPURT_BVH_COVERED(id, flags, u, v, d, e1, e2, anyHit) true
#endif

uniform usamplerBuffer bvhNodes;     // two texels a node, one per child (common/bvh.h)
uniform vec3 bvhBoxMin;              // the nodes' quantisation frame: corner and step
uniform vec3 bvhBoxStep;
uniform samplerBuffer bvhTriangles;  // the leaves' triangles: v0 + id, v1 + coverage flags, v2
uniform int maxNodeSteps;            // more nodes than a ray can visit: RAY_OVERFLOW

#define GPURT_BVH_PARAMS
#define GPURT_BVH_ARGS
#define GPURT_BVH_NODE(i) texelFetch(bvhNodes, i)
#define GPURT_BVH_TRI(i) texelFetch(bvhTriangles, i)
#define GPURT_BVH_BOX_MIN bvhBoxMin
#define GPURT_BVH_BOX_STEP bvhBoxStep
#include "common/bvh.h"

// The nodes a ray may visit (accel/trace.glsl).
int accelStepLimit() { return maxNodeSteps; }

// The accelerator's trace for accel/trace.glsl: the closest hit (any hit with anyHit) of o + t d
// with 0 < t < tLimit, its id or -1, with t, u, v; steps counts the nodes visited.
int accelTrace(vec3 o, vec3 d, float tLimit, bool anyHit, out float t, out float u, out float v, out int steps,
               out int state) {
    int tests;  // unused here (the cpu's cost estimate)
    return bvhTrace(o, d, tLimit, anyHit, maxNodeSteps, t, u, v, steps, tests, state);
}
