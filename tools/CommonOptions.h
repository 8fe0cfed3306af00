// Options shared by the subcommands that make a GL context: --gl egl|osmesa and --glsl-dir.
#pragma once

#include "stream/GLContext.h"
#include "stream/ShaderLibrary.h"

#include <CLI/CLI.hpp>

#include <string>

namespace gpurt {

struct ContextOptions {
    std::string gl = "egl";
    std::string glslDir;

    GLContext makeContext() const {
        GLBackend backend = GLBackend::Egl;
        parseGLBackend(gl, backend);
        if (!glslDir.empty()) ShaderLibrary::global().setDirectory(glslDir);
        return GLContext(backend);
    }
};

inline void addContextOptions(CLI::App& cmd, ContextOptions& options) {
    cmd.add_option("--gl", options.gl, "OpenGL context: egl (headless EGL, default) or osmesa")
        ->check(CLI::IsMember({"egl", "osmesa"}));
    cmd.add_option("--glsl-dir", options.glslDir,
                   "Load GLSL kernels from this folder instead of the embedded copies")
        ->check(CLI::ExistingDirectory);
}

}  // namespace gpurt
