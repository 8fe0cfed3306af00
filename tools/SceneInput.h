// Scene loading for the commands (until the content-sniffing SceneLoader lands: OBJ only).
#pragma once

#include "raytrace/ObjLoader.h"
#include "raytrace/Scene.h"

#include <glm/glm.hpp>

#include <filesystem>
#include <optional>

namespace gpurt {

struct LoadedScene {
    Scene scene;
    std::optional<glm::ivec2> size;
};
inline LoadedScene loadSceneFile(const std::filesystem::path& path) { return {loadObj(path), {}}; }

}  // namespace gpurt
