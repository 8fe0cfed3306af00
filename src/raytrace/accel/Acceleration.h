// The acceleration structure a render traces, chosen per scene among the registered accelerators
// (accel/Accelerator.h: the uniform grid, the design's reference, and the BVH), built or read from
// a packed file, and with `auto` the one an estimate made at build time says is cheaper
// (chooseAcceleration).
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "raytrace/accel/Accelerator.h"
#include "raytrace/camera/Camera.h"
#include "scene/Scene.h"

namespace gpurt {

struct Acceleration {
    std::shared_ptr<const AccelStructure> structure;
    // Set when auto chose: each accelerator's estimated cost of a ray (accel/Acceleration.cpp says
    // how), in the time of one triangle test, in registry order.
    std::vector<std::pair<std::string, double>> estimate;
    // The grid's resolution, or the one it would have (--stats reports it for every structure).
    glm::ivec3 gridResolution{1};
    // "built", "packed" (a packed scene's own structure) or "auto" (built, then chosen).
    std::string source = "built";

    const AcceleratorInfo& accelerator() const { return structure->accelerator(); }
    std::string_view name() const { return accelerator().name; }
    // How far secondary rays start off a surface.
    float rayOffset() const { return structure->rayOffset(); }
};

// The estimated cost of a ray through `structure`: the primary rays of a 64 x 64 image of
// `camera`'s view (the whole image, whatever its tile) traced on the CPU, each visit of a cell or
// node weighed by its accelerator's visitCost and each triangle test by 1. Deterministic: counts,
// not timings.
double estimateCost(const Scene& scene, const AccelStructure& structure, const CameraBasis& camera);

// The structure for `choice` (an accelerator's name or "auto"; InputError for another): `packed`
// (a packed scene's) where it is of the kind asked and its accelerator's reuse keeps it, built
// otherwise; for auto every accelerator's (a packed one stands alone), and the cheapest by
// estimateCost kept. Camera: as above.
Acceleration chooseAcceleration(const Scene& scene, std::string_view choice, std::shared_ptr<const AccelStructure> packed,
                                const AccelOptions& options, const CameraBasis& camera);

// The cpu backend's accelerator over `accel`'s structure, which must outlive it.
std::unique_ptr<CpuAccelerator> makeCpuAccelerator(const Scene& scene, const Acceleration& accel);

}  // namespace gpurt
