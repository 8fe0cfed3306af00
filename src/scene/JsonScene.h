// JSON scene files (docs/SCENE_FORMAT.md): OBJ meshes with transforms and material overrides,
// point lights, camera, background and render settings, validated strictly.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "scene/Scene.h"

namespace gpurt {

// A scene file's scene plus what it says about the image that Scene does not hold.
struct JsonSceneFile {
    Scene scene;
    std::optional<glm::ivec2> size;  // "render": {"size": [w, h]}; none when the file does not say
};

// Loads a JSON scene and the OBJ files it names (relative to the JSON file's folder). Meshes are
// numbered in list order, continuing the count (CONTRACT.md, triangle numbering). Each mesh's MTL
// materials are appended to the scene's list, or its one override material.
// Throws InputError, one line naming the file and the JSON pointer of the bad value
// ("scene.json: /lights/0/colour: unknown key"; "scene.json:3:7: syntax error ..." for bad JSON),
// for syntax errors, unknown keys, wrong types, missing keys or files, out-of-range or non-finite
// numbers and singular transforms. An error inside an OBJ file is the OBJ loader's (naming the
// OBJ).
JsonSceneFile loadJsonSceneFile(const std::filesystem::path& path);

// loadJsonSceneFile on text already in memory: `path` names the file in messages, and mesh files
// are found relative to its folder (the file itself need not exist). The fuzz target's entry
// point.
JsonSceneFile parseJsonScene(const std::string& text, const std::filesystem::path& path);

// loadJsonSceneFile(path).scene.
Scene loadJsonScene(const std::filesystem::path& path);

}  // namespace gpurt
