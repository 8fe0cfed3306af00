// Scene access for the integrators' kernels: the packed scene textures of SceneTextures (layout in
// common/scene_layout.h). The accelerator's own textures are its kernels' (glsl/accel/).
#include "pixel.glsl"

uniform sampler2D triangles;    // v0 + material, e1, e2
uniform sampler2D materials;
uniform sampler2D vertexNormals;  // per triangle n0, n1, n2 as the triangles' texels
uniform sampler2D triangleTexcoords;  // per triangle (t0, t1), (t2, 0, 0)
uniform usamplerBuffer textureTexels; // every texture image's sRGB RGBA8 texels
uniform usamplerBuffer textureTable;  // per texture (first texel, width, height, wrapS | wrapT << 8)
uniform samplerBuffer srgbTable;      // the linear value of each sRGB code
#ifdef SCENE_SHEEN
uniform samplerBuffer sheenTable;  // the sheen's albedo E(n.v, roughness) (scene_layout.h GPURT_SHEEN_TABLE)
// Entry (i, j) of it (common/materials/gltf.h sheenAlbedo; C++: materials/SheenTable.cpp).
float sheenAlbedoTexel(int i, int j) { return texelFetch(sheenTable, j * GPURT_SHEEN_TABLE + i).x; }
#endif
uniform sampler2D vertexColors;       // per triangle c0, c1, c2 as the triangles' texels
#ifdef SCENE_VERTEX_TANGENTS
uniform sampler2D vertexTangents;     // per triangle t0, t1, t2 (tangent, handedness) as the triangles' texels
#endif
uniform samplerBuffer emitters;  // EmitterTable: (cdf, triangle id) per emitting triangle
uniform int emitterCount;        // 0: no emitters
uniform float emitterArea;       // their total area

// Vertex 0, the two edges and the material id of triangle `id`.
void fetchTriangle(int id, out vec3 v0, out vec3 e1, out vec3 e2, out int material) {
    ivec2 at = ivec2(3 * (id % GPURT_TRIANGLES_PER_ROW), id / GPURT_TRIANGLES_PER_ROW);
    vec4 a = texelFetch(triangles, at, 0);
    v0 = a.xyz;
    material = int(a.w);
    e1 = texelFetch(triangles, at + ivec2(1, 0), 0).xyz;
    e2 = texelFetch(triangles, at + ivec2(2, 0), 0).xyz;
}

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

