// The box every accelerator is built in, and the ray offset that follows from it: the same for
// the grid and the BVH, so that both trace the same secondary rays and give the same images.
#pragma once

#include <utility>

#include <glm/glm.hpp>

#include "scene/Scene.h"

namespace gpurt {

// The scene's bounds, padded so that no extent is zero (a flat scene) and triangles on the
// bounds are strictly inside; -1 to 1 on every axis for a scene of nothing. Throws InputError for
// non-finite vertices.
std::pair<glm::vec3, glm::vec3> sceneBox(const Scene& scene);

// How far secondary and shadow rays start off a surface: 1e-4 * the box's largest extent.
float sceneRayOffset(glm::vec3 boxMin, glm::vec3 boxMax);

}  // namespace gpurt
