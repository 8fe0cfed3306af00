// The CPU side of the scene textures: the texels of the triangles, the materials and what else the
// integrators read, laid out as glsl/common/scene_layout.h says (an accelerator's own textures are
// its folder's: accel/grid/GridTexels, accel/bvh/BvhTexels, using triangleListTexels). SceneTextures
// uploads them; `gpurt pack` reports their sizes and dumps them (--dump) without a GL context.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "raytrace/lights/EmitterTable.h"
#include "base/LargeArray.h"
#include "scene/Scene.h"

namespace gpurt {

// Triangle and material ids travel as float32 in the GL backend (the hit stream, the triangle
// texture's w), exact only below 2^24: scenes must have fewer of each.
inline constexpr size_t kMaxTextureTriangles = (size_t(1) << 24) - 1;
inline constexpr size_t kMaxTextureMaterials = (size_t(1) << 24) - 1;

// One texture's texels, row 0 first (the order of a GL upload), `channels` 32-bit values each:
// unsigned integers (R32UI, RG32UI) in `uints`, or floats (RGBA32F) in `floats`. Huge-page arrays
// (LargeArray.h): a big model's triangle lists are hundreds of megabytes, written once.
struct TextureTexels {
    std::string name;  // the sampler's name in the kernels: voxelIndex, cellTriangles, ...
    int width = 0, rows = 0, channels = 0;
    bool isFloat = false;
    LargeArray<uint32_t> uints;
    LargeArray<float> floats;

    size_t texels() const { return size_t(width) * size_t(rows); }
    size_t bytes() const { return texels() * size_t(channels) * 4; }
    // "RG32UI", "R32UI" or "RGBA32F".
    const char* formatName() const;
};

// Rows needed to hold `count` items at `perRow` a row (at least one row).
size_t textureRowsFor(size_t count, size_t perRow);

// A texture of `rows` rows of `width` texels of `channels` zeros (floats or uints), named `name`.
TextureTexels emptyTexture(const char* name, size_t width, size_t rows, int channels, bool isFloat);
// An accelerator's triangle list (the grid's cell lists, the BVH's leaves): triangle ids[k] at
// entry k, three texels an entry: (v0, triangle id), (v1, coverage flags: common/alpha.h
// GPURT_COVER_*), (v2, 0), the vertices as the scene holds them, so that a shared edge is the same
// numbers in both of its triangles (the watertight triangle test, common/raymath.h);
// GPURT_REFS_PER_ROW entries a row.
TextureTexels triangleListTexels(const Scene& scene, const std::vector<uint32_t>& ids, const char* name);
// RGBA32F, three texels a triangle: (v0, material id), (v1 - v0, 0), (v2 - v0, 0).
TextureTexels triangleTexels(const Scene& scene);
// RGBA32F, GPURT_MATERIAL_TEXELS texels a material (glsl/common/scene_layout.h), at most
// GPURT_MATERIALS_PER_ROW materials a row.
TextureTexels materialTexels(const Scene& scene);
// RGBA32F, as the triangle texture: (n0, 0), (n1, 0), (n2, 0) per triangle of scene.normals;
// one triangle of zeros when it is empty.
TextureTexels vertexNormalTexels(const Scene& scene);
// RGBA32F, two texels a triangle of scene.texcoords, laid out as the triangles: (t0, t1),
// (t2, 0, 0); one triangle of zeros when it is empty.
TextureTexels texcoordTexels(const Scene& scene);
// RGBA32F, as the vertex normals: (c0, 0), (c1, 0), (c2, 0) per triangle of scene.colors; one
// triangle of zeros when it is empty.
TextureTexels vertexColorTexels(const Scene& scene);
// RGBA32F, as the vertex normals: (t0), (t1), (t2) per triangle of scene.tangents, each the
// tangent and its handedness w; one triangle of zeros when it is empty.
TextureTexels vertexTangentTexels(const Scene& scene);
// R32UI, every texture's texels one after another (GPURT_INDEX_WIDTH a row); one texel when
// the scene has no texture.
TextureTexels textureImageTexels(const Scene& scene);
// RGBA32UI, one texel per texture: (first texel in textureImageTexels, width, height,
// wrapS | wrapT << 8); (0, 1, 1, 0) when there is none.
TextureTexels textureTableTexels(const Scene& scene);
// R32F, the 256 linear values of the sRGB codes (srgbDecodeTable).
TextureTexels srgbTableTexels();
// KHR_materials_sheen's albedo table (materials/SheenTable.h): R32F, row-major.
TextureTexels sheenTableTexels();
// RG32F, one row: (cumulative area share, triangle id) per entry of the emitter table; (1, -1)
// when it is empty.
TextureTexels emitterTexels(const EmitterTable& emitters);

// The integrators' (SceneTextures): the triangles to the sRGB table, then the vertex colours, then
// (only for a scene that has them) the vertex tangents.
std::vector<TextureTexels> integratorTextureTexels(const Scene& scene);

}  // namespace gpurt
