#include "stream/GLContext.h"

#include "stream/GL.h"
#include "stream/StreamErrors.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/osmesa.h>

#include <array>
#include <cstdlib>
#include <cstring>

namespace gpurt {

bool parseGLBackend(const std::string& text, GLBackend& backend) {
    if (text == "egl") {
        backend = GLBackend::Egl;
        return true;
    }
    if (text == "osmesa") {
        backend = GLBackend::OSMesa;
        return true;
    }
    return false;
}

struct GLContext::Impl {
    std::string platform;
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext eglContext = EGL_NO_CONTEXT;
    OSMesaContext osmesaContext = nullptr;
    std::array<unsigned char, 4> osmesaPixel{};  // OSMesa needs a buffer to be made current

    // Releases the EGL context and display, if any (also between attempts at creation).
    void releaseEgl() {
        if (eglContext != EGL_NO_CONTEXT) {
            eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(display, eglContext);
        }
        if (display != EGL_NO_DISPLAY) eglTerminate(display);
        eglContext = EGL_NO_CONTEXT;
        display = EGL_NO_DISPLAY;
    }

    ~Impl() {
        releaseEgl();
        if (osmesaContext) OSMesaDestroyContext(osmesaContext);
    }
};

namespace {

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    const size_t n = std::strlen(name);
    for (const char* p = std::strstr(list, name); p; p = std::strstr(p + n, name)) {
        const bool startOk = p == list || p[-1] == ' ';
        const bool endOk = p[n] == ' ' || p[n] == '\0';
        if (startOk && endOk) return true;
    }
    return false;
}

const char* eglErrorName(EGLint e) {
    switch (e) {
        case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
        case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
        case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
        default: return "EGL error";
    }
}

// Initializes `display`, binds desktop GL and creates a current 4.5 core context on it.
// Returns an empty string on success, else why it failed.
std::string makeEglContext(GLContext::Impl& impl, EGLDisplay display) {
    EGLint major = 0, minor = 0;
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor))
        return std::string("eglInitialize failed (") + eglErrorName(eglGetError()) + ")";
    impl.display = display;
    if (!eglBindAPI(EGL_OPENGL_API)) return "eglBindAPI(EGL_OPENGL_API) failed";

    const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
    EGLConfig config = nullptr;
    if (!hasExtension(extensions, "EGL_KHR_no_config_context")) {
        const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0,
                                        EGL_NONE};
        EGLint count = 0;
        if (!eglChooseConfig(display, configAttribs, &config, 1, &count) || count == 0)
            return "no EGL config renders desktop OpenGL";
    }
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    impl.eglContext = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttribs);
    if (impl.eglContext == EGL_NO_CONTEXT)
        return std::string("no OpenGL 4.5 core context (") + eglErrorName(eglGetError()) + ")";
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl.eglContext))
        return std::string("eglMakeCurrent without a surface failed (") +
               eglErrorName(eglGetError()) + ")";
    if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(eglGetProcAddress)))
        return "loading OpenGL 4.5 functions failed";
    return {};
}

void createEgl(GLContext::Impl& impl) {
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!clientExtensions)
        throw EnvironmentError("EGL: no client extensions (is libegl1 with a vendor library installed?)");
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    auto queryDevices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto queryDeviceString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
        eglGetProcAddress("eglQueryDeviceStringEXT"));
    if (!getPlatformDisplay)
        throw EnvironmentError("EGL: eglGetPlatformDisplayEXT is missing");

    const char* forced = std::getenv("GPURT_EGL_PLATFORM");
    const std::string force = forced ? forced : "";
    const bool canSurfaceless = hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless") &&
                                force != "device";
    const bool canDevice = hasExtension(clientExtensions, "EGL_EXT_platform_device") &&
                           queryDevices && force != "surfaceless";

    // Hardware devices first, software (Mesa's swrast device) last.
    std::vector<EGLDeviceEXT> hardware, software;
    if (canDevice) {
        std::array<EGLDeviceEXT, 16> devices{};
        EGLint count = 0;
        if (queryDevices(EGLint(devices.size()), devices.data(), &count)) {
            for (EGLint i = 0; i < count; ++i) {
                const char* ext = queryDeviceString ? queryDeviceString(devices[i], EGL_EXTENSIONS)
                                                    : nullptr;
                (hasExtension(ext, "EGL_MESA_device_software") ? software : hardware)
                    .push_back(devices[i]);
            }
        }
    }

    std::string why;
    auto tryDevice = [&](EGLDeviceEXT device) {
        const std::string error = makeEglContext(
            impl, getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, device, nullptr));
        if (error.empty()) {
            impl.platform = "EGL device";
            return true;
        }
        why += (why.empty() ? "" : "; ") + std::string("device: ") + error;
        impl.releaseEgl();
        return false;
    };
    for (EGLDeviceEXT device : hardware)
        if (tryDevice(device)) return;
    if (canSurfaceless) {
        const std::string error = makeEglContext(
            impl, getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
        if (error.empty()) {
            impl.platform = "EGL surfaceless";
            return;
        }
        why += (why.empty() ? "" : "; ") + std::string("surfaceless: ") + error;
        impl.releaseEgl();
    }
    for (EGLDeviceEXT device : software)
        if (tryDevice(device)) return;
    if (why.empty()) why = "neither EGL_MESA_platform_surfaceless nor an EGL device is available";
    throw EnvironmentError("no headless OpenGL 4.5 core context through EGL: " + why);
}

void createOSMesa(GLContext::Impl& impl) {
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
                           OSMESA_ACCUM_BITS, 0, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    impl.osmesaContext = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!impl.osmesaContext) throw EnvironmentError("OSMesa: no OpenGL 4.5 core context");
    if (!OSMesaMakeCurrent(impl.osmesaContext, impl.osmesaPixel.data(), GL_UNSIGNED_BYTE, 1, 1))
        throw EnvironmentError("OSMesa: OSMesaMakeCurrent failed");
    if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(OSMesaGetProcAddress)))
        throw EnvironmentError("OSMesa: loading OpenGL 4.5 functions failed");
    impl.platform = "OSMesa";
}

}  // namespace

GLContext::GLContext(GLBackend backend) : impl_(std::make_unique<Impl>()) {
    if (backend == GLBackend::Egl)
        createEgl(*impl_);
    else
        createOSMesa(*impl_);
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 45)
        throw EnvironmentError("OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
                               " context; gpurt needs 4.5 core");
}

GLContext::~GLContext() = default;
GLContext::GLContext(GLContext&&) noexcept = default;
GLContext& GLContext::operator=(GLContext&&) noexcept = default;

const std::string& GLContext::platform() const { return impl_->platform; }

std::vector<std::pair<std::string, std::string>> glInfo() {
    std::vector<std::pair<std::string, std::string>> rows;
    auto str = [](GLenum e) {
        const auto* s = reinterpret_cast<const char*>(glGetString(e));
        return std::string(s ? s : "?");
    };
    auto integer = [](GLenum e) {
        GLint64 v = 0;
        glGetInteger64v(e, &v);
        return std::to_string(v);
    };
    rows.emplace_back("vendor", str(GL_VENDOR));
    rows.emplace_back("renderer", str(GL_RENDERER));
    rows.emplace_back("version", str(GL_VERSION));
    rows.emplace_back("glsl", str(GL_SHADING_LANGUAGE_VERSION));
    rows.emplace_back("max_texture_size", integer(GL_MAX_TEXTURE_SIZE));
    GLint viewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    rows.emplace_back("max_viewport_dims",
                      std::to_string(viewport[0]) + "x" + std::to_string(viewport[1]));
    rows.emplace_back("max_draw_buffers", integer(GL_MAX_DRAW_BUFFERS));
    rows.emplace_back("max_color_attachments", integer(GL_MAX_COLOR_ATTACHMENTS));
    rows.emplace_back("max_fragment_texture_units", integer(GL_MAX_TEXTURE_IMAGE_UNITS));
    rows.emplace_back("max_uniform_block_size", integer(GL_MAX_UNIFORM_BLOCK_SIZE));
    rows.emplace_back("max_fragment_uniform_components", integer(GL_MAX_FRAGMENT_UNIFORM_COMPONENTS));
    rows.emplace_back("max_shader_storage_block_size", integer(GL_MAX_SHADER_STORAGE_BLOCK_SIZE));
    GLint bits = 0;
    glGetQueryiv(GL_SAMPLES_PASSED, GL_QUERY_COUNTER_BITS, &bits);
    rows.emplace_back("samples_passed_counter_bits", std::to_string(bits));
    glGetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &bits);
    rows.emplace_back("time_elapsed_counter_bits", std::to_string(bits));
    return rows;
}

bool isSoftwareRenderer() {
    const auto* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string renderer = r ? r : "";
    return renderer.find("llvmpipe") != std::string::npos ||
           renderer.find("softpipe") != std::string::npos ||
           renderer.find("swrast") != std::string::npos;
}

}  // namespace gpurt
