// Traverser (Purcell et al. 2002, 4.2; Christen 2005, 5.4.3): 3D-DDA through the uniform grid for
// ACTIVE rays. A non-empty cell puts the ray in WAIT for the intersector; leaving the grid or
// passing the ray's limit makes it DEAD (a miss). The seed takes one cell per pass; this kernel
// takes up to TRAVERSE_STEPS cells per pass (a define), trading passes for divergence.
#include "grid.glsl"

#ifndef TRAVERSE_STEPS
#define TRAVERSE_STEPS 1
#endif

uniform sampler2D rayOrigin;
uniform sampler2D rayDir;
uniform sampler2D ddaState;  // in place: (tMax, state)
uniform isampler2D voxel;    // in place: (cell, cells visited)

layout(location = 0) out vec4 ddaOut;
layout(location = 1) out ivec4 voxelOut;

void main() {
    vec4 dda = readStream(ddaState);
    if (int(dda.w) != RAY_ACTIVE) discard;  // masking usually removed these already
    vec4 origin = readStream(rayOrigin);
    vec3 o = origin.xyz;
    float tLimit = origin.w;
    vec3 d = readStream(rayDir).xyz;
    ivec4 v = readStream(voxel);
    ivec3 cell = v.xyz;
    int steps = v.w;
    vec3 tMax = dda.xyz;
    int state = RAY_ACTIVE;
    for (int i = 0; i < TRAVERSE_STEPS; ++i) {
        if (steps >= maxCellSteps) {
            state = RAY_OVERFLOW;
            break;
        }
        steps += 1;  // this cell is visited
        uvec2 range = cellRange(cell);
        if (range.y != 0u) {
            state = RAY_WAIT;
            break;
        }
        // An empty cell: range.x is its skip distance.
        if (ddaCellExit(tMax) > tLimit || !ddaAdvance(o, d, gridMin, cellSize, gridRes, int(range.x), cell, tMax)) {
            state = RAY_DEAD;
            break;
        }
    }
    ddaOut = vec4(tMax, float(state));
    voxelOut = ivec4(cell, steps);
}
