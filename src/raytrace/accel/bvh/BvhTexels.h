// The BVH's scene textures, laid out as glsl/common/scene_layout.h says (BvhGl uploads them,
// BvhCpu traverses the same texels).
#pragma once

#include "raytrace/accel/bvh/Bvh.h"
#include "raytrace/textures/SceneTextureLayout.h"

#include <vector>

namespace gpurt {

// RGBA32UI, the BVH's nodes, two texels each, one per child: its box in 16-bit steps of
// Bvh::quantisation, rounded outwards, and its reference (glsl/common/bvh.h bvhChildBox);
// GPURT_BVH_NODES_PER_ROW nodes a row.
TextureTexels bvhNodeTexels(const Bvh& bvh);
// RGBA32F, the BVH's leaf-ordered triangle list (triangleListTexels).
TextureTexels bvhTriangleTexels(const Scene& scene, const Bvh& bvh);
// All the textures of a BVH scene, in the order SceneTextures binds them: the BVH's, then the
// integrators' (integratorTextureTexels).
std::vector<TextureTexels> sceneTextureTexels(const Scene& scene, const Bvh& bvh);

}  // namespace gpurt
