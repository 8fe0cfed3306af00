// The material seam on the CPU: a hit's material record (glsl/common/material.h), what the
// kernels' fetchMaterialRecord (glsl/trace/shading.glsl) reads from the material texels.
#pragma once

#include <cstdint>

#include "raytrace/RayMath.h"
#include "scene/Scene.h"

namespace gpurt {

// The record of triangle `prim`'s material at barycentrics (u, v): its fields, the diffuse colour
// textured there.
raymath::MaterialRecord materialRecord(const Scene& scene, uint32_t prim, float u, float v);

}  // namespace gpurt
