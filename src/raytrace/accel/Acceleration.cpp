#include "raytrace/accel/Acceleration.h"

#include <future>

#include "image/InputError.h"
#include "raytrace/accel/grid/GridAccelerator.h"

namespace gpurt {

namespace {

constexpr int kEstimateSize = 64;

// Every accelerator's structure at once: all but the last are built beside it (the grid's serial
// steps, the counting sort's prefix sums and the skip distances, run beside the BVH's build).
std::vector<std::shared_ptr<const AccelStructure>> buildAll(const Scene& scene, const AccelOptions& options) {
    const std::vector<const AcceleratorInfo*>& all = accelerators();
    std::vector<std::future<std::shared_ptr<const AccelStructure>>> beside;
    for (size_t k = 0; k + 1 < all.size(); ++k)
        beside.push_back(std::async(std::launch::async, [&, k] { return all[k]->build(scene, options); }));
    std::shared_ptr<const AccelStructure> last = all.back()->build(scene, options);
    std::vector<std::shared_ptr<const AccelStructure>> built;
    for (auto& b : beside) built.push_back(b.get());
    built.push_back(std::move(last));
    return built;
}

}  // namespace

double estimateCost(const Scene& scene, const AccelStructure& structure, const CameraBasis& view) {
    CameraBasis camera = view;
    camera.width = camera.height = kEstimateSize;  // the same view (its aspect stays)
    camera.rowBegin = camera.rowCount = 0;
    const std::unique_ptr<CpuAccelerator> tracer = structure.cpu(scene);
    double visits = 0, tests = 0;
    for (int j = 0; j < kEstimateSize; ++j)
        for (int i = 0; i < kEstimateSize; ++i) {
            const TraceHit h = tracer->closestHit(camera.eye, primaryDirection(camera, i, j), 1e30f, 0u);
            visits += h.steps;
            tests += h.tests;
        }
    const double rays = double(kEstimateSize) * kEstimateSize;
    return (visits * structure.accelerator().visitCost + tests) / rays;
}

Acceleration chooseAcceleration(const Scene& scene, std::string_view choice, std::shared_ptr<const AccelStructure> packed,
                                const AccelOptions& options, const CameraBasis& camera) {
    if (choice != "auto" && !findAccelerator(choice))
        throw InputError("--accel: unknown structure '" + std::string(choice) + "' (" + acceleratorNames(", ") +
                         " or auto)");
    // A packed scene carries the one its packing chose: it stands.
    if (choice == "auto" && packed) choice = packed->accelerator().name;
    Acceleration a;
    if (packed && packed->accelerator().name == choice) {
        a.structure = packed->accelerator().reuse(packed, options);
        if (a.structure) a.source = "packed";
    }
    if (!a.structure && choice != "auto") a.structure = findAccelerator(choice)->build(scene, options);
    if (!a.structure) {
        double best = 0;
        for (std::shared_ptr<const AccelStructure>& s : buildAll(scene, options)) {
            const double cost = estimateCost(scene, *s, camera);
            a.estimate.emplace_back(s->accelerator().name, cost);
            if (!a.structure || cost < best) {
                a.structure = std::move(s);
                best = cost;
            }
        }
        a.source = "auto";
    }
    const UniformGrid* grid = gridOf(a.structure);
    a.gridResolution = grid ? grid->resolution : gridResolution(scene, options.grid);
    return a;
}

std::unique_ptr<CpuAccelerator> makeCpuAccelerator(const Scene& scene, const Acceleration& accel) {
    return accel.structure->cpu(scene);
}

}  // namespace gpurt
