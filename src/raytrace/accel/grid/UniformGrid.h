// The uniform grid acceleration structure (Christen 2005, section 4.2; Purcell et al. 2002): a
// box split into nx*ny*nz cells, each with the ids of the triangles that overlap it, stored as
// prefix sums (cellStart) into one flat id list. Both backends traverse this same grid.
#pragma once

#include <cstddef>
#include <algorithm>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "scene/Scene.h"

namespace gpurt {

struct GridOptions {
    float lambda = 3.0f;                   // cells along the longest axis ~ lambda * N^(1/3)
    std::optional<glm::ivec3> resolution;  // overrides the automatic resolution
    int threads = 0;                       // 0: all cores
    bool skip = true;                      // empty-space skipping distances (computeSkip)
};

struct UniformGrid {
    glm::ivec3 resolution{1};                        // nx, ny, nz >= 1
    glm::vec3 min{0.0f}, max{0.0f}, cellSize{1.0f};  // cellSize = (max-min)/resolution, all > 0
    std::vector<uint32_t> cellStart;                 // size nx*ny*nz + 1 (prefix sums)
    // Triangle ids of cell c: [cellStart[c], cellStart[c+1]), ascending.
    std::vector<uint32_t> cellTriangles;
    // Empty-space skipping (proximity clouds, Cohen & Sheffer 1994): per cell, 0 where the cell
    // has triangles, else the chessboard distance in cells to the nearest cell that has (at most
    // 255), so every cell nearer than that is empty. Derived from cellStart (computeSkip).
    std::vector<uint8_t> skip;

    // The skip distance of an empty cell: every cell nearer than it (chessboard) is empty. 1 (no
    // skipping) when skip was not computed.
    int skipDistance(size_t cell) const { return skip.empty() ? 1 : std::max<int>(1, skip[cell]); }

    int cellIndex(glm::ivec3 v) const { return v.x + resolution.x * (v.y + resolution.y * v.z); }
    size_t cells() const;

    // Offset of secondary and shadow ray origins along the normal: 1e-4 * the box's largest extent.
    float rayOffset() const;
    // Slack when accepting a hit beyond the current cell's exit: 1e-4 * the smallest cell size.
    float hitTolerance() const;
    // The cells a ray may visit before both backends stop it (RAY_OVERFLOW): nx + ny + nz + 3,
    // more than a straight line can cross, so only a bug can reach it.
    int maxCellSteps() const { return resolution.x + resolution.y + resolution.z + 3; }
};

// Fills grid.skip from grid.cellStart: an exact chessboard distance transform (two raster passes
// over the 26-neighbourhood), independent of thread count.
void computeSkip(UniformGrid& grid);

// Most cells an automatic or explicit resolution may have (cellStart alone is 4 bytes a cell).
inline constexpr size_t kMaxGridCells = size_t(1) << 26;

// Builds the grid over the scene's bounds on `options.threads` threads; the result is the same
// whatever the thread count. Throws InputError for a bad explicit resolution or lambda, or a
// scene with non-finite vertices.
UniformGrid buildGrid(const Scene& scene, const GridOptions& options);

// The resolution buildGrid would give the scene, without building it.
glm::ivec3 gridResolution(const Scene& scene, const GridOptions& options);

}  // namespace gpurt
