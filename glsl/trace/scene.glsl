// Scene access for the tracing kernels: the grid parameters and the packed scene textures of
// SceneTextures (layout in common/scene_layout.h).
#include "../common/scene_layout.h"
#include "../common/raymath.h"
#include "../common/stream.glsl"

uniform usamplerBuffer voxelIndex;  // (list start, count) per cell
uniform samplerBuffer cellTriangles; // the cells' lists: v0 + id, e1, e2
uniform sampler2D triangles;    // v0 + material, e1, e2
uniform sampler2D materials;
uniform sampler2D vertexNormals;  // per triangle n0, n1, n2 as the triangles' texels
uniform sampler2D triangleTexcoords;  // per triangle (t0, t1), (t2, 0, 0)
uniform usamplerBuffer textureTexels; // every texture image's sRGB RGBA8 texels
uniform usamplerBuffer textureTable;  // per texture (first texel, width, height, wrapS | wrapT << 8)
uniform samplerBuffer srgbTable;      // the linear value of each sRGB code
uniform samplerBuffer emitters;  // EmitterTable: (cdf, triangle id) per emitting triangle
uniform int emitterCount;        // 0: no emitters
uniform float emitterArea;       // their total area

uniform vec3 gridMin;
uniform vec3 gridMax;
uniform vec3 cellSize;
uniform ivec3 gridRes;
uniform float cellTolerance;  // a hit up to this far beyond the cell's exit still counts in it
uniform int maxCellSteps;     // more cells than a ray can cross: RAY_OVERFLOW
uniform int tileRow;          // the image row of the streams' row 0 (--tile; 0 for the whole image)

// The image pixel (column, row from the top) of this stream element, where the streams hold the
// image's rows from tileRow on.
uvec2 imagePixel() { return uvec2(gl_FragCoord.xy) + uvec2(0u, uint(tileRow)); }

// (start, count) of the triangle list of cell v.
uvec2 cellRange(ivec3 v) {
    uint c = uint(v.x + gridRes.x * (v.y + gridRes.y * v.z));
    return texelFetch(voxelIndex, int(c)).xy;
}

// Triangle `k` of the concatenated cell lists: its vertex 0, edges and id.
int fetchListTriangle(uint k, out vec3 v0, out vec3 e1, out vec3 e2) {
    int at = int(3u * k);
    vec4 a = texelFetch(cellTriangles, at);
    v0 = a.xyz;
    e1 = texelFetch(cellTriangles, at + 1).xyz;
    e2 = texelFetch(cellTriangles, at + 2).xyz;
    return int(a.w);
}

// Vertex 0, the two edges and the material id of triangle `id`.
void fetchTriangle(int id, out vec3 v0, out vec3 e1, out vec3 e2, out int material) {
    ivec2 at = ivec2(3 * (id % GPURT_TRIANGLES_PER_ROW), id / GPURT_TRIANGLES_PER_ROW);
    vec4 a = texelFetch(triangles, at, 0);
    v0 = a.xyz;
    material = int(a.w);
    e1 = texelFetch(triangles, at + ivec2(1, 0), 0).xyz;
    e2 = texelFetch(triangles, at + ivec2(2, 0), 0).xyz;
}

// The grid-box entry parameter of a ray that starts at o, or GPURT_MISSED_BOX (-1) when the
// segment [0, tLimit] misses the box.
float gridEntry(vec3 o, vec3 d, float tLimit) { return boxEntry(o, d, tLimit, gridMin, gridMax); }

// The emitter table entry for u in [0, 1): the first k with u < cdf[k] (EmitterTable::pick).
int pickEmitter(float u) {
    int lo = 0, hi = emitterCount - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (u < texelFetch(emitters, mid).x) hi = mid;
        else lo = mid + 1;
    }
    return lo;
}

