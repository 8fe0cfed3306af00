// `gpurt view SCENE`: the scene in a window (GLFW), rendered by the same gl renderer as
// `gpurt render`, progressively: while the camera is still each frame adds one sample per pixel to
// the pixels' sums and a present pass (glsl/view/present.frag) shows their mean, tone mapped as
// the PNG is, or an AOV in false colour. Under the path integrator the mean is denoised first
// (raytrace/denoise: the kernels of render --denoise over the sums; key N toggles). No image
// passes through the CPU per frame. Controls:
// CONTRACT.md, "Viewer"; README.
#include "Commands.h"
#include "CommonOptions.h"
#include "raytrace/integrators/Registry.h"

#include "image/AtomicFile.h"
#include "raytrace/render/Renderer.h"
#include "stream/GPUKernel.h"
#include "image/ImageIO.h"
#include "raytrace/scene/SceneScale.h"
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
#include <filesystem>
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
    bool noDenoise = false;  // --no-denoise
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

// The viewer's window, its progressive renderer and the display pass, frame after frame.
class Viewer {
  public:
    Viewer(const ViewOptions& o, const Scene& scene, const Acceleration& accel, const PictureCliOptions::Values& picture,
           CameraControl control, RenderSettings settings, uint32_t samples, int frames)
        : o_(o), control_(std::move(control)), settings_(settings), samples_(samples), frames_(frames),
          bounds_(scene.bounds()), toneMapMode_(toneMapCode(picture.colour.toneMap)),
          exposure_(exposureScale(picture.colour.exposure)) {
        // The path integrator's picture is denoised (N toggles): its features and variance summed.
        const bool features = integratorInfo(settings_.integrator).features;
        denoising_ = features && !o.noDenoise;
        if (features) settings_.features = settings_.variance = true;
        try {
            window_ = std::make_unique<GLWindow>(settings.width, settings.height, "gpurt view");
        } catch (const EnvironmentError& e) {
            throw EnvironmentError(std::string("view: ") + e.what() + "; gpurt render writes the picture to a file instead");
        }
        if (!o.glslDir.empty()) ShaderLibrary::global().setDirectory(o.glslDir);
        renderer_ = makeRenderer(RendererConfig{Backend::Gl, settings.integrator, o.tracer.options()}, scene, accel);
        progressive_ = renderer_->progressive();
        width_ = window_->width();
        height_ = window_->height();
    }

    // Frames until the window closes or --frames / --bench are done; then the last frame again,
    // the screenshot, the bench's JSON.
    void run() {
        while (!window_->closeRequested()) {
            const bool screenshotNow = handleEvents();
            if (window_->closeRequested()) break;
            if (dirty_) restart();
            if (done_ < samples_) progressive_->addSample(done_++, samples_);
            show();
            if (screenshotNow) screenshot();
            window_->swapBuffers();
            ++frame_;
            afterFrame();
            if (frames_ > 0 && frame_ >= frames_) break;
        }
        if (present_) {
            // The camera of the last events (closing with them unrendered would show the old one).
            if (dirty_) {
                restart();
                progressive_->addSample(done_++, samples_);
            }
            show();  // the last frame again into the back buffer, for the screenshot
            if (!o_.screenshot.empty()) writeScreenshot(o_.screenshot);
        }
        if (o_.bench) printBench();
    }

    const CameraSpec& camera() const { return control_.spec; }
    glm::ivec2 size() const { return {width_, height_}; }

  private:
    // The window's events: resize, display modes, escape, camera moves. Returns whether P asked
    // for a screenshot.
    bool handleEvents() {
        window_->pollEvents();
        bool screenshotNow = false;
        for (const WindowEvent& e : window_->events()) {
            if (e.type == WindowEvent::Resize && e.x > 0 && e.y > 0) {
                width_ = int(e.x);
                height_ = int(e.y);
                dirty_ = true;
            } else if (e.type == WindowEvent::Key && e.press && e.key >= GLFW_KEY_1 && e.key <= GLFW_KEY_5) {
                mode_ = e.key - GLFW_KEY_1;
            } else if (e.type == WindowEvent::Key && e.press && e.key == GLFW_KEY_ESCAPE) {
                window_->requestClose();
            } else if (e.type == WindowEvent::Key && e.press && e.key == GLFW_KEY_P) {
                screenshotNow = true;
            } else if (e.type == WindowEvent::Key && e.press && e.key == GLFW_KEY_F) {
                focusUnderMouse();
            } else if (e.type == WindowEvent::Key && e.press && e.key == GLFW_KEY_N &&
                       integratorInfo(settings_.integrator).features) {
                denoising_ = !denoising_;
            } else {
                const CameraSpec before = control_.spec;
                if (control_.handle(e, height_)) {
                    try {
                        makeCamera(control_.spec, width_, height_);
                        dirty_ = true;
                    } catch (const InputError&) {
                        control_.spec = before;  // a move that would break the camera is ignored
                    }
                }
            }
        }
        return screenshotNow;
    }

    // F: the plane of focus through what the pixel centre under the mouse sees (its distance along
    // the view direction); nothing where it sees nothing. Without a lens (--lens-radius, --fstop)
    // everything stays sharp, and a line says so.
    void focusUnderMouse() {
        if (dirty_) restart();  // the AOVs of the camera on screen
        const int x = int(std::floor(control_.lastX)), y = int(std::floor(control_.lastY));
        const float t = progressive_->hitDistance(x, y);
        if (!std::isfinite(t)) return;
        const CameraBasis camera = makeCamera(control_.spec, width_, height_);
        control_.spec.focusDistance = t * glm::dot(primaryDirection(camera, x, y), camera.forward);
        if (!control_.spec.hasLens()) std::fprintf(stderr, "gpurt: F sets the focus; no lens (--lens-radius or --fstop) blurs\n");
        dirty_ = true;
    }

    // A new camera or size: the pixel centres' AOVs, and the sample sums start again.
    void restart() {
        const CameraBasis camera = makeCamera(control_.spec, width_, height_);
        settings_.width = width_;
        settings_.height = height_;
        progressive_->begin(camera, settings_);
        // New streams (first frame, resize; new streams may reuse the old ones' addresses): a new
        // display pass.
        if (!present_ || presentSize_ != glm::ivec2(width_, height_)) {
            presentSize_ = glm::ivec2(width_, height_);
            present_ = std::make_unique<GPUKernel>("present", "view/present.frag");
            progressive_->bindDisplay(*present_);
        }
        const float dist = glm::length(control_.spec.eye - bounds_.center());
        const float radius = bounds_.empty() ? 1.0f : glm::length(bounds_.halfExtent());
        depthRange_ = glm::vec2(std::max(0.0f, dist - radius), dist + radius);
        done_ = 0;
        denoisedAt_ = 0;
        dirty_ = false;
    }

    // The present pass: the denoised mean when the denoiser is on (denoising the sums again only
    // when a sample was added since), else the raw one.
    void show(bool raw = false) {
        const bool denoised = denoising_ && mode_ == 0 && !raw;
        if (denoised && denoisedAt_ != done_) {
            progressive_->denoise();
            denoisedAt_ = done_;
        }
        present_->setScreenTarget(width_, height_)
            .setUniform("showDenoised", denoised ? 1 : 0)
            .setUniform("mode", mode_)
            .setUniform("samples", float(std::max(1u, done_)))
            .setUniform("exposureScale", exposure_)
            .setUniform("toneMapMode", toneMapMode_)
            .setUniform("depthRange", depthRange_)
            .dispatch();
    }

    void writeScreenshot(const std::string& path) { writePngRgb8(path, width_, height_, window_->readPixels()); }

    void screenshot() {
        std::string path = o_.screenshot;
        if (path.empty()) {
            char name[32];
            std::snprintf(name, sizeof name, "gpurt-view-%04d.png", screenshots_++);
            path = name;
        }
        writeScreenshot(path);
        std::fprintf(stderr, "gpurt: screenshot %s\n", path.c_str());
        if (denoising_ && mode_ == 0) {  // the raw mean beside it, as FILE-raw.png
            const std::filesystem::path p(path);
            const std::string rawPath = (p.parent_path() / (p.stem().string() + "-raw" + p.extension().string())).string();
            show(true);
            writeScreenshot(rawPath);
            show();
            std::fprintf(stderr, "gpurt: screenshot %s (not denoised)\n", rawPath.c_str());
        }
    }

    uint64_t raysSoFar() const {
        const RenderStats& s = progressive_->stats();
        return s.primaryRays + s.shadowRays + s.secondaryRays;
    }

    // The bench's clock starts after the first frame (it compiles the kernels); the title shows
    // the frame rate twice a second.
    void afterFrame() {
        ++titleFrames_;
        if (o_.bench && frame_ == 1) {
            glFinish();
            benchStart_ = std::chrono::steady_clock::now();
            benchRays_ = raysSoFar();
        }
        const auto now = std::chrono::steady_clock::now();
        const double sinceTitle = std::chrono::duration<double>(now - lastTitle_).count();
        if (sinceTitle < 0.5) return;
        const uint64_t rays = raysSoFar();
        char title[192];
        std::snprintf(title, sizeof title,
                      "gpurt view: %.1f fps, %.0f ms/frame, %.1f Mrays/s, %u/%u samples, %s, frame %d",
                      titleFrames_ / sinceTitle, 1e3 * sinceTitle / titleFrames_,
                      double(rays - titleRays_) / sinceTitle * 1e-6, done_, samples_, kModeNames[mode_], frame_);
        window_->setTitle(title);
        titleRays_ = rays;
        lastTitle_ = now;
        titleFrames_ = 0;
    }

    void printBench() const {
        glFinish();
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - benchStart_).count();
        const uint64_t rays = raysSoFar() - benchRays_;
        nlohmann::json j;
        j["fps"] = double(frame_ - 1) / seconds;
        j["ms_per_frame"] = 1e3 * seconds / double(frame_ - 1);
        j["mrays_per_s"] = double(rays) / seconds * 1e-6;
        j["width"] = width_;
        j["height"] = height_;
        j["frames"] = frame_ - 1;
        j["renderer"] = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        std::printf("%s\n", j.dump().c_str());
    }

    const ViewOptions& o_;
    CameraControl control_;
    RenderSettings settings_;
    uint32_t samples_;
    int frames_;
    Bounds bounds_;
    int toneMapMode_;
    float exposure_;
    std::unique_ptr<GLWindow> window_;
    std::unique_ptr<Renderer> renderer_;
    ProgressiveRenderer* progressive_ = nullptr;
    std::unique_ptr<GPUKernel> present_;
    glm::ivec2 presentSize_{0};
    int width_ = 0, height_ = 0;
    uint32_t done_ = 0;
    int mode_ = 0, frame_ = 0, screenshots_ = 0;
    bool denoising_ = false;
    uint32_t denoisedAt_ = 0;  // the samples in the sums at the last denoise
    bool dirty_ = true;
    glm::vec2 depthRange_{0.0f, 1.0f};
    std::chrono::steady_clock::time_point benchStart_ = std::chrono::steady_clock::now();
    std::chrono::steady_clock::time_point lastTitle_ = benchStart_;
    uint64_t benchRays_ = 0, titleRays_ = 0;
    int titleFrames_ = 0;
};

int runView(const ViewOptions& o) {
    // Everything that can be refused is checked before a window opens.
    const PictureCliOptions::Values picture = o.picture.values();
    if (!o.screenshot.empty()) checkOutputPaths({o.screenshot});
    o.tracer.options();  // refuses a bad --mask now
    int scaleExponent = 0;
    LoadedScene loaded = loadSceneToRender(o.scene, o.camera.upAxis, picture.crease, scaleExponent);
    applyEnvironmentOptions(loaded.scene, picture);
    const Scene& scene = loaded.scene;
    const glm::ivec2 size = o.camera.imageSize(loaded.size);
    checkRenderFitsInMemory(size, Backend::Gl, picture.integrator);
    CameraControl control;
    control.spec = control.initial = o.camera.spec(scene, size, scaleExponent);
    makeCamera(control.spec, size.x, size.y);  // refuses an unusable camera now
    const Bounds bounds = scene.bounds();
    const float diagonal = bounds.empty() ? 1.0f : 2.0f * glm::length(bounds.halfExtent());
    control.step = 0.02f * (diagonal > 0.0f ? diagonal : 1.0f);
    const RenderSettings settings = PictureCliOptions::settings(picture, size, o.bounces, scene, scaleExponent);
    // Samples of one camera: --spp, else --frames (so that N frames are N samples, as render
    // --spp N), else 256; --bench: one a frame for all its frames.
    const bool sppGiven = o.picture.sppOption && o.picture.sppOption->count() > 0;
    const int frames = o.bench ? kBenchFrames + 1 : o.frames;
    const uint32_t samples = sppGiven ? picture.samples : frames > 0 ? uint32_t(frames) : 256u;
    const Acceleration accel = o.grid.accelerate(loaded, makeCamera(control.spec, size.x, size.y));

    Viewer viewer(o, scene, accel, picture, control, settings, samples, frames);
    viewer.run();
    // The camera in use, as options of gpurt render (in the scene file's units, turned up as the
    // viewer turned the scene); on stderr with --bench, whose stdout is its JSON object alone.
    const CameraSpec& c = viewer.camera();
    const std::string upAxis = o.camera.upAxis.empty() ? std::string() : " --up-axis " + o.camera.upAxis;
    std::string lens;
    if (c.fstop > 0.0f) lens += " --fstop " + formatFloat(c.fstop);
    else if (c.lensRadius > 0.0f) lens += " --lens-radius " + formatFloat(std::ldexp(c.lensRadius, scaleExponent));
    if (c.focusDistance > 0.0f) lens += " --focus-distance " + formatFloat(std::ldexp(c.focusDistance, scaleExponent));
    if (c.blades > 0) lens += " --blades " + std::to_string(c.blades);
    if (c.bladeRotation != 0.0f) lens += " --blade-rotation " + formatFloat(c.bladeRotation);
    std::fprintf(o.bench ? stderr : stdout, "--eye %s --target %s --up %s --fovy %s --size %dx%d%s%s\n",
                 formatVec3(unscaled(c.eye, scaleExponent)).c_str(),
                 formatVec3(unscaled(c.target, scaleExponent)).c_str(), formatVec3(c.up).c_str(),
                 formatFloat(c.fovy).c_str(), viewer.size().x, viewer.size().y, lens.c_str(), upAxis.c_str());
    return 0;
}

}  // namespace

void addViewCommand(CLI::App& app, std::function<int()>& run) {
    auto o = std::make_shared<ViewOptions>();
    auto* cmd = app.add_subcommand("view", "Explore a scene in a window, rendered progressively by the stream kernels");
    cmd->add_option("scene", o->scene, "Scene file: .obj, .json, .gltf, .glb, .ply or .gpscene (gpurt pack)")
        ->required()
        ->check(kNotEmpty);
    cmd->add_option("--frames", o->frames, "Render this many frames, then close (the samples of a still camera)")
        ->check(CLI::Range(1, 1 << 24));
    cmd->add_option("--screenshot", o->screenshot, "Write the last frame to this PNG on closing (and on P)")
        ->check(kNotEmpty);
    cmd->add_flag("--bench", o->bench,
                  "Render " + std::to_string(kBenchFrames) + " timed frames and print one JSON object on stdout "
                  "(fps, ms_per_frame, mrays_per_s, width, height, frames, renderer; the camera goes to stderr)");
    cmd->add_option("--bounces", o->bounces, "Whitted: mirror and glass levels (default: the scene's, 3); path: the longest path in hits (default " + std::to_string(kDefaultPathBounces) + ")")->check(CLI::Range(0, 64));
    cmd->add_option("--glsl-dir", o->glslDir, "Load GLSL kernels from this folder instead of the embedded copies")
        ->check(CLI::ExistingDirectory);
    cmd->add_flag("--no-denoise", o->noDenoise,
                  "Show the raw mean of the samples (path integrator; the denoiser is on by default, key N toggles)");
    o->picture.add(*cmd);
    o->tracer.add(*cmd);
    o->grid.add(*cmd);
    o->camera.add(*cmd);
    cmd->callback([&run, o] { run = [o] { return runView(*o); }; });
}

}  // namespace gpurt
