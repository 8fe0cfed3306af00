// Wavefront OBJ (+ MTL) loading into a Scene, numbered as the contract says.
#pragma once

#include <filesystem>
#include <string>

#include "scene/Scene.h"

namespace gpurt {

// Loads an OBJ file and its material libraries. Polygons become triangle fans (v0, vi, vi+1), so
// triangle k is the contract's triangle k. A material library that cannot be opened is a warning
// on stderr, and the faces get the default material.
// Throws InputError ("FILE:LINE: what is wrong") for an unreadable file, binary data, a bad or
// out-of-range index, a face with fewer than 3 vertices, a vertex with fewer than 3 coordinates,
// or a coordinate that is not a finite float.
Scene loadObj(const std::filesystem::path& path);

// loadObj on text already in memory: `path` names the file in messages, and material libraries
// are opened in its folder (the file itself need not exist). The fuzz target's entry point.
Scene parseObj(std::string text, const std::filesystem::path& path);

}  // namespace gpurt
