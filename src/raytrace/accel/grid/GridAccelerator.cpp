// The uniform grid's registry entry: build, the packed sections GRID (resolution, box, cell
// size), CELL (cellStart) and LIST (cellTriangles), the checks the reader and the writer make,
// turning and rescaling (exact).
#include "raytrace/accel/grid/GridAccelerator.h"

#include <cmath>

#include "raytrace/accel/grid/GridCpu.h"
#include "raytrace/accel/grid/GridTexels.h"
#include "raytrace/common/Vec3.h"

namespace gpurt {

namespace {

constexpr char kGrid[] = "GRID";
constexpr char kCellStart[] = "CELL";
constexpr char kCellList[] = "LIST";
constexpr size_t kGridBytes = 3 * 4 + 9 * 4;

std::string resolutionText(glm::ivec3 r) {
    return std::to_string(r.x) + "x" + std::to_string(r.y) + "x" + std::to_string(r.z);
}

// The grid's resolution, box and cell size, the shape buildGrid gives and the traversal relies
// on; returns the number of cells.
uint64_t checkGridShape(const FileLoc& file, const Scene& scene, const UniformGrid& grid) {
    const glm::ivec3 r = grid.resolution;
    if (r.x < 1 || r.y < 1 || r.z < 1)
        failAt(file, "grid: resolution " + resolutionText(r) + " is not at least 1 on every axis");
    uint64_t cells = 1;
    for (int a = 0; a < 3; ++a) {
        // Each factor is checked before the product grows, so the product cannot overflow.
        if (uint64_t(r[a]) > kMaxGridCells || cells * uint64_t(r[a]) > kMaxGridCells)
            failAt(file, "grid: resolution " + resolutionText(r) + " has more than " + std::to_string(kMaxGridCells) +
                             " cells");
        cells *= uint64_t(r[a]);
    }
    if (!isFinite(grid.min) || !isFinite(grid.max) || !isFinite(grid.cellSize))
        failAt(file, "grid: bounds or cell size are not finite");
    for (int a = 0; a < 3; ++a)
        if (!(grid.min[a] < grid.max[a])) failAt(file, "grid: bounds are empty on axis " + std::to_string(a));
    const glm::vec3 cellSize = (grid.max - grid.min) / glm::vec3(r);
    if (cellSize != grid.cellSize) failAt(file, "grid: cell size is not (max - min) / resolution");
    const Bounds bounds = scene.bounds();
    if (!bounds.empty())
        for (int a = 0; a < 3; ++a)
            if (!(grid.min[a] <= bounds.min[a] && bounds.max[a] <= grid.max[a]))
                failAt(file, "grid: bounds do not contain the scene's triangles");
    return cells;
}

// The grid's cell lists: cellStart from 0, never decreasing, no cell past the list, the last
// ending at the list's end; every id a triangle, each cell's ids strictly ascending.
void checkGridLists(const FileLoc& file, const Scene& scene, const UniformGrid& grid, uint64_t cells) {
    const size_t n = scene.triangles.size();
    if (grid.cellStart.size() != cells + 1)
        failAt(file, "grid: " + std::to_string(grid.cellStart.size()) + " cell starts for " + std::to_string(cells) +
                         " cells (expected cells + 1)");
    if (grid.cellStart[0] != 0) failAt(file, "grid: the first cell does not start at 0");
    for (size_t c = 0; c < cells; ++c) {
        const uint32_t begin = grid.cellStart[c], end = grid.cellStart[c + 1];
        if (end < begin) failAt(file, "grid: cell starts decrease at cell " + std::to_string(c + 1));
        if (end > grid.cellTriangles.size())
            failAt(file, "grid: cell " + std::to_string(c) + " ends at " + std::to_string(end) + ", past the " +
                             std::to_string(grid.cellTriangles.size()) + " list entries");
        for (uint32_t k = begin; k < end; ++k) {
            const uint32_t id = grid.cellTriangles[k];
            if (id >= n)
                failAt(file, "grid: cell " + std::to_string(c) + " lists triangle " + std::to_string(id) + " of " +
                                 std::to_string(n));
            if (k > begin && !(grid.cellTriangles[k - 1] < id))
                failAt(file, "grid: the list of cell " + std::to_string(c) + " is not strictly ascending");
        }
    }
    if (grid.cellStart[cells] != grid.cellTriangles.size())
        failAt(file, "grid: the last cell ends at " + std::to_string(grid.cellStart[cells]) + ", not at the " +
                         std::to_string(grid.cellTriangles.size()) + " list entries");
}

// GRID: the resolution (3 x u32), then min, max and the cell size (3 x vec3).
void readShape(const PackedSection& s, UniformGrid& grid) {
    s.fixedSize(kGridBytes);
    ByteReader in = s.reader();
    for (int a = 0; a < 3; ++a) grid.resolution[a] = static_cast<int32_t>(in.u32());
    grid.min = in.vec3();
    grid.max = in.vec3();
    grid.cellSize = in.vec3();
}

// CELL: one u32 per cell plus one, for a resolution checked against kMaxGridCells first.
void readCellStart(const PackedSection& s, UniformGrid& grid) {
    const glm::ivec3 r = grid.resolution;
    uint64_t cells = 1;
    for (int a = 0; a < 3; ++a) {
        if (r[a] < 1 || uint64_t(r[a]) > kMaxGridCells || cells * uint64_t(r[a]) > kMaxGridCells)
            s.fail("grid: resolution " + resolutionText(r) + " is not 1.." + std::to_string(kMaxGridCells) + " cells");
        cells *= uint64_t(r[a]);
    }
    if (s.size() != (cells + 1) * 4)
        s.fail("section " + s.tag + ": " + std::to_string(s.size()) + " bytes, expected " +
               std::to_string((cells + 1) * 4) + " for the " + std::to_string(cells) + " cells of the grid");
    ByteReader in = s.reader();
    grid.cellStart.resize(size_t(cells) + 1);
    in.u32s(grid.cellStart);
}

// LIST: the cells' triangle ids, one u32 each.
void readCellList(const PackedSection& s, UniformGrid& grid) {
    if (s.size() % 4 != 0) s.fail("section " + s.tag + ": " + std::to_string(s.size()) + " bytes, not a whole number of ids");
    ByteReader in = s.reader();
    grid.cellTriangles.resize(size_t(s.size() / 4));
    in.u32s(grid.cellTriangles);
}

// The grid of the scene turned by rotateUpToY(axis): an axis permutation with signs, so each new
// axis is an old one, perhaps reversed. The box's corners turn exactly (a negated interval's width
// is the same float), the cells are the same cells in the new order, each list as it was (the
// triangles keep their ids); the skip distances are derived again.
UniformGrid turnGrid(const UniformGrid& grid, UpAxis axis) {
    if (axis == UpAxis::PosY) return grid;
    glm::ivec3 from(0);  // the old axis of each new one
    glm::ivec3 sign(1);
    for (int k = 0; k < 3; ++k) {
        glm::vec3 unit(0.0f);
        unit[k] = 1.0f;
        const glm::vec3 turned = upAxisToY(unit, axis);
        for (int a = 0; a < 3; ++a)
            if (turned[a] != 0.0f) {
                from[a] = k;
                sign[a] = turned[a] > 0.0f ? 1 : -1;
            }
    }
    UniformGrid t;
    for (int a = 0; a < 3; ++a) {
        const int k = from[a];
        t.resolution[a] = grid.resolution[k];
        t.min[a] = sign[a] > 0 ? grid.min[k] : -grid.max[k];
        t.max[a] = sign[a] > 0 ? grid.max[k] : -grid.min[k];
        t.cellSize[a] = grid.cellSize[k];
    }
    t.cellStart.reserve(grid.cellStart.size());
    t.cellTriangles.reserve(grid.cellTriangles.size());
    t.cellStart.push_back(0);
    glm::ivec3 cell;
    for (cell.z = 0; cell.z < t.resolution.z; ++cell.z)
        for (cell.y = 0; cell.y < t.resolution.y; ++cell.y)
            for (cell.x = 0; cell.x < t.resolution.x; ++cell.x) {
                glm::ivec3 old;
                for (int a = 0; a < 3; ++a) old[from[a]] = sign[a] > 0 ? cell[a] : t.resolution[a] - 1 - cell[a];
                const size_t c = size_t(grid.cellIndex(old));
                t.cellTriangles.insert(t.cellTriangles.end(), grid.cellTriangles.begin() + grid.cellStart[c],
                                       grid.cellTriangles.begin() + grid.cellStart[c + 1]);
                t.cellStart.push_back(uint32_t(t.cellTriangles.size()));
            }
    if (!grid.skip.empty()) computeSkip(t);
    return t;
}

class GridStructure final : public AccelStructure {
  public:
    explicit GridStructure(UniformGrid grid) : grid_(std::move(grid)) {}
    const UniformGrid& grid() const { return grid_; }

    const AcceleratorInfo& accelerator() const override { return gridAccelerator(); }
    float rayOffset() const override { return grid_.rayOffset(); }
    std::string summary() const override { return "grid " + resolutionText(grid_.resolution); }
    std::vector<std::pair<std::string, double>> figures() const override { return {}; }
    std::shared_ptr<const AccelStructure> turnedUp(UpAxis axis) const override {
        return std::make_shared<GridStructure>(turnGrid(grid_, axis));
    }
    std::shared_ptr<const AccelStructure> rescaled(int exponent) const override {
        UniformGrid g = grid_;
        g.min = rescalePoint(g.min, exponent);
        g.max = rescalePoint(g.max, exponent);
        g.cellSize = rescalePoint(g.cellSize, exponent);
        return std::make_shared<GridStructure>(std::move(g));
    }
    std::unique_ptr<CpuAccelerator> cpu(const Scene& scene) const override {
        return std::make_unique<GridCpu>(scene, grid_);
    }
    std::vector<TextureTexels> texels(const Scene& scene) const override { return sceneTextureTexels(scene, grid_); }
    void validate(const FileLoc& file, const Scene& scene) const override {
        checkGridLists(file, scene, grid_, checkGridShape(file, scene, grid_));
    }
    void pack(std::string_view tag, ByteWriter& out) const override {
        if (tag == kGrid) {
            for (int a = 0; a < 3; ++a) out.u32(static_cast<uint32_t>(grid_.resolution[a]));
            out.vec3(grid_.min);
            out.vec3(grid_.max);
            out.vec3(grid_.cellSize);
        } else if (tag == kCellStart) {
            out.u32s(grid_.cellStart);
        } else if (tag == kCellList) {
            out.u32s(grid_.cellTriangles);
        }
    }

  private:
    UniformGrid grid_;
};

std::shared_ptr<const AccelStructure> build(const Scene& scene, const AccelOptions& options) {
    GridOptions grid = options.grid;
    grid.threads = options.threads;
    return makeStructure(buildGrid(scene, grid));
}

std::shared_ptr<const AccelStructure> unpack(std::span<const PackedSection> sections, const Scene& scene) {
    UniformGrid grid;
    readShape(sections[0], grid);
    readCellStart(sections[1], grid);
    readCellList(sections[2], grid);
    checkGridLists(sections[0].file, scene, grid, checkGridShape(sections[0].file, scene, grid));
    // The skip distances are derived from cellStart (computeSkip) rather than stored.
    computeSkip(grid);
    return makeStructure(std::move(grid));
}

// A packed grid serves unless --lambda asks for another (so that every route gives the same
// image), and --skip off takes its skip distances away.
std::shared_ptr<const AccelStructure> reuse(std::shared_ptr<const AccelStructure> packed, const AccelOptions& options) {
    if (options.newGrid) return nullptr;
    if (options.grid.skip) return packed;
    UniformGrid grid = *gridOf(packed);
    grid.skip.clear();
    return makeStructure(std::move(grid));
}

}  // namespace

std::shared_ptr<const AccelStructure> makeStructure(UniformGrid grid) {
    return std::make_shared<GridStructure>(std::move(grid));
}

const UniformGrid* gridOf(const AccelStructure* structure) {
    const auto* g = dynamic_cast<const GridStructure*>(structure);
    return g ? &g->grid() : nullptr;
}

const AcceleratorInfo& gridAccelerator() {
    // A cell's visit costs 1.6 triangle tests on the gl backend: a least squares fit of the gl
    // trace times of seven scenes (boxes to the bunny, 512 x 512 primary rays, llvmpipe on 2
    // cores) to the counts (docs/PERFORMANCE.md, "A second accelerator").
    static const AcceleratorInfo info{"grid",
                                      "uniform grid, 3D-DDA",
                                      {kGrid, kCellStart, kCellList},
                                      1.6,
                                      build,
                                      unpack,
                                      reuse};
    return info;
}

}  // namespace gpurt
