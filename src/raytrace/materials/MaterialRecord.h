// The material seam on the CPU: a hit's material record (glsl/common/material.h), what the
// kernels' fetchMaterialRecord (glsl/scene/shading.glsl) reads from the material texels.
#pragma once

#include <cstdint>

#include "raytrace/common/RayMath.h"
#include "scene/Scene.h"

namespace gpurt {

// The record of triangle `prim`'s material at barycentrics (u, v): its fields, the diffuse colour
// textured there and times its vertex colour.
raymath::MaterialRecord materialRecord(const Scene& scene, uint32_t prim, float u, float v);
// Material m's record without its texture (kd is its diffuse factor): for questions no texture
// changes (materialSpawns, materialSplits).
raymath::MaterialRecord materialRecord(const Material& m);

}  // namespace gpurt
