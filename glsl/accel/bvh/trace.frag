// The BVH traversal (bvh_trace.glsl) as one kernel: every element that carries a ray is traced to
// its closest hit, or with ANY_HIT (shadow rays) to any hit before its limit, in one pass: no ray
// state between passes. With CAMERA the kernel generates the camera's primary rays itself (as the
// grid's trace.frag does) and reads no ray stream.
#include "bvh_trace.glsl"
#ifdef CAMERA
#include "scene/camera.glsl"
#endif

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
    int steps, state;
    int id = accelTrace(o, d, tLimit, anyHit, t, u, v, steps, state);
    stepsOut = ivec4(0, 0, 0, steps);
    hitOut = vec4(id >= 0 ? t : GPURT_FAR, u, v, float(id));
}
