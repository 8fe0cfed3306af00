// The ray math of glsl/common/raymath.h (and the sampling of sampling.h) for C++: the same source, compiled with GLM's GLSL-like
// types, so that the CPU backend and the kernels evaluate identical float operations.
#pragma once

#include <glm/glm.hpp>

#include "../../../glsl/common/scene_layout.h"

namespace gpurt::raymath {
using namespace glm;
// Entry (i, j) of the sheen's albedo table (glsl/common/scene_layout.h GPURT_SHEEN_TABLE; the
// kernels read it from their sheenTable buffer): raytrace/materials/SheenTable.cpp.
float sheenAlbedoTexel(int i, int j);
#include "../../../glsl/common/raymath.h"
#include "../../../glsl/common/sampling.h"
#include "../../../glsl/common/alpha.h"
#include "../../../glsl/common/shading.h"
#include "../../../glsl/common/material.h"
#include "../../../glsl/common/path.h"
#include "../../../glsl/common/texture.h"
#include "../../../glsl/common/environment.h"
#include "../../../glsl/common/adaptive.h"
}  // namespace gpurt::raymath
