// glTF 2.0 scenes (.gltf with its buffers, .glb) through tinygltf (Debian libtinygltf-dev) into a
// Scene. What is used (docs/SCENE_FORMAT.md): every node of the default scene with its transform
// (matrix or TRS, through the hierarchy); triangle primitives (TRIANGLES, TRIANGLE_STRIP,
// TRIANGLE_FAN; indexed or not, every index and component type the spec and KHR_mesh_quantization
// allow, byte strides, normalized integers, sparse accessors, KHR_draco_mesh_compression),
// POSITION and NORMAL; skins at their bind pose (JOINTS_n / WEIGHTS_n); materials (pbrMetallicRoughness
// base colour factor as the diffuse colour, metallic as mirror reflectivity tinted by the base
// colour, KHR_materials_transmission with KHR_materials_ior as glass, emissiveFactor with
// KHR_materials_emissive_strength as emission); the first perspective camera met in the node order
// as the scene camera; KHR_lights_punctual point lights. Triangles are numbered as CONTRACT.md says:
// the default scene's nodes depth-first in file order (children after their parent), each mesh's
// primitives in order, each primitive's triangles in index order.
#pragma once

#include <filesystem>
#include <string>

#include "scene/Scene.h"

namespace gpurt {

// Whether the bytes start with the binary glTF magic "glTF".
bool looksLikeGlb(const std::string& head);

// Reads a .gltf (JSON) or .glb (binary, by its magic) file; external buffers are read relative to
// its folder. Throws InputError naming the file for a file that is not glTF, missing or short
// buffers, accessors outside their buffers, indices out of range, non-finite positions, damaged
// Draco data, broken skins (joints that are no node, joint indices out of range, a wrong count of
// inverseBindMatrices), node cycles. Points and lines, morph targets, animations, and extensions
// and attributes gpurt does not use are warnings naming them. The materials' texture slots are read as
// docs/SCENE_FORMAT.md says; an image that cannot be read is a warning (the material keeps its factors).
Scene loadGltf(const std::filesystem::path& path);

// loadGltf on bytes already in memory; external buffers are looked for in `folder` (the fuzz
// target's entry point).
Scene parseGltf(const std::string& bytes, const std::string& name, const std::filesystem::path& folder);

}  // namespace gpurt
