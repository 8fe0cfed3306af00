// A headless desktop OpenGL 4.5 core context, current on the calling thread for its lifetime.
//
// EGL (default): a hardware EGL device where there is one (EGL_EXT_platform_device, e.g. an
// NVIDIA GPU), else Mesa's surfaceless platform (EGL_MESA_platform_surfaceless, llvmpipe without a
// GPU), else any EGL device (Mesa's software device). GPURT_EGL_PLATFORM=surfaceless|device forces
// one. OSMesa is the alternative. Surfaceless contexts have no default framebuffer: everything
// renders into FBOs.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace gpurt {

enum class GLBackend { Egl, OSMesa };

// Parses "egl" / "osmesa"; returns false for anything else.
bool parseGLBackend(const std::string& text, GLBackend& backend);

class GLContext {
  public:
    // Creates the context and makes it current; throws EnvironmentError with one line saying why
    // when no 4.5 core context can be made.
    explicit GLContext(GLBackend backend = GLBackend::Egl);
    ~GLContext();
    GLContext(const GLContext&) = delete;
    GLContext& operator=(const GLContext&) = delete;
    GLContext(GLContext&&) noexcept;
    GLContext& operator=(GLContext&&) noexcept;

    // How the context was made: "EGL surfaceless", "EGL device", "OSMesa".
    const std::string& platform() const;

    struct Impl;  // EGL or OSMesa handles (GLContext.cpp)

  private:
    std::unique_ptr<Impl> impl_;
};

// GL_VENDOR, GL_RENDERER, GL_VERSION and the limits gpurt relies on, as (name, value) rows.
std::vector<std::pair<std::string, std::string>> glInfo();

// True when the renderer is a software rasterizer (llvmpipe, softpipe, swrast).
bool isSoftwareRenderer();

}  // namespace gpurt
