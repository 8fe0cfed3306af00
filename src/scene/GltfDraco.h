// KHR_draco_mesh_compression for the glTF reader (GltfLoader.cpp): a primitive's Draco-compressed
// buffer view decoded by Google's Draco library (Debian libdraco-dev) into the values its
// accessors would have held.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "image/InputError.h"

namespace gpurt {

// tinygltf refuses a primitive whose indices accessor has no buffer view, and that is what a
// Draco-compressed primitive has (its indices are the decoded faces). Returns the file's bytes
// (JSON or GLB) with "indices" taken out of every primitive that has KHR_draco_mesh_compression,
// or the bytes unchanged when no primitive has it or they are not JSON this can read (tinygltf
// then says what is wrong with them).
std::string withoutDracoIndices(const std::string& bytes);

// One decoded attribute: `components` values per point, point after point, as read from the
// Draco data (integers as they are, not normalised).
struct DracoAttribute {
    int components = 0;
    bool integer = false;  // stored as integers (so that an accessor's `normalized` applies)
    std::vector<double> values;
};

// A decoded Draco mesh: its points, its faces as indices (three per triangle, each below
// `points`), and its attributes by their unique id (the ids KHR_draco_mesh_compression names).
struct DracoMesh {
    size_t points = 0;
    std::vector<uint32_t> indices;
    std::map<int, DracoAttribute> attributes;
};

// Decodes `size` bytes of Draco mesh data. Damaged data, a point cloud instead of a mesh, or more
// points than `maxPoints` throw InputError "FILE: AT: Draco data ...".
DracoMesh decodeDracoMesh(const unsigned char* data, size_t size, uint64_t maxPoints,
                          const FileLoc& file, const std::string& at);

}  // namespace gpurt
