// The uniform grid's scene textures (glsl/common/scene_layout.h): its voxel index and cell lists.
#include "raytrace/accel/grid/GridTexels.h"

namespace gpurt {

namespace {
using namespace glm;
#include "../../../../glsl/common/scene_layout.h"
}  // namespace

TextureTexels voxelIndexTexels(const UniformGrid& grid) {
    const size_t cells = grid.cells();
    TextureTexels index = emptyTexture("voxelIndex", GPURT_INDEX_WIDTH,
                                       textureRowsFor(cells, GPURT_INDEX_WIDTH), 2, false);
    for (size_t c = 0; c < cells; ++c) {
        // An empty cell carries its skip distance instead of a list start (count 0 tells).
        index.uints[c * 2] = grid.cellStart[c + 1] != grid.cellStart[c] ? grid.cellStart[c]
                                                                         : uint32_t(grid.skipDistance(c));
        index.uints[c * 2 + 1] = grid.cellStart[c + 1] - grid.cellStart[c];
    }
    return index;
}

TextureTexels cellTriangleTexels(const Scene& scene, const UniformGrid& grid) {
    return triangleListTexels(scene, grid.cellTriangles, "cellTriangles");
}

std::vector<TextureTexels> sceneTextureTexels(const Scene& scene, const UniformGrid& grid) {
    std::vector<TextureTexels> all{voxelIndexTexels(grid), cellTriangleTexels(scene, grid)};
    for (TextureTexels& t : integratorTextureTexels(scene)) all.push_back(std::move(t));
    return all;
}

}  // namespace gpurt
