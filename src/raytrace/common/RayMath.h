// The ray math of glsl/common/raymath.h (and the sampling of sampling.h) for C++: the same source, compiled with GLM's GLSL-like
// types, so that the CPU backend and the kernels evaluate identical float operations.
#pragma once

#include <glm/glm.hpp>

namespace gpurt::raymath {
using namespace glm;
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
