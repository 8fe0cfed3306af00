// The BVH as a registered accelerator (accel/Accelerator.h): its structure, and the tree inside
// one.
#pragma once

#include <memory>

#include "raytrace/accel/Accelerator.h"
#include "raytrace/accel/bvh/Bvh.h"

namespace gpurt {

// The tree as a structure of the registry.
std::shared_ptr<const AccelStructure> makeStructure(Bvh bvh);

// The tree of a structure, or null when it is another accelerator's (or none).
const Bvh* bvhOf(const AccelStructure* structure);
inline const Bvh* bvhOf(const std::shared_ptr<const AccelStructure>& structure) { return bvhOf(structure.get()); }

}  // namespace gpurt
