// The ray math of glsl/common/raymath.h for C++: the same source, compiled with GLM's GLSL-like
// types, so that the CPU backend and the kernels evaluate identical float operations.
#pragma once

#include <glm/glm.hpp>

namespace gpurt::raymath {
using namespace glm;
#include "../../glsl/common/raymath.h"
}  // namespace gpurt::raymath
