// The OpenGL API as gpurt sees it: the glad-generated 4.5 core loader, plus the error check that
// runs after every pass in debug builds.
#pragma once

#include <glad/gl.h>

namespace gpurt {

// Throws UsageError naming `what` when glGetError reports an error (drains all pending errors).
void checkGLError(const char* what);

// GPURT_CHECK_GL(what): checkGLError in debug builds, nothing in release builds.
#ifndef NDEBUG
#define GPURT_CHECK_GL(what) ::gpurt::checkGLError(what)
#else
#define GPURT_CHECK_GL(what) ((void)0)
#endif

}  // namespace gpurt
