// Voxel precalculation (Christen 2005, 5.4.2; Amanatides & Woo 1987): the cell where the ray
// enters the grid and the ray parameter of the next cell boundary on each axis. In contrast to
// Amanatides & Woo there is no tDelta stream: the traverser recomputes each boundary from the cell
// index (common/raymath.h), which costs a few multiplies instead of a texture fetch and does not
// drift. Elements without a ray this trace are discarded: their streams keep the terminal state
// of an earlier trace, and the occlusion count of this pass is the number of rays.
#include "grid.glsl"

uniform sampler2D rayOrigin;
uniform sampler2D rayDir;

layout(location = 0) out vec4 dda;     // (tMax, state)
layout(location = 1) out ivec4 voxel;  // (cell, cells visited)
layout(location = 2) out vec4 hit;     // (t, u, v, triangle | -1)

void main() {
    vec4 dir = readStream(rayDir);
    if (dir.w == GPURT_NO_RAY) discard;
    vec4 origin = readStream(rayOrigin);
    float tEnter = gridEntry(origin.xyz, dir.xyz, origin.w);
    hit = vec4(GPURT_FAR, 0.0f, 0.0f, -1.0f);
    if (tEnter == GPURT_MISSED_BOX) {
        dda = vec4(GPURT_FAR, GPURT_FAR, GPURT_FAR, float(RAY_INACTIVE));
        voxel = ivec4(0);
        return;
    }
    ivec3 cell;
    vec3 tMax;
    ddaSetup(origin.xyz, dir.xyz, tEnter, gridMin, cellSize, gridRes, cell, tMax);
    dda = vec4(tMax, float(RAY_ACTIVE));
    voxel = ivec4(cell, 0);
}
