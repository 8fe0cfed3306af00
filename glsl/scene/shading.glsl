// Shared by the shading kernels: the shading math of common/shading.h and the material interface
// of common/material.h (both shared with the CPU backend), and the material record's fetch.
#include "scene.glsl"
#include "../common/shading.h"
#include "../common/material.h"
#include "../common/texture.h"

uniform float rayOffset;  // UniformGrid::rayOffset: how far secondary rays start off the surface

#include "../common/sampling.h"
// The emitters' point for the sample numbers u, uniform by area (the emitter by a binary search of
// the area table, EmitterTable::pick): q on triangle `id`.
vec3 emitterPointOf(vec2 u, out int id) {
    int k = pickEmitter(u.x);
    vec2 entry = texelFetch(emitters, k).xy;
    float lower = k == 0 ? 0.0f : texelFetch(emitters, k - 1).x;
    vec3 v0, e1, e2;
    int material;
    id = int(entry.y);
    fetchTriangle(id, v0, e1, e2, material);
    return emitterPoint(v0, e1, e2, vec2(remapToUnit(u.x, lower, entry.x), u.y));
}

// The emitters' point of a pixel's sample (s of n, seed, sampler) in dimension
// GPURT_DIM_EMITTER + depth (common/integrators/lights.h emitterVisible).
vec3 emitterSamplePoint(uvec2 pixel, uint s, uint n, uint seed, uint sampler, uint depth, out int id) {
    return emitterPointOf(sample2D(sampler, pixel.x, pixel.y, s, n, seed, GPURT_DIM_EMITTER + depth), id);
}

// The image coordinates at barycentrics (u, v) of triangle `id` (zeros without texture coordinates).
// What a scene lacks is compiled out (SceneTextures::bind defines SCENE_TEXTURES,
// SCENE_VERTEX_NORMALS, SCENE_VERTEX_COLORS, SCENE_EMITTERS): llvmpipe runs both sides of a branch under masks.
vec2 fetchTexcoord(int id, float u, float v) {
#ifdef SCENE_TEXTURES
    ivec2 at = ivec2(GPURT_TEXCOORD_TEXELS * (id % GPURT_TRIANGLES_PER_ROW), id / GPURT_TRIANGLES_PER_ROW);
    vec4 a = texelFetch(triangleTexcoords, at, 0);
    vec4 b = texelFetch(triangleTexcoords, at + ivec2(1, 0), 0);
    return interpolateTexcoord(a.xy, a.zw, b.xy, u, v);
#else
    return vec2(0.0f);
#endif
}

// The vertex colour of triangle `id` at barycentrics (u, v) (common/shading.h); white without
// vertex colours (compiled out: SCENE_VERTEX_COLORS).
vec3 fetchVertexColor(int id, float u, float v) {
#ifdef SCENE_VERTEX_COLORS
    ivec2 at = ivec2(3 * (id % GPURT_TRIANGLES_PER_ROW), id / GPURT_TRIANGLES_PER_ROW);
    return interpolateVertexColor(texelFetch(vertexColors, at, 0).xyz, texelFetch(vertexColors, at + ivec2(1, 0), 0).xyz,
                                  texelFetch(vertexColors, at + ivec2(2, 0), 0).xyz, u, v);
#else
    return vec3(1.0f);
#endif
}

vec3 textureTexel(int first, int width, int x, int y) {
    uint c = texelFetch(textureTexels, first + y * width + x).x;
    return vec3(texelFetch(srgbTable, int(c & 0xffu)).x, texelFetch(srgbTable, int((c >> 8) & 0xffu)).x,
                texelFetch(srgbTable, int((c >> 16) & 0xffu)).x);
}

// The diffuse colour kd times texture `tex`'s filtered colour at image coordinates t (-1: no
// texture; src/raytrace/materials/SurfaceTexture.cpp diffuseAt).
vec3 texturedDiffuse(int tex, vec3 kd, vec2 t) {
#ifdef SCENE_TEXTURES
    if (tex < 0) return kd;
    uvec4 info = texelFetch(textureTable, tex);
    int first = int(info.x), w = int(info.y), h = int(info.z);
    ivec2 columns, rows;
    vec2 f;
    bilinearFootprint(t, w, h, int(info.w & 0xffu), int(info.w >> 8), columns, rows, f);
    return kd * bilinearBlend(textureTexel(first, w, columns.x, rows.x), textureTexel(first, w, columns.y, rows.x),
                              textureTexel(first, w, columns.x, rows.y), textureTexel(first, w, columns.y, rows.y), f);
#else
    return kd;
#endif
}

// Channel `code` % 4 (0 R .. 3 A) of texture `code` / 4 at image coordinates t, filtered, as a
// linear number in [0, 1]; 1 for code -1 (src/raytrace/materials/SurfaceTexture.cpp sampleChannel).
float textureChannel(int code, vec2 t) {
#ifdef SCENE_TEXTURES
    if (code < 0) return 1.0f;
    uvec4 info = texelFetch(textureTable, code >> 2);
    int first = int(info.x), w = int(info.y), h = int(info.z);
    uint shift = 8u * uint(code & 3);
    ivec2 columns, rows;
    vec2 f;
    bilinearFootprint(t, w, h, int(info.w & 0xffu), int(info.w >> 8), columns, rows, f);
    float c00 = float((texelFetch(textureTexels, first + rows.x * w + columns.x).x >> shift) & 0xffu);
    float c01 = float((texelFetch(textureTexels, first + rows.x * w + columns.y).x >> shift) & 0xffu);
    float c10 = float((texelFetch(textureTexels, first + rows.y * w + columns.x).x >> shift) & 0xffu);
    float c11 = float((texelFetch(textureTexels, first + rows.y * w + columns.y).x >> shift) & 0xffu);
    return bilinearBlend(vec3(c00), vec3(c01), vec3(c10), vec3(c11), f).x / 255.0f;
#else
    return 1.0f;
#endif
}

// The linear values of texture `tex`'s red, green and blue channels at t (a normal map).
vec3 textureLinear(int tex, vec2 t) {
    return vec3(textureChannel(4 * tex, t), textureChannel(4 * tex + 1, t), textureChannel(4 * tex + 2, t));
}

// The texture coordinates' differences along triangle `id`'s edges, t1 - t0 and t2 - t0 (0
// without texture coordinates in the scene).
void fetchTexcoordEdges(int id, out vec2 dt1, out vec2 dt2) {
    dt1 = vec2(0.0f);
    dt2 = vec2(0.0f);
#ifdef SCENE_TEXTURES
    ivec2 at = ivec2(GPURT_TEXCOORD_TEXELS * (id % GPURT_TRIANGLES_PER_ROW), id / GPURT_TRIANGLES_PER_ROW);
    vec4 a = texelFetch(triangleTexcoords, at, 0);
    vec4 b = texelFetch(triangleTexcoords, at + ivec2(1, 0), 0);
    dt1 = a.zw - a.xy;
    dt2 = b.xy - a.xy;
#endif
}

#ifdef SCENE_VERTEX_TANGENTS
// Triangle `id`'s vertex tangent at barycentrics uv (common/shading.h interpolateTangent).
vec4 fetchVertexTangent(int id, vec2 uv) {
    ivec2 corner = ivec2(3 * (id % GPURT_TRIANGLES_PER_ROW), id / GPURT_TRIANGLES_PER_ROW);
    return interpolateTangent(texelFetch(vertexTangents, corner, 0), texelFetch(vertexTangents, corner + ivec2(1, 0), 0),
                              texelFetch(vertexTangents, corner + ivec2(2, 0), 0), uv.x, uv.y);
}
#endif

// The shading normal ns bent by normal map `map` (-1: none) of scale `scale` (fetchMappedNormal;
// a clearcoat's normal map: fetchMaterialRecord).
vec3 fetchNormalMapped(int map, float scale, int id, vec3 e1, vec3 e2, vec3 d, vec3 ng, vec3 ns, vec2 t, vec2 uv) {
#ifdef SCENE_NORMAL_MAPS
    if (map < 0) return ns;
    vec2 dt1, dt2;
    fetchTexcoordEdges(id, dt1, dt2);
#ifdef SCENE_VERTEX_TANGENTS
    return normalMappedTangent(ns, ng, d, fetchVertexTangent(id, uv), e1, e2, dt1, dt2,
                               textureLinear(map, t), scale);
#else
    return normalMapped(ns, ng, d, e1, e2, dt1, dt2, textureLinear(map, t), scale);
#endif
#else
    return ns;
#endif
}

// The shading normal ns of triangle `id` (edges e1, e2, seen along d, geometric normal ng) with
// material m's normal map applied at image coordinates t (common/shading.h normalMapped): in the
// frame of the triangle's vertex tangents at barycentrics uv where the scene has them
// (SCENE_VERTEX_TANGENTS, normalMappedTangent, which falls back to the generated frame where they
// are zero or degenerate), else in the frame generated from its texture coordinates.
vec3 fetchMappedNormal(int m, int id, vec3 e1, vec3 e2, vec3 d, vec3 ng, vec3 ns, vec2 t, vec2 uv) {
#ifdef SCENE_NORMAL_MAPS
    vec4 f = texelFetch(materials, GPURT_MATERIAL_TEXEL(m, 5), 0);
    vec4 g = texelFetch(materials, GPURT_MATERIAL_TEXEL(m, 6), 0);
    return fetchNormalMapped(int(g.z), f.z, id, e1, e2, d, ng, ns, t, uv);
#else
    return ns;
#endif
}

// The radiance an emitter's material m emits (the light a shadow ray towards it carries).
vec3 fetchEmission(int m) { return texelFetch(materials, GPURT_MATERIAL_TEXEL(m, 3), 0).xyz; }

// The shading normal of triangle `id` at barycentrics (u, v), facing as ng (common/shading.h).
vec3 fetchShadingNormal(int id, float u, float v, vec3 ng) {
#ifdef SCENE_VERTEX_NORMALS
    ivec2 at = ivec2(3 * (id % GPURT_TRIANGLES_PER_ROW), id / GPURT_TRIANGLES_PER_ROW);
    vec3 n0 = texelFetch(vertexNormals, at, 0).xyz;
    vec3 n1 = texelFetch(vertexNormals, at + ivec2(1, 0), 0).xyz;
    vec3 n2 = texelFetch(vertexNormals, at + ivec2(2, 0), 0).xyz;
    return shadingNormal(n0, n1, n2, u, v, ng);
#else
    return ng;
#endif
}

// KHR_materials_anisotropy's direction in scene space of triangle `id` at barycentrics uv
// (common/shading.h anisotropyFrameDirection): `direction` in the frame of its vertex tangent
// (SCENE_VERTEX_TANGENTS) or of its texture coordinates (SCENE_TEXTURES) or around the up axis,
// about the front side's shading normal (MaterialRecord.cpp anisotropyDirectionAt).
vec3 fetchAnisotropyDirection(int id, vec2 uv, vec2 direction) {
    vec3 v0, e1, e2;
    int material;
    fetchTriangle(id, v0, e1, e2, material);
    vec3 ns = fetchShadingNormal(id, uv.x, uv.y, facingNormal(e1, e2, -cross(e1, e2)));
    vec2 dt1, dt2;
    fetchTexcoordEdges(id, dt1, dt2);
    vec4 tangent = vec4(0.0f);
    bool hasTangent = false;
#ifdef SCENE_VERTEX_TANGENTS
    tangent = fetchVertexTangent(id, uv);
    hasTangent = true;
#endif
    return anisotropyFrameDirection(ns, hasTangent, tangent, e1, e2, dt1, dt2, direction);
}

// The layers of glTF's extensions of the record r of the material at texel `at` (fetchMaterialRecord):
// KHR_materials_specular, _sheen, _clearcoat, _iridescence and _anisotropy, and KHR_materials_volume's
// medium, each compiled in for scenes that have it.
void fetchLayers(inout MaterialRecord r, ivec2 at, int id, vec2 uv, vec3 d, vec2 t) {
#ifdef SCENE_ANISOTROPY  // KHR_materials_anisotropy: the strength (B of its map) and the direction (RG, turned)
    vec4 an = texelFetch(materials, at + ivec2(15, 0), 0);
    vec3 texel = vec3(1.0f, 0.5f, 1.0f);
#ifdef SCENE_TEXTURES
    if (an.w >= 0.0f) texel = textureLinear(int(an.w), t);
#endif
    vec3 anisotropy = gltfAnisotropyAt(an.x, an.yz, texel);
    r.anisotropy = anisotropy.z;
    if (r.anisotropy > 0.0f) {
        r.anisotropyDirection = fetchAnisotropyDirection(id, uv, vec2(anisotropy.x, anisotropy.y));
        if (r.anisotropyDirection == vec3(0.0f)) r.anisotropy = 0.0f;  // no tangent (n along the up axis): isotropic
    }
#endif
#ifdef SCENE_VOLUME  // KHR_materials_volume: the absorption coefficient (Material::absorption)
    r.absorption = texelFetch(materials, at + ivec2(13, 0), 0).xyz;
#endif
#ifdef SCENE_DISPERSION  // KHR_materials_dispersion (Material::disperses)
    r.dispersion = texelFetch(materials, at + ivec2(16, 0), 0).x;
#endif
#ifdef SCENE_IRIDESCENCE  // KHR_materials_iridescence: the film's weight (R of its map), index, thickness (G)
    vec4 film = texelFetch(materials, at + ivec2(14, 0), 0);
    r.iridescence = film.x * textureChannel(int(texelFetch(materials, at + ivec2(12, 0), 0).w), t);
    r.iridescenceIor = film.y;
    r.iridescenceThickness = mix(film.z, film.w, textureChannel(int(texelFetch(materials, at + ivec2(13, 0), 0).w), t));
#endif
#ifdef SCENE_SPECULAR_LAYER  // KHR_materials_specular
    vec4 sp = texelFetch(materials, at + ivec2(8, 0), 0);
    r.specularWeight = sp.w * textureChannel(int(sp.y), t);
    r.specularColor = texturedDiffuse(int(sp.z), texelFetch(materials, at + ivec2(9, 0), 0).xyz, t);
#endif
#ifdef SCENE_SHEEN  // KHR_materials_sheen: its colour (sRGB map) and roughness (A of its map)
    vec4 sh = texelFetch(materials, at + ivec2(11, 0), 0);
    r.sheenColor = texturedDiffuse(int(sh.z), texelFetch(materials, at + ivec2(12, 0), 0).xyz, t);
    r.sheenRoughness = sh.y * textureChannel(int(sh.w), t);
#endif
#ifdef SCENE_CLEARCOAT  // KHR_materials_clearcoat: the coat and its normal, the interpolated one or its own map's
    vec4 cc = texelFetch(materials, at + ivec2(10, 0), 0);
    r.coat = texelFetch(materials, at + ivec2(9, 0), 0).w * textureChannel(int(cc.y), t);
    r.coatRoughness = cc.x * textureChannel(int(cc.z), t);
    if (r.coat > 0.0f) {
        vec3 v0, e1, e2;
        int material;
        fetchTriangle(id, v0, e1, e2, material);
        vec3 ng = facingNormal(e1, e2, d);
        r.coatNormal = fetchNormalMapped(int(cc.w), texelFetch(materials, at + ivec2(11, 0), 0).x, id, e1, e2, d, ng,
                                         fetchShadingNormal(id, uv.x, uv.y, ng), t, uv);
    }
#endif
}

// The material record (common/material.h) of material m at image coordinates t: every field of
// its texels, the diffuse colour textured at t and times the vertex colour, t and the colour those
// of triangle `id` at the hit's barycentrics uv (surface.frag writes uv; the later passes read it
// from surfaceView.w and surfaceShading.w, id from surfacePoint.w), seen along d (a clearcoat's
// normal faces the ray: CpuScene::surfaceAt). What a kernel does not use the compiler drops.
MaterialRecord fetchMaterialRecord(int m, int id, vec2 uv, vec3 d) {
    vec2 t = fetchTexcoord(id, uv.x, uv.y);
    ivec2 at = GPURT_MATERIAL_TEXEL(m, 0);
    vec4 a = texelFetch(materials, at, 0);
    vec4 b = texelFetch(materials, at + ivec2(1, 0), 0);
    vec4 c = texelFetch(materials, at + ivec2(2, 0), 0);
    vec4 e = texelFetch(materials, at + ivec2(4, 0), 0);
    MaterialRecord r;
    r.model = int(c.w);
    r.kd = texturedDiffuse(int(b.w), a.xyz, t);
    r.kd = r.kd * fetchVertexColor(id, uv.x, uv.y);
    r.ks = b.xyz;
    r.ns = a.w;
    r.reflectivity = c.xyz;
    r.tf = e.xyz;
    r.ior = abs(e.w);
    r.thin = e.w < 0.0f;
    vec4 emission = texelFetch(materials, at + ivec2(3, 0), 0);
    r.emission = emission.xyz;
    r.emitterLight = true;
    r.metallic = 0.0f;
    r.roughness = 1.0f;
    r.occlusion = 1.0f;
    r.specularColor = vec3(1.0f);
    r.specularWeight = 1.0f;
    r.coat = 0.0f;
    r.coatRoughness = 0.0f;
    r.coatNormal = vec3(0.0f, 0.0f, 1.0f);
    r.sheenColor = vec3(0.0f);
    r.sheenRoughness = 0.0f;
    r.iridescence = 0.0f;
    r.iridescenceIor = 1.3f;
    r.iridescenceThickness = 0.0f;
    r.anisotropy = 0.0f;
    r.anisotropyDirection = vec3(1.0f, 0.0f, 0.0f);
    r.absorption = vec3(0.0f);
    r.dispersion = 0.0f;
#ifdef SCENE_MODEL_2
    vec4 f = texelFetch(materials, at + ivec2(5, 0), 0);
    vec4 g = texelFetch(materials, at + ivec2(6, 0), 0);
    r.metallic = f.x * textureChannel(int(g.y), t);
    r.roughness = f.y * textureChannel(int(g.x), t);
    r.occlusion = 1.0f + f.w * (textureChannel(int(emission.w), t) - 1.0f);
    if (g.w >= 0.0f) {
        r.emission = texturedDiffuse(int(g.w), r.emission, t);
        r.emitterLight = false;
    }
#ifdef SCENE_TRANSMISSION_MAPS  // a transmissive glTF material with a transmissionTexture: its R scales the factor
    r.tf = r.tf * textureChannel(int(texelFetch(materials, at + ivec2(8, 0), 0).x), t);
#endif
    fetchLayers(r, at, id, uv, d, t);
#endif
    return r;
}

// The pixel of the path in this element (path integrator): the element itself in round 0 (the
// camera rays, in image order), else the one its path state (pdf, x, y, 0) carries, as the live
// paths are packed after each round (integrators/path/bounce.frag).
ivec2 pathPixel(vec4 state, int depth) { return depth == 0 ? ivec2(imagePixel()) : ivec2(state.yz); }

#include "../common/environment.h"
#ifdef SCENE_ENVIRONMENT  // SceneTextures::bind: the scene has an environment light
#include "environment.glsl"
#else
// No environment: the shared integrators (common/integrators/) see sceneHasEnvironment false and
// environmentSampled false (integrators/hooks.glsl), so nothing calls these.
vec3 environmentRadiance(vec3 d) { return vec3(0.0f); }
float environmentLightPdf(vec3 d) { return 0.0f; }
bool sampleEnvironment(vec2 u, out vec3 dir, out float pdf) {
    dir = vec3(0.0f);
    pdf = 0.0f;
    return false;
}
vec3 environmentAmbient(vec3 n) { return vec3(0.0f); }
#endif
