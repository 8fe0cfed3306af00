// Options shared by the subcommands: the GL context (--gl, --glsl-dir), the camera (--eye,
// --target, --up, --fovy), the image size (--size), and their parsing into one-line errors.
#pragma once

#include "raytrace/camera/Camera.h"
#include "image/Colour.h"
#include "image/InputError.h"
#include "raytrace/common/GlOptions.h"
#include "raytrace/render/Renderer.h"
#include "scene/Scene.h"
#include "raytrace/scene/SceneLoader.h"
#include "raytrace/accel/Acceleration.h"
#include "raytrace/accel/grid/UniformGrid.h"
#include "stream/GLContext.h"
#include "stream/ShaderLibrary.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json_fwd.hpp>
#include <glm/glm.hpp>

#include <cmath>
#include <map>
#include <optional>
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

// A finite float; InputError naming the option otherwise.
float parseFiniteFloat(const std::string& option, const std::string& text);
// A decimal integer in [lo, hi]; InputError naming the option otherwise.
uint32_t parseCount(const std::string& option, const std::string& text, uint32_t lo, uint32_t hi);
// "x,y,z" -> vec3; InputError naming the option otherwise.
glm::vec3 parseVec3(const std::string& option, const std::string& text);
// "WxH" -> (W, H) with 1 <= W, H <= 16384 and W * H <= 8192 * 8192.
glm::ivec2 parseSize(const std::string& option, const std::string& text);

// Throws EnvironmentError (exit 2) when a render of `size` (raytrace/render/Renderer.h renderBytes) would
// need more memory than the machine has available (MemAvailable): Linux overcommits, so past
// that point the render would be killed instead of failing cleanly.
void checkRenderFitsInMemory(glm::ivec2 size, Backend backend, Integrator integrator);

// --up-axis y|z|x|-y|-z|-x: the axis that is up in the scene file; the scene is turned so that it
// is up (+y) before anything else (the default camera, --eye and --target are in the turned scene).
void addUpAxisOption(CLI::App& cmd, std::string& upAxis);
// --up-axis as an axis (none when not given); InputError for a bad one.
std::optional<UpAxis> upAxisOf(const std::string& upAxisOption);
// Turns the loaded scene so that --up-axis (when given, else the scene's own) points up, with its
// accelerator (the library's turnSceneUp, raytrace/scene/SceneLoader.h). InputError for a bad --up-axis.
void turnSceneUp(LoadedScene& loaded, const std::string& upAxisOption);

// Refuses an empty value ("--fovy ''"), which the options below would take for "not given".
inline const CLI::Validator kNotEmpty(
    [](std::string& value) { return value.empty() ? std::string("empty value") : std::string(); },
    "", "NOT_EMPTY");

struct CameraOptions {
    std::string eye, target, up, fovy, size;
    std::string lensRadius, fstop, focusDistance, blades, bladeRotation;  // depth of field
    std::string upAxis;  // --up-axis; empty: the scene's own (a JSON scene's "up_axis", else y)

    void add(CLI::App& cmd) {
        cmd.add_option("--eye", eye, "Camera position x,y,z (overrides the scene's camera)")
            ->check(kNotEmpty);
        cmd.add_option("--target", target, "Point the camera looks at, x,y,z")->check(kNotEmpty);
        cmd.add_option("--up", up, "Up vector x,y,z (default 0,1,0)")->check(kNotEmpty);
        cmd.add_option("--fovy", fovy, "Vertical field of view in degrees (default 45)")
            ->check(kNotEmpty);
        cmd.add_option("--size", size, "Image size WxH (default 512x512, or the scene's)")
            ->check(kNotEmpty);
        CLI::Option* radius = cmd.add_option("--lens-radius", lensRadius,
                                             "Depth of field: the thin lens's radius in scene units (default 0: "
                                             "a pinhole camera, everything sharp)")
                                  ->check(kNotEmpty);
        cmd.add_option("--fstop", fstop,
                       "Depth of field: the lens's f-number N, as Cycles (radius = f / (2 N), f the focal length "
                       "of a 36 mm sensor across the image's larger side; a scene unit is a metre)")
            ->check(kNotEmpty)
            ->excludes(radius);
        cmd.add_option("--focus-distance", focusDistance,
                       "Depth of field: the distance of the sharp plane along the view direction (default: "
                       "from the eye to the target)")
            ->check(kNotEmpty);
        cmd.add_option("--blades", blades, "Depth of field: aperture blades, 0 (a disc, default) or 3 to 64")
            ->check(kNotEmpty);
        cmd.add_option("--blade-rotation", bladeRotation,
                       "Depth of field: the angle in degrees of the first blade corner from the right, "
                       "counter-clockwise (default 0)")
            ->check(kNotEmpty);
        addUpAxisOption(cmd, upAxis);
    }
    // The image size: --size, else the scene file's, else 512x512.
    glm::ivec2 imageSize(std::optional<glm::ivec2> sceneSize) const;
    // The camera: the scene's (its camera, else its animation's first frame, else the contract's
    // default camera for its bounds), or frame `frame` of its animation, with each option given
    // overriding its part. Throws InputError for an unusable camera.
    // `scaleExponent`: the scene was rescaled by 2^-scaleExponent for rendering (SceneScale.h);
    // --eye and --target, given in the scene file's units, are rescaled alike.
    CameraBasis camera(const Scene& scene, glm::ivec2 size, int scaleExponent = 0,
                       std::optional<int> frame = std::nullopt) const;
    // The same before it is made a basis (unchecked; makeCamera checks it).
    CameraSpec spec(const Scene& scene, glm::ivec2 size, int scaleExponent = 0,
                    std::optional<int> frame = std::nullopt) const;
};

// The picture options of render and view: --spp, --seed, --exposure, --tonemap, --smooth.
struct PictureCliOptions {
    std::string spp = "1", seed = "0", exposure = "0", tonemap = "aces", smooth = "60", integrator = "whitted";
    std::string env, envStrength, envRotate, envSampling = "mis";
    std::string sampler = "sobol", noiseThreshold = "0", minSpp, clampDirect = "0", clampIndirect = "10";
    // The integrators' own options (IntegratorInfo::options) as given, by their uniform names.
    std::map<std::string, std::string> integratorOptions;
    CLI::Option* sppOption = nullptr;

    void add(CLI::App& cmd);
    // The parsed values; InputError naming the option otherwise.
    struct Values {
        uint32_t samples = 1, seed = 0;
        SamplerKind sampler = SamplerKind::Sobol;  // --sampler
        float noiseThreshold = 0.0f;              // --noise-threshold (0: off)
        uint32_t minSamples = 0;                  // --min-spp, or the threshold's default
        float clampDirect = 0.0f, clampIndirect = 10.0f;  // --clamp-direct, --clamp-indirect (0: off)
        float crease = 60.0f;  // --smooth; < 0: off
        ColourSettings colour;
        Integrator integrator = Integrator::Whitted;
        std::string env;                     // --env: a file, "none", or empty (the scene's)
        std::optional<float> envStrength;    // --env-strength
        std::optional<float> envRotate;      // --env-rotate, degrees
        bool envSampled = true;              // --env-sampling mis (true) or bsdf
        std::map<std::string, float> integratorOptions;  // those given, in scene units
    };
    Values values() const;
    // --bounces as given (>= 0), else the integrator's default: the scene's for Whitted (its
    // mirror and glass levels, 3 unless it says), kDefaultPathBounces for path.
    static int bounces(int given, const Scene& scene, Integrator integrator);
    // The render settings of the values for an image of `size`, with bounces(given, ...), for the
    // scene rescaled by 2^-scaleExponent (loadSceneToRender: distances scale with it).
    static RenderSettings settings(const Values& values, glm::ivec2 size, int given, const Scene& scene,
                                   int scaleExponent);
};

// The scene as render and view trace it: the library's prepareScene (raytrace/scene/SceneLoader.h) with
// --up-axis and --smooth (crease < 0: faceted). `normalsMs`, if given, gets the smooth normals'
// share of the time (--stats' normals phase).
LoadedScene loadSceneToRender(const std::string& path, const std::string& upAxisOption, float crease,
                              int& scaleExponent, double* normalsMs = nullptr);

// The environment light of render and view (CONTRACT.md): --env FILE replaces the scene's,
// --env none removes it and the default light; otherwise a scene without a light of its own gets
// the default light (addDefaultLight). Then --env-strength, --env-rotate and --env-sampling apply
// to whichever environment the scene has. Throws InputError naming a file that cannot be read.
void applyEnvironmentOptions(Scene& scene, const PictureCliOptions::Values& values);

// The acceleration structure options of render, view and bench: --accel, and the grid's
// --lambda and --skip.
struct GridCliOptions {
    std::string accel = "auto";
    float lambda = GridOptions{}.lambda;
    bool skip = true;
    CLI::Option* lambdaOption = nullptr;

    void add(CLI::App& cmd);
    // The structure to trace for --accel (accel/Acceleration.h chooseAcceleration): a packed
    // scene's own where it is of the kind asked (its grid only without --lambda, which asks for a
    // grid built from the triangles as any other scene's, so every route gives the same image),
    // else built;
    // `camera` is the view auto's estimate traces.
    Acceleration accelerate(const LoadedScene& loaded, const CameraBasis& camera) const;
};

// --accel's values: the registered accelerators' names (accel/Accelerator.h) and auto.
std::vector<std::string> accelChoices();

// What render and bench report of the structure: auto's estimates ("accel_estimate": {name:
// cost}) and the structure's figures under its accelerator's name ("bvh": {"nodes", "depth"}).
void addAccelJson(nlohmann::json& j, const Acceleration& accel);
// Auto's estimates as text: "grid 12.3, bvh 8.1".
std::string estimateText(const Acceleration& accel);

// The GL trace loop's options of render and bench: --kernel, --traverse-steps, --mask and
// --wait-threshold.
struct TracerCliOptions {
    std::string kernel;  // empty: the default
    int megakernelBounces = 0;
    int traverseSteps = 0;
    std::string mask;
    float waitThreshold = 0.0f;
    bool maskPaths = false;

    void add(CLI::App& cmd);
    // Throws InputError for an unknown --mask.
    GpuTracerOptions options() const;
};

}  // namespace gpurt
