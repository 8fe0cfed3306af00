// The uniform grid's scene textures, laid out as glsl/common/scene_layout.h says (GridGl uploads
// them, GridCpu's traversal reads the grid itself).
#pragma once

#include "raytrace/accel/grid/UniformGrid.h"
#include "raytrace/textures/SceneTextureLayout.h"

#include <vector>

namespace gpurt {

// RG32UI, one texel per cell: (start of the cell's list, its length), or (skip distance, 0) for an
// empty cell.
TextureTexels voxelIndexTexels(const UniformGrid& grid);
// RGBA32F, the cells' lists in order (triangleListTexels).
TextureTexels cellTriangleTexels(const Scene& scene, const UniformGrid& grid);
// All the textures of a grid scene, in the order SceneTextures binds them: the grid's, then the
// integrators' (integratorTextureTexels).
std::vector<TextureTexels> sceneTextureTexels(const Scene& scene, const UniformGrid& grid);

}  // namespace gpurt
