// The acceleration structure a render traces, chosen per scene: the uniform grid (the design's
// reference, accel/grid/) or the BVH (accel/bvh/), built or read from a packed file, and with
// `auto` the one an estimate made at build time says is cheaper (chooseAcceleration).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "raytrace/camera/Camera.h"
#include "raytrace/accel/CpuAccelerator.h"
#include "raytrace/accel/bvh/Bvh.h"
#include "raytrace/accel/grid/UniformGrid.h"
#include "scene/Scene.h"

namespace gpurt {

enum class AccelKind { Grid, Bvh };
enum class AccelChoice { Grid, Bvh, Auto };

const char* accelName(AccelKind kind);  // "grid", "bvh"
// "grid", "bvh" or "auto"; false for anything else.
bool parseAccelChoice(const std::string& text, AccelChoice& choice);

// What `auto` measured: the estimated cost of a ray through each structure (accel/Acceleration.cpp
// says how), in the time of one triangle test.
struct AccelEstimate {
    double grid = 0, bvh = 0;
};

struct Acceleration {
    AccelKind kind = AccelKind::Grid;
    std::optional<UniformGrid> grid;  // set when kind is Grid (or auto built both)
    std::optional<Bvh> bvh;           // set when kind is Bvh (or auto built both)
    std::optional<AccelEstimate> estimate;  // set when auto chose
    // The grid's resolution, or the one it would have (--stats reports it for either structure).
    glm::ivec3 gridResolution{1};
    // "built", "packed" (a packed scene's own structure) or "auto" (built, then chosen).
    std::string source = "built";

    // How far secondary rays start off a surface (the same for both structures).
    float rayOffset() const;
};

// The estimated cost of a ray through each of the two structures: the primary rays of a 64 x 64
// image of `camera`'s view (the whole image, whatever its tile) traced on the CPU, each visit of a grid cell
// or a BVH node and each triangle test weighed by its cost on the gl backend (measured on
// llvmpipe, docs/PERFORMANCE.md). Deterministic: counts, not timings.
AccelEstimate estimateAccelerators(const Scene& scene, const UniformGrid& grid, const Bvh& bvh,
                                   const CameraBasis& camera);

// The structure for `choice`: the given ones where they are of the right kind (a packed scene's),
// built otherwise; for Auto both, and the cheaper kept (the estimate says). Camera: as above.
Acceleration chooseAcceleration(const Scene& scene, AccelChoice choice, std::optional<UniformGrid> grid,
                                std::optional<Bvh> bvh, const GridOptions& gridOptions,
                                const CameraBasis& camera);

// The cpu backend's accelerator over `accel`'s structure, which must outlive it.
std::unique_ptr<CpuAccelerator> makeCpuAccelerator(const Scene& scene, const Acceleration& accel);

}  // namespace gpurt
