// `gpurt view SCENE`: the scene in a window (GLFW), rendered by the same GpuTracer kernel chain as
// `gpurt render`, progressively: while the camera is still each frame adds one sample per pixel to
// the pixels' sums and a present pass (glsl/view/present.frag) shows their mean, tone mapped as
// the PNG is, or an AOV in false colour. No image passes through the CPU per frame. Controls:
// CONTRACT.md, "Viewer"; README.
#include "Commands.h"
#include "CommonOptions.h"

#include "image/AtomicFile.h"
#include "raytrace/GpuPipeline.h"
#include "raytrace/GpuTracer.h"
#include "image/ImageIO.h"
#include "raytrace/SceneScale.h"
#include "scene/SmoothNormals.h"
#include "stream/GLWindow.h"
#include "stream/KernelStats.h"
#include "stream/StreamErrors.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

namespace gpurt {

namespace {

struct ViewOptions {
    std::string scene;
    TracerCliOptions tracer;
    GridCliOptions grid;
    CameraOptions camera;
    PictureCliOptions picture;
    int bounces = -1;
    int frames = 0;
    std::string screenshot;
    bool bench = false;
    std::string glslDir;
};

constexpr int kBenchFrames = 30;
const char* const kModeNames[] = {"shaded", "depth", "normal", "prim", "steps"};

glm::vec3 rotate(glm::vec3 v, glm::vec3 axis, float radians) {
    return glm::vec3(glm::rotate(glm::mat4(1.0f), radians, axis) * glm::vec4(v, 0.0f));
}

// The camera a user steers: orbit about the target, pan, zoom and fly (CONTRACT.md, "Viewer").
struct CameraControl {
    CameraSpec spec, initial;
    float step;  // fly distance per key press: 2% of the scene's diagonal
    bool orbiting = false, panning = false;
    double lastX = 0, lastY = 0;

    // Returns whether the camera changed.
    bool handle(const WindowEvent& e, int height) {
        const glm::vec3 forward = glm::normalize(spec.target - spec.eye);
        const glm::vec3 right = glm::normalize(glm::cross(forward, spec.up));
        const glm::vec3 upOrtho = glm::cross(right, forward);
        switch (e.type) {
            case WindowEvent::MouseButton:
                if (e.key == GLFW_MOUSE_BUTTON_LEFT) orbiting = e.press;
                if (e.key == GLFW_MOUSE_BUTTON_RIGHT) panning = e.press;
                return false;
            case WindowEvent::CursorMove: {
                const double dx = e.x - lastX, dy = e.y - lastY;
                lastX = e.x;
                lastY = e.y;
                if (orbiting && (dx != 0 || dy != 0)) {
                    glm::vec3 offset = spec.eye - spec.target;
                    offset = rotate(offset, glm::normalize(spec.up), float(-dx) * 0.01f);
                    const glm::vec3 pitched = rotate(offset, right, float(-dy) * 0.01f);
                    // Not over the pole: the view direction must not turn parallel to up.
                    if (std::fabs(glm::dot(glm::normalize(pitched), glm::normalize(spec.up))) < 0.995f) offset = pitched;
                    spec.eye = spec.target + offset;
                    return true;
                }
                if (panning && (dx != 0 || dy != 0)) {
                    const float perPixel = glm::length(spec.target - spec.eye) * 2.0f *
                                           std::tan(spec.fovy * float(M_PI) / 360.0f) / float(std::max(1, height));
                    const glm::vec3 move = (float(-dx) * right + float(dy) * upOrtho) * perPixel;
                    spec.eye += move;
                    spec.target += move;
                    return true;
                }
                return false;
            }
            case WindowEvent::Scroll: {
                if (e.y == 0) return false;
                const glm::vec3 offset = spec.eye - spec.target;
                spec.eye = spec.target + offset * std::pow(0.9f, float(e.y));
                return true;
            }
            case WindowEvent::Key: {
                if (!e.press) return false;
                glm::vec3 move(0.0f);
                if (e.key == GLFW_KEY_W) move = forward;
                if (e.key == GLFW_KEY_S) move = -forward;
                if (e.key == GLFW_KEY_D) move = right;
                if (e.key == GLFW_KEY_A) move = -right;
                if (e.key == GLFW_KEY_E) move = upOrtho;
                if (e.key == GLFW_KEY_Q) move = -upOrtho;
                if (e.key == GLFW_KEY_R) {
                    spec = initial;
                    return true;
                }
                if (move == glm::vec3(0.0f)) return false;
                spec.eye += move * step;
                spec.target += move * step;
                return true;
            }
            default: return false;
        }
    }
};

std::string formatFloat(float v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", double(v));
    return text;
}

// A point of the rescaled scene in the scene file's units (SceneScale.h: exact).
glm::vec3 unscaled(glm::vec3 p, int exponent) {
    return {std::ldexp(p.x, exponent), std::ldexp(p.y, exponent), std::ldexp(p.z, exponent)};
}

std::string formatVec3(glm::vec3 v) { return formatFloat(v.x) + "," + formatFloat(v.y) + "," + formatFloat(v.z); }

int runView(const ViewOptions& o) {
    // Everything that can be refused is checked before a window opens.
    const PictureCliOptions::Values picture = o.picture.values();
    if (!o.screenshot.empty()) checkOutputPaths({o.screenshot});
    const GpuTracerOptions tracerOptions = o.tracer.options();
    int scaleExponent = 0;
    LoadedScene loaded = loadSceneToRender(o.scene, picture.crease, scaleExponent);
    const Scene& scene = loaded.scene;
    const glm::ivec2 size = o.camera.imageSize(loaded.size);
    checkRenderFitsInMemory(size, true, picture.integrator == Integrator::Path);
    CameraControl control;
    control.spec = control.initial = o.camera.spec(scene, size, scaleExponent);
    makeCamera(control.spec, size.x, size.y);  // refuses an unusable camera now
    const Bounds bounds = scene.bounds();
    const float diagonal = bounds.empty() ? 1.0f : 2.0f * glm::length(bounds.halfExtent());
    control.step = 0.02f * (diagonal > 0.0f ? diagonal : 1.0f);
    RenderSettings settings;
    settings.maxBounces = PictureCliOptions::bounces(o.bounces, scene, picture.integrator);
    settings.integrator = picture.integrator;
    settings.seed = picture.seed;
    // Samples of one camera: --spp, else --frames (so that N frames are N samples, as render
    // --spp N), else 256; --bench: one a frame for all its frames.
    const bool sppGiven = o.picture.sppOption && o.picture.sppOption->count() > 0;
    const int frames = o.bench ? kBenchFrames + 1 : o.frames;
    const uint32_t samples = sppGiven ? picture.samples : frames > 0 ? uint32_t(frames) : 256u;
    const std::optional<UniformGrid> built = o.grid.build(loaded);
    const UniformGrid& grid = built ? *built : *loaded.grid;

    std::unique_ptr<GLWindow> window;
    try {
        window = std::make_unique<GLWindow>(size.x, size.y, "gpurt view");
    } catch (const EnvironmentError& e) {
        throw EnvironmentError(std::string("view: ") + e.what() + "; gpurt render writes the picture to a file instead");
    }
    if (!o.glslDir.empty()) ShaderLibrary::global().setDirectory(o.glslDir);
    GpuTracer tracer(scene, grid, tracerOptions);
    const int toneMapMode = toneMapCode(picture.colour.toneMap);
    const float exposure = exposureScale(picture.colour.exposure);

    int width = window->width(), height = window->height();
    std::unique_ptr<GPUKernel> present;
    glm::ivec2 presentSize(0);
    uint32_t done = 0;
    int mode = 0, frame = 0, screenshots = 0;
    bool dirty = true;
    glm::vec2 depthRange(0.0f, 1.0f);
    auto show = [&] {
        present->setScreenTarget(width, height)
            .setUniform("mode", mode)
            .setUniform("samples", float(std::max(1u, done)))
            .setUniform("exposureScale", exposure)
            .setUniform("toneMapMode", toneMapMode)
            .setUniform("depthRange", depthRange)
            .dispatch();
    };
    auto writeScreenshot = [&](const std::string& path) {
        writePngRgb8(path, width, height, window->readPixels());
    };
    // A new camera or size: the pixel centres' AOVs, and the sample sums start again.
    auto restart = [&] {
        const CameraBasis camera = makeCamera(control.spec, width, height);
        settings.width = width;
        settings.height = height;
        GpuPipeline& p = tracer.beginProgressive(camera, settings);
        // New streams (first frame, resize; a new pipeline may reuse the old one's address): a
        // new present pass.
        if (!present || presentSize != glm::ivec2(width, height)) {
            presentSize = glm::ivec2(width, height);
            present = std::make_unique<GPUKernel>("present", "view/present.frag");
            present->addInput(p.sampleSum, "sampleSum").addInput(p.aovHit, "aovHit");
            present->addInput(p.aovCells, "aovCells").addInput(p.aovNormal, "aovNormal");
        }
        const float dist = glm::length(control.spec.eye - bounds.center());
        const float radius = bounds.empty() ? 1.0f : glm::length(bounds.halfExtent());
        depthRange = glm::vec2(std::max(0.0f, dist - radius), dist + radius);
        done = 0;
        dirty = false;
    };
    const auto started = std::chrono::steady_clock::now();
    auto benchStart = started;
    uint64_t benchRays = 0;
    auto lastTitle = started;
    int titleFrames = 0;
    while (!window->closeRequested()) {
        window->pollEvents();
        bool screenshotNow = false;
        for (const WindowEvent& e : window->events()) {
            if (e.type == WindowEvent::Resize && e.x > 0 && e.y > 0) {
                width = int(e.x);
                height = int(e.y);
                dirty = true;
            } else if (e.type == WindowEvent::Key && e.press && e.key >= GLFW_KEY_1 && e.key <= GLFW_KEY_5) {
                mode = e.key - GLFW_KEY_1;
            } else if (e.type == WindowEvent::Key && e.press && e.key == GLFW_KEY_ESCAPE) {
                window->requestClose();
            } else if (e.type == WindowEvent::Key && e.press && e.key == GLFW_KEY_P) {
                screenshotNow = true;
            } else {
                const CameraSpec before = control.spec;
                if (control.handle(e, height)) {
                    try {
                        makeCamera(control.spec, width, height);
                        dirty = true;
                    } catch (const InputError&) {
                        control.spec = before;  // a move that would break the camera is ignored
                    }
                }
            }
        }
        if (window->closeRequested()) break;
        if (dirty) restart();
        if (done < samples) tracer.addSample(done++, samples);
        show();
        if (screenshotNow) {
            const std::string path = !o.screenshot.empty() ? o.screenshot : [&] {
                char name[32];
                std::snprintf(name, sizeof name, "gpurt-view-%04d.png", screenshots++);
                return std::string(name);
            }();
            writeScreenshot(path);
            std::fprintf(stderr, "gpurt: screenshot %s\n", path.c_str());
        }
        window->swapBuffers();
        ++frame;
        ++titleFrames;
        if (o.bench && frame == 1) {  // the first frame compiles the kernels: not timed
            glFinish();
            benchStart = std::chrono::steady_clock::now();
            benchRays = tracer.progressiveStats().primaryRays + tracer.progressiveStats().shadowRays +
                        tracer.progressiveStats().secondaryRays;
        }
        const auto now = std::chrono::steady_clock::now();
        const double sinceTitle = std::chrono::duration<double>(now - lastTitle).count();
        if (sinceTitle >= 0.5) {
            const RenderStats& s = tracer.progressiveStats();
            static uint64_t raysBefore = 0;
            const uint64_t rays = s.primaryRays + s.shadowRays + s.secondaryRays;
            char title[160];
            std::snprintf(title, sizeof title, "gpurt view: %.1f fps, %.0f ms/frame, %.1f Mrays/s, %u/%u samples, %s",
                          titleFrames / sinceTitle, 1e3 * sinceTitle / titleFrames,
                          double(rays - raysBefore) / sinceTitle * 1e-6, done, samples, kModeNames[mode]);
            window->setTitle(title);
            raysBefore = rays;
            lastTitle = now;
            titleFrames = 0;
        }
        if (frames > 0 && frame >= frames) break;
    }
    if (present) {
        // The camera of the last events (closing with them unrendered would show the old one).
        if (dirty) {
            restart();
            tracer.addSample(done++, samples);
        }
        show();  // the last frame again into the back buffer, for the screenshot
        if (!o.screenshot.empty()) writeScreenshot(o.screenshot);
    }
    if (o.bench) {
        glFinish();
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - benchStart).count();
        const RenderStats& s = tracer.progressiveStats();
        const uint64_t rays = s.primaryRays + s.shadowRays + s.secondaryRays - benchRays;
        nlohmann::json j;
        j["fps"] = double(frame - 1) / seconds;
        j["ms_per_frame"] = 1e3 * seconds / double(frame - 1);
        j["mrays_per_s"] = double(rays) / seconds * 1e-6;
        j["width"] = width;
        j["height"] = height;
        j["frames"] = frame - 1;
        j["renderer"] = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        std::printf("%s\n", j.dump().c_str());
    }
    // The camera in use, as options of gpurt render (in the scene file's units).
    std::printf("--eye %s --target %s --up %s --fovy %s --size %dx%d\n",
                formatVec3(unscaled(control.spec.eye, scaleExponent)).c_str(),
                formatVec3(unscaled(control.spec.target, scaleExponent)).c_str(),
                formatVec3(control.spec.up).c_str(), formatFloat(control.spec.fovy).c_str(), width, height);
    return 0;
}

}  // namespace

void addViewCommand(CLI::App& app, std::function<int()>& run) {
    auto o = std::make_shared<ViewOptions>();
    auto* cmd = app.add_subcommand("view", "Explore a scene in a window, rendered progressively by the stream kernels");
    cmd->add_option("scene", o->scene, "Scene file")->required()->check(kNotEmpty);
    cmd->add_option("--frames", o->frames, "Render this many frames, then close (the samples of a still camera)")
        ->check(CLI::Range(1, 1 << 24));
    cmd->add_option("--screenshot", o->screenshot, "Write the last frame to this PNG on closing (and on P)")
        ->check(kNotEmpty);
    cmd->add_flag("--bench", o->bench, "Render a fixed number of frames and print one JSON object (fps, ...)");
    cmd->add_option("--bounces", o->bounces, "Whitted: mirror and glass levels (default: the scene's, 3); path: the longest path in hits (default " + std::to_string(kDefaultPathBounces) + ")")->check(CLI::Range(0, 64));
    cmd->add_option("--glsl-dir", o->glslDir, "Load GLSL kernels from this folder instead of the embedded copies")
        ->check(CLI::ExistingDirectory);
    o->picture.add(*cmd);
    o->tracer.add(*cmd);
    o->grid.add(*cmd);
    o->camera.add(*cmd);
    cmd->callback([&run, o] { run = [o] { return runView(*o); }; });
}

}  // namespace gpurt
