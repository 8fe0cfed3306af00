// The BVH traversal (common/bvh.h, the cpu backend's BvhCpu word for word) as one kernel: every
// element that carries a ray is traced to its closest hit, or with ANY_HIT (shadow rays) to any
// hit before its limit, in one pass: no ray state between passes. With CAMERA the kernel generates
// the camera's primary rays itself (as the grid's trace.frag does) and reads no ray stream.
#include "scene/pixel.glsl"
// Outside the #ifdefs: a file is included once, so the first #include of it must not be skipped.
#include "common/sampling.h"
// Some material has alpha or culls its back faces: candidate hits are tested (scene/alpha.glsl).
#if defined(SCENE_ALPHA) || defined(SCENE_CULL_BACK)
#include "scene/alpha.glsl"
uint rayCoverageKey = 0u;
#define GPURT_BVH_COVERED(id, flags, u, v, d, e1, e2) hitCovered(id, flags, u, v, rayCoverageKey, d, e1, e2)
#else
#define GPURT_BVH_COVERED(id, flags, u, v, d, e1, e2) true
#endif
#ifdef CAMERA
#include "scene/camera.glsl"
#endif

uniform usamplerBuffer bvhNodes;     // two texels a node, one per child (common/bvh.h)
uniform vec3 bvhBoxMin;              // the nodes' quantisation frame: corner and step
uniform vec3 bvhBoxStep;
uniform samplerBuffer bvhTriangles;  // the leaves' triangles: v0 + id, e1, e2
uniform int maxNodeSteps;            // more nodes than a ray can visit: RAY_OVERFLOW

#define GPURT_BVH_PARAMS
#define GPURT_BVH_NODE(i) texelFetch(bvhNodes, i)
#define GPURT_BVH_TRI(i) texelFetch(bvhTriangles, i)
#define GPURT_BVH_BOX_MIN bvhBoxMin
#define GPURT_BVH_BOX_STEP bvhBoxStep
#include "common/bvh.h"

#ifndef CAMERA
uniform sampler2D rayOrigin;
uniform sampler2D rayDir;
#endif

layout(location = 0) out ivec4 stepsOut;  // w: nodes visited
layout(location = 1) out vec4 hitOut;     // (t, u, v, triangle | -1)

void main() {
#ifdef CAMERA
    vec3 o = eye;
    vec3 d = primaryDirection();
    float tLimit = GPURT_FAR;
#else
    vec4 origin = readStream(rayOrigin);
    vec4 dir = readStream(rayDir);
    if (dir.w == GPURT_NO_RAY) discard;
    vec3 o = origin.xyz;
    vec3 d = dir.xyz;
    float tLimit = origin.w;
#endif
#ifdef ANY_HIT
    bool anyHit = true;
#else
    bool anyHit = false;
#endif
#ifdef SCENE_ALPHA
    rayCoverageKey = elementCoverageKey();
#endif
    float t, u, v;
    int steps, tests, state;  // tests: unused here (the cpu's cost estimate)
    int id = bvhTrace(o, d, tLimit, anyHit, maxNodeSteps, t, u, v, steps, tests, state);
    stepsOut = ivec4(0, 0, 0, steps);
    hitOut = vec4(id >= 0 ? t : GPURT_FAR, u, v, float(id));
}
