// The accelerator seam: what the integrators ask of an acceleration structure, on both backends.
// An accelerator owns its build over the scene's triangles, its scene textures and kernels (gl),
// its per-ray state and its trace loop; the integrators see only rays in and hits out.
//   cpu: closest hit and any hit for one ray (CpuAccelerator).
//   gl:  "trace these ray streams into this hit stream" (GlAccelerator), the streams laid out as
//        glsl/common/scene_layout.h says: rayOrigin (o, tLimit), rayDir (d, GPURT_A_RAY |
//        GPURT_NO_RAY), hit (t, u, v, triangle | -1), one element per ray.
// The uniform grid (accel/grid/) is the one accelerator today; docs/ARCHITECTURE.md says how to
// add another.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>


namespace gpurt {

// The result of one traversal. A miss has prim = -1 and t = +inf.
struct TraceHit {
    float t;
    int prim;
    float u, v;  // barycentrics of the hit (weights of v1 and v2)
    int steps;   // cells (or nodes) visited
    int tests;   // triangle tests made
    int state;   // RAY_DEAD (hit or left the structure), RAY_INACTIVE (missed its box), RAY_OVERFLOW
};

class CpuAccelerator {
  public:
    virtual ~CpuAccelerator() = default;
    // First hit of o + t d with 0 < t < tLimit; d must be normalised. A hit on a surface with
    // alpha counts only where it covers the ray of coverage key `coverageKey` (the ray's sample:
    // glsl/common/alpha.h coverageKey; AlphaCoverage).
    virtual TraceHit closestHit(glm::vec3 o, glm::vec3 d, float tLimit, uint32_t coverageKey) const = 0;
    // Any hit with 0 < t < tLimit (shadow rays): prim is some blocker, not necessarily the
    // nearest. Blocked exactly when closestHit hits.
    virtual TraceHit anyHit(glm::vec3 o, glm::vec3 d, float tLimit, uint32_t coverageKey) const = 0;
};

}  // namespace gpurt
