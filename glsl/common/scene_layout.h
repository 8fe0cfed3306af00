// How the scene is laid out in textures (SceneTextures.cpp writes it, glsl/scene/scene.glsl reads
// it). Valid C++ and GLSL; tests/raytrace checks that both sides agree.
#ifndef GPURT_SCENE_LAYOUT_H
#define GPURT_SCENE_LAYOUT_H

// Voxel index: RG32UI, one texel per grid cell c = x + nx * (y + ny * z), wrapped into rows of
// this width: (start of the cell's list in the cell triangles, number of triangles) or, for an
// empty cell, (skip distance of UniformGrid::skip, 0). The GL holds the voxel index and the cell
// triangles as buffer textures, the same texels row after row, so the kernels address them in
// 1D (texel c here, 3k + i for list entry k); the rows are the layout of `gpurt pack --dump`.
#define GPURT_INDEX_WIDTH 4096
// Grid element lists ("cell triangles"): RGBA32F, the triangles of every cell's list in list
// order, three texels each: the vertices themselves, with w = the triangle id and its coverage
// flags: (v0.xyz, id), (v1.xyz, coverage flags: common/alpha.h GPURT_COVER_*), (v2.xyz, 0). The
// vertices, not edges rounded to floats: the watertight triangle test (common/raymath.h) needs a
// shared edge's vertices to be the same numbers in both of its triangles. This many references a
// row (3 x 4096 texels).
#define GPURT_REFS_PER_ROW 4096
// BVH nodes (accel/bvh): RGBA32UI buffer texture, two texels a node (common/bvh.h), this many
// nodes a row in `gpurt pack --dump`; its leaf-ordered triangle list is laid out as the cell lists.
#define GPURT_BVH_NODES_PER_ROW 1024
// The largest step of a BVH node's quantised box coordinate (16 bits, common/bvh.h).
#define GPURT_BVH_STEPS 65535u
// Triangles: RGBA32F, three texels each, one triangle never split across rows:
// (v0.xyz, material id), (e1 = v1 - v0, 0), (e2 = v2 - v0, 0).
#define GPURT_TRIANGLES_PER_ROW 1024
// Materials: RGBA32F, seventeen texels each, GPURT_MATERIALS_PER_ROW materials a row (a material
// never split across rows; material m at GPURT_MATERIAL_TEXEL(m, 0)): (diffuse, shininess), (specular, diffuse
// texture | -1), (reflectivity, model), (emission, occlusion channel), (transmission filter, index
// of refraction | 0, negated for a thin wall), (metallic, roughness, normal scale, occlusion
// strength), (roughness channel, metallic channel, normal texture | -1, emissive texture | -1),
// (alpha mode, alpha factor, alpha cutoff, alpha channel), (transmission channel, specular channel,
// specular colour texture | -1, specular factor), (specular colour, clearcoat), (clearcoat
// roughness, clearcoat channel, clearcoat roughness channel, clearcoat normal texture | -1),
// (clearcoat normal scale, sheen roughness, sheen colour texture | -1, sheen roughness channel),
// (sheen colour, iridescence channel), (volume absorption coefficient: Material::absorption,
// iridescence thickness channel), (iridescence factor, its index, its thickness's minimum and
// maximum, nm), (anisotropy strength, the cosine and sine of its rotation, its texture | -1),
// (KHR_materials_dispersion's dispersion on a transmissive solid, else 0; 0, 0, 0); a
// channel is 4 texture + channel (0 R .. 3 A), or -1. Back-face culling is in the accelerators'
// triangle lists (coverage flags: common/alpha.h GPURT_COVER_*).
#define GPURT_MATERIAL_TEXELS 17
#define GPURT_MATERIALS_PER_ROW 512
// Texel k of material m.
#define GPURT_MATERIAL_TEXEL(m, k) \
    ivec2(GPURT_MATERIAL_TEXELS * ((m) % GPURT_MATERIALS_PER_ROW) + (k), (m) / GPURT_MATERIALS_PER_ROW)
// The sheen's directional albedo E(n.v, roughness) (KHR_materials_sheen's albedo scaling;
// materials/SheenTable.cpp): R32F, GPURT_SHEEN_TABLE x GPURT_SHEEN_TABLE values, sqrt(n.v) along a
// row and the roughness down, both from 0 to 1 at the ends, as a buffer (row-major).
#define GPURT_SHEEN_TABLE 32
// Texture coordinates (scenes with a textured material): RGBA32F, two texels per triangle, laid
// out as the triangles (GPURT_TRIANGLES_PER_ROW a row): (t0, t1), (t2, 0, 0), in the image
// coordinates of common/texture.h; one triangle of zeros when the scene has none.
#define GPURT_TEXCOORD_TEXELS 2
// Vertex colours (scenes with colours, SCENE_VERTEX_COLORS): RGBA32F, three texels per triangle,
// laid out as the triangles: (c0, 0), (c1, 0), (c2, 0), linear RGB; one triangle of zeros when the
// scene has none.
// Vertex tangents (scenes with glTF TANGENT on a normal-mapped material, SCENE_VERTEX_TANGENTS):
// RGBA32F, three texels per triangle, laid out as the triangles: t0, t1, t2, each (tangent,
// handedness w = +-1), all zero for a triangle without.
// Texture images: an R32UI buffer texture of every texture's texels one after another, each image
// top row first, r | g << 8 | b << 16 | a << 24 sRGB; and an RGBA32UI buffer texture, one texel
// per texture: (its first texel there, width, height, wrapS | wrapT << 8). A single texel of each
// when the scene has no texture. The kernels decode the sRGB codes with an R32F buffer texture of
// 256 floats (common/texture.h srgbDecode8).
// Emitters (EmitterTable): RG32F buffer texture, one texel per emitting triangle: (cumulative
// area share, triangle id); one texel (1, -1) when the scene has none.

// Stream element (x, y) of the image-sized ray streams is pixel column x, row y counted from the
// TOP (so a download is in the contract's top-first order).
// The ray streams every accelerator traces: rayOrigin (o, tLimit), rayDir (d, GPURT_A_RAY or
// GPURT_NO_RAY); the hit stream it writes: (t, u, v, triangle | -1).
#define GPURT_A_RAY 0.0f      // rayDir.w: this element carries a ray
#define GPURT_NO_RAY -2.0f    // rayDir.w: this element carries no ray in this trace

#endif
