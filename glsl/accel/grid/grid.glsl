// The uniform grid accelerator's scene textures and parameters (accel/grid/GridGl binds them),
// for its kernels: precalc, traverse, intersect and the fused trace.
#include "scene/pixel.glsl"

uniform usamplerBuffer voxelIndex;   // (list start, count) per cell
uniform samplerBuffer cellTriangles; // the cells' lists: v0 + id, v1 + coverage flags, v2

uniform vec3 gridMin;
uniform vec3 gridMax;
uniform vec3 cellSize;
uniform ivec3 gridRes;
uniform float cellTolerance;  // a hit up to this far beyond the cell's exit still counts in it
uniform int maxCellSteps;     // more cells than a ray can cross: RAY_OVERFLOW

#define GPURT_MISSED_BOX -1.0f  // gridEntry of a ray that misses the grid's box (a miss, counted)

// (start, count) of the triangle list of cell v.
uvec2 cellRange(ivec3 v) {
    uint c = uint(v.x + gridRes.x * (v.y + gridRes.y * v.z));
    return texelFetch(voxelIndex, int(c)).xy;
}

// Triangle `k` of the concatenated cell lists: its vertices, coverage flags and id.
int fetchListTriangle(uint k, out vec3 v0, out vec3 v1, out vec3 v2, out float flags) {
    int at = int(3u * k);
    vec4 a = texelFetch(cellTriangles, at);
    v0 = a.xyz;
    vec4 b = texelFetch(cellTriangles, at + 1);
    v1 = b.xyz;
    flags = b.w;
    v2 = texelFetch(cellTriangles, at + 2).xyz;
    return int(a.w);
}

// How common/grid.h reads the grid here (the kernel defines GRID_COVERED, then includes it).
#define GPURT_GRID_PARAMS
#define GPURT_GRID_ARGS
#define GPURT_GRID_MIN gridMin
#define GPURT_GRID_BOX_MAX gridMax
#define GPURT_GRID_CELL cellSize
#define GPURT_GRID_RES gridRes
#define GPURT_GRID_TOLERANCE cellTolerance
#define GPURT_GRID_RANGE(cell) cellRange(cell)
#define GPURT_GRID_SKIP(cell, range) int((range).x)  // an empty cell's entry holds its skip distance
#define GPURT_GRID_TRI(k, v0, v1, v2, flags) fetchListTriangle(k, v0, v1, v2, flags)
#define GPURT_GRID_COVERED(id, flags, u, v, d, e1, e2, anyHit) GRID_COVERED(id, flags, u, v, d, e1, e2, anyHit)

// The grid-box entry parameter of a ray that starts at o, or GPURT_MISSED_BOX (-1) when the
// segment [0, tLimit] misses the box.
float gridEntry(vec3 o, vec3 d, float tLimit) { return boxEntry(o, d, tLimit, gridMin, gridMax); }
