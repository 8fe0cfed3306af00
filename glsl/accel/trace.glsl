// The scene's accelerator inside another kernel (the integrators' megakernels): its textures and
// uniforms (GlAccelerator::bindTrace adds them with the define that names it) and
//   int accelTrace(vec3 o, vec3 d, float tLimit, bool anyHit, out float t, out float u,
//                  out float v, out int steps, out int state)
// the closest hit (any hit with anyHit) of o + t d with 0 < t < tLimit: the triangle id or -1, and
//   int accelStepLimit()
// the cells or nodes a ray may visit (steps reaching it: the ray overflowed, or ended there).
// Alpha coverage and culling test each candidate with the key in rayCoverageKey.
// Files are included once, whatever #if they sit in: the files both accelerators include come first.
#include "scene/pixel.glsl"
#include "common/sampling.h"
#include "scene/alpha.glsl"
#if defined(ACCEL_BVH)
#include "bvh/bvh_trace.glsl"
#elif defined(ACCEL_GRID)
#include "grid/grid_trace.glsl"
#else
#error "accel/trace.glsl: no accelerator defined (GlAccelerator::bindTrace)"
#endif
