#include "stream/GL.h"

#include "stream/StreamErrors.h"

#include <string>

namespace gpurt {

namespace {
const char* errorName(GLenum e) {
    switch (e) {
        case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
        case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
        case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
        default: return "unknown GL error";
    }
}
}  // namespace

void checkGLError(const char* what) {
    std::string errors;
    for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
        if (!errors.empty()) errors += ", ";
        errors += errorName(e);
    }
    if (errors.empty()) return;
    std::string message = std::string(what) + ": " + errors;
    if (errors.find("GL_OUT_OF_MEMORY") != std::string::npos) throw EnvironmentError(message);
    throw UsageError(message);
}

}  // namespace gpurt
