// The ray sets of gpurt bench, the same for every backend: primary rays (one per pixel, the
// contract camera) and shadow rays (one per primary hit, towards one point light, packed so that
// the live rays are contiguous).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "raytrace/camera/Camera.h"
#include "raytrace/common/RenderTypes.h"
#include "scene/Scene.h"
#include "raytrace/accel/grid/UniformGrid.h"

namespace gpurt {

// One ray per pixel of `camera`, row 0 = the top row, tLimit = GPURT_FAR.
RayStream primaryRays(const CameraBasis& camera);

// For each primary hit (hits[i].w >= 0, in pixel order), the renderer's shadow ray towards
// `light`: from the hit point offset along the normal that faces the primary ray, limited to the
// light's distance. Laid out `width` rays a row; unused elements of the last row carry no ray.
// Where the shadow rays of gpurt bench go: the scene's first point light, or the headlight at the
// eye (lightsOrHeadlight), or the eye for a scene lit only by its emitters or background.
glm::vec3 shadowRayTarget(const Scene& scene, glm::vec3 eye);

RayStream shadowRays(const Scene& scene, float rayOffset, const RayStream& primary,
                     const std::vector<glm::vec4>& hits, glm::vec3 light);

}  // namespace gpurt
