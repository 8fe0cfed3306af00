// The uniform grid as a registered accelerator (accel/Accelerator.h): its structure, and the
// grid inside one.
#pragma once

#include <memory>

#include "raytrace/accel/Accelerator.h"
#include "raytrace/accel/grid/UniformGrid.h"

namespace gpurt {

// The grid as a structure of the registry.
std::shared_ptr<const AccelStructure> makeStructure(UniformGrid grid);

// The grid of a structure, or null when it is another accelerator's (or none).
const UniformGrid* gridOf(const AccelStructure* structure);
inline const UniformGrid* gridOf(const std::shared_ptr<const AccelStructure>& structure) {
    return gridOf(structure.get());
}

}  // namespace gpurt
