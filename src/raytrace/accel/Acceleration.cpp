#include "raytrace/accel/Acceleration.h"

#include <future>

#include "raytrace/accel/SceneBox.h"
#include "raytrace/accel/bvh/BvhCpu.h"
#include "raytrace/accel/grid/GridCpu.h"

namespace gpurt {

namespace {

// The cost of a grid cell's and a BVH node's visit on the gl backend, in triangle tests: a least
// squares fit of the gl trace times of seven scenes (boxes to the bunny, 512 x 512 primary rays,
// llvmpipe on 2 cores) to these counts (docs/PERFORMANCE.md, "A second accelerator"); with them the
// estimate picked the faster structure on all seven.
constexpr double kCellCost = 1.6;
constexpr double kNodeCost = 2.6;
constexpr double kTestCost = 1.0;
constexpr int kEstimateSize = 64;

}  // namespace

const char* accelName(AccelKind kind) { return kind == AccelKind::Bvh ? "bvh" : "grid"; }

bool parseAccelChoice(const std::string& text, AccelChoice& choice) {
    if (text == "grid") choice = AccelChoice::Grid;
    else if (text == "bvh") choice = AccelChoice::Bvh;
    else if (text == "auto") choice = AccelChoice::Auto;
    else return false;
    return true;
}

float Acceleration::rayOffset() const {
    if (grid) return grid->rayOffset();
    if (bvh) return bvh->rayOffset();
    return sceneRayOffset(glm::vec3(-1.0f), glm::vec3(1.0f));
}

AccelEstimate estimateAccelerators(const Scene& scene, const UniformGrid& grid, const Bvh& bvh,
                                   const CameraBasis& view) {
    CameraBasis camera = view;
    camera.width = camera.height = kEstimateSize;  // the same view (its aspect stays)
    camera.rowBegin = camera.rowCount = 0;
    const GridCpu gridTracer(scene, grid);
    const BvhCpu bvhTracer(scene, bvh);
    double cells = 0, gridTests = 0, nodes = 0, bvhTests = 0;
    for (int j = 0; j < kEstimateSize; ++j)
        for (int i = 0; i < kEstimateSize; ++i) {
            const glm::vec3 d = primaryDirection(camera, i, j);
            const TraceHit g = gridTracer.closestHit(camera.eye, d, 1e30f, 0u);
            const TraceHit b = bvhTracer.closestHit(camera.eye, d, 1e30f, 0u);
            cells += g.steps;
            gridTests += g.tests;
            nodes += b.steps;
            bvhTests += b.tests;
        }
    const double rays = double(kEstimateSize) * kEstimateSize;
    return {(cells * kCellCost + gridTests * kTestCost) / rays, (nodes * kNodeCost + bvhTests * kTestCost) / rays};
}

Acceleration chooseAcceleration(const Scene& scene, AccelChoice choice, std::optional<UniformGrid> grid,
                                std::optional<Bvh> bvh, const GridOptions& gridOptions, const CameraBasis& camera) {
    // A packed scene carries the one its packing chose: it stands.
    if (choice == AccelChoice::Auto && grid.has_value() != bvh.has_value())
        choice = bvh ? AccelChoice::Bvh : AccelChoice::Grid;
    Acceleration a;
    a.kind = choice == AccelChoice::Bvh ? AccelKind::Bvh : AccelKind::Grid;
    a.source = (choice == AccelChoice::Grid && grid) || (choice == AccelChoice::Bvh && bvh) ? "packed" : "built";
    if (choice == AccelChoice::Auto && !grid && !bvh) {
        // Both at once: the grid's serial steps (the counting sort's prefix sums, the skip
        // distances) run beside the BVH's build rather than after it.
        std::future<UniformGrid> built = std::async(std::launch::async, [&] { return buildGrid(scene, gridOptions); });
        bvh = buildBvh(scene, BvhOptions{gridOptions.threads});
        grid = built.get();
    }
    if (choice != AccelChoice::Bvh && !grid) grid = buildGrid(scene, gridOptions);
    if (choice != AccelChoice::Grid && !bvh) bvh = buildBvh(scene, BvhOptions{gridOptions.threads});
    if (choice == AccelChoice::Auto) {
        a.estimate = estimateAccelerators(scene, *grid, *bvh, camera);
        a.kind = a.estimate->bvh < a.estimate->grid ? AccelKind::Bvh : AccelKind::Grid;
        a.source = "auto";
    }
    a.gridResolution = grid ? grid->resolution : gridResolution(scene, gridOptions);
    if (a.kind == AccelKind::Bvh) a.bvh = std::move(bvh);
    else a.grid = std::move(grid);
    return a;
}

std::unique_ptr<CpuAccelerator> makeCpuAccelerator(const Scene& scene, const Acceleration& accel) {
    if (accel.kind == AccelKind::Bvh) return std::make_unique<BvhCpu>(scene, *accel.bvh);
    return std::make_unique<GridCpu>(scene, *accel.grid);
}

}  // namespace gpurt
