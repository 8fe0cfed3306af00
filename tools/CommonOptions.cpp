#include "CommonOptions.h"

#include "raytrace/scene/SceneScale.h"
#include "raytrace/integrators/Registry.h"
#include "scene/SmoothNormals.h"
#include "stream/StreamErrors.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>
#include <vector>

namespace gpurt {

namespace {
bool parseFloat(const std::string& text, float& value) {
    if (text.empty()) return false;
    char* end = nullptr;
    value = std::strtof(text.c_str(), &end);
    return end == text.c_str() + text.size() && std::isfinite(value);
}
}  // namespace

float parseFiniteFloat(const std::string& option, const std::string& text) {
    float value = 0.0f;
    if (!parseFloat(text, value)) throw InputError(option + ": '" + text + "' is not a finite number");
    return value;
}

uint32_t parseCount(const std::string& option, const std::string& text, uint32_t lo, uint32_t hi) {
    const bool digits = !text.empty() && text.size() <= 10 && text.find_first_not_of("0123456789") == std::string::npos;
    const unsigned long long value = digits ? std::stoull(text) : 0;
    if (!digits || value < lo || value > hi)
        throw InputError(option + ": '" + text + "' is not an integer from " + std::to_string(lo) +
                         " to " + std::to_string(hi));
    return static_cast<uint32_t>(value);
}

glm::vec3 parseVec3(const std::string& option, const std::string& text) {
    std::vector<std::string> parts;
    std::stringstream in(text);
    for (std::string part; std::getline(in, part, ',');) parts.push_back(part);
    glm::vec3 v(0.0f);
    if (parts.size() != 3 || !parseFloat(parts[0], v.x) || !parseFloat(parts[1], v.y) || !parseFloat(parts[2], v.z))
        throw InputError(option + ": '" + text + "' is not three finite numbers x,y,z");
    return v;
}

glm::ivec2 parseSize(const std::string& option, const std::string& text) {
    const size_t x = text.find('x');
    auto parseInt = [&](const std::string& s, int& v) {
        if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos) return false;
        v = std::stoi(s);
        return true;
    };
    int w = 0, h = 0;
    if (x == std::string::npos || !parseInt(text.substr(0, x), w) || !parseInt(text.substr(x + 1), h))
        throw InputError(option + ": '" + text + "' is not a size WxH (e.g. 512x512)");
    if (w < 1 || h < 1) throw InputError(option + ": " + text + ": width and height must be at least 1");
    if (w > 16384 || h > 16384)
        throw InputError(option + ": " + text + ": at most 16384 pixels on a side");
    if (int64_t(w) * int64_t(h) > int64_t(8192) * 8192)
        throw InputError(option + ": " + text + ": at most 67108864 (8192x8192) pixels");
    return {w, h};
}

void checkRenderFitsInMemory(glm::ivec2 size, Backend backend, Integrator integrator) {
    const double needed = renderBytes(backend, integrator, double(size.x) * double(size.y));
    std::ifstream meminfo("/proc/meminfo");
    std::string key;
    double availableKiB = 0.0;
    while (meminfo >> key) {
        if (key == "MemAvailable:") {
            meminfo >> availableKiB;
            break;
        }
        meminfo.ignore(1 << 10, '\n');
    }
    if (!(availableKiB > 0.0)) return;  // not Linux, or no figure: let the allocations decide
    if (needed > availableKiB * 1024.0) {
        char text[160];
        std::snprintf(text, sizeof text,
                      "--size %dx%d: the %s backend needs about %.1f GB, only %.1f GB of memory "
                      "is available",
                      size.x, size.y, backend == Backend::Gl ? "gl" : "cpu", needed / 1e9, availableKiB * 1024.0 / 1e9);
        throw EnvironmentError(text);
    }
}

glm::ivec2 CameraOptions::imageSize(std::optional<glm::ivec2> sceneSize) const {
    if (!size.empty()) return parseSize("--size", size);
    return sceneSize.value_or(glm::ivec2(512, 512));
}

CameraBasis CameraOptions::camera(const Scene& scene, glm::ivec2 imageSize, int scaleExponent,
                                  std::optional<int> frame) const {
    const CameraSpec s = spec(scene, imageSize, scaleExponent, frame);
    return makeCamera(s, imageSize.x, imageSize.y);
}

CameraSpec CameraOptions::spec(const Scene& scene, glm::ivec2 imageSize, int scaleExponent,
                               std::optional<int> frame) const {
    CameraSpec spec;
    if (!fovy.empty()) {
        float f = 0.0f;
        if (!parseFloat(fovy, f)) throw InputError("--fovy: '" + fovy + "' is not a number");
        spec.fovy = f;
        if (!(f > 0.0f && f < 180.0f)) throw InputError("--fovy: " + fovy + " is outside (0, 180)");
    }
    const std::optional<CameraSpec> given =
        frame ? scene.animation->at(*frame) : scene.camera ? scene.camera
                                            : scene.animation ? std::optional(scene.animation->at(0))
                                                              : std::nullopt;
    if (given) {
        const float f = spec.fovy;
        spec = *given;
        if (!fovy.empty()) spec.fovy = f;
    } else if (eye.empty() || target.empty()) {
        const float f = spec.fovy;
        spec = defaultCamera(scene.bounds(), imageSize.x, imageSize.y, f);
    }
    if (!eye.empty()) spec.eye = rescalePoint(parseVec3("--eye", eye), scaleExponent);
    if (!target.empty()) spec.target = rescalePoint(parseVec3("--target", target), scaleExponent);
    if (!up.empty()) spec.up = parseVec3("--up", up);
    spec.metre = std::ldexp(1.0f, -scaleExponent);
    if (!lensRadius.empty()) {
        spec.lensRadius = std::ldexp(parseFiniteFloat("--lens-radius", lensRadius), -scaleExponent);  // makeCamera checks it
        spec.fstop = 0.0f;
    }
    if (!fstop.empty()) {
        spec.fstop = parseFiniteFloat("--fstop", fstop);
        if (!(spec.fstop > 0.0f)) throw InputError("--fstop: " + fstop + " is not above 0");
        spec.lensRadius = 0.0f;
    }
    if (!focusDistance.empty()) {
        spec.focusDistance = std::ldexp(parseFiniteFloat("--focus-distance", focusDistance), -scaleExponent);
        if (!(spec.focusDistance > 0.0f)) throw InputError("--focus-distance: " + focusDistance + " is not above 0");
    }
    if (!blades.empty()) spec.blades = int(parseCount("--blades", blades, 0, 64));  // 1 and 2: makeCamera refuses
    if (!bladeRotation.empty()) spec.bladeRotation = parseFiniteFloat("--blade-rotation", bladeRotation);
    return spec;
}

void GridCliOptions::add(CLI::App& cmd) {
    std::string help = "Acceleration structure:";
    for (const AcceleratorInfo* a : accelerators()) help += " " + std::string(a->name) + " (" + std::string(a->help) + "),";
    help += " or auto (default: builds each and keeps the one an estimate of the trace cost says is cheapest; a packed "
            "scene's own structure stands)";
    cmd.add_option("--accel", accel, help)->check(CLI::IsMember(accelChoices()));
    lambdaOption = cmd.add_option("--lambda", lambda,
                                  "Grid density: cells along the longest axis ~ lambda * N^(1/3) "
                                  "(a packed scene's own grid is used unless this is given)")
                       ->check(CLI::Range(0.01f, 64.0f));
    cmd.add_option("--skip", skip, "Empty-space skipping over empty cells (proximity clouds): on (default) or off")
        ->transform(CLI::CheckedTransformer(std::map<std::string, bool>{{"on", true}, {"off", false}}));
}

Acceleration GridCliOptions::accelerate(const LoadedScene& loaded, const CameraBasis& camera) const {
    AccelOptions options;
    options.grid.lambda = lambda;
    options.grid.skip = skip;
    // --lambda asks for a grid built from the triangles as any other scene's, so that every route
    // gives the same image.
    options.newGrid = lambdaOption && lambdaOption->count() > 0;
    const std::string choice = options.newGrid && accel == "auto" ? "grid" : accel;
    return chooseAcceleration(loaded.scene, choice, loaded.accel, options, camera);
}

std::vector<std::string> accelChoices() {
    std::vector<std::string> names;
    for (const AcceleratorInfo* a : accelerators()) names.emplace_back(a->name);
    names.emplace_back("auto");
    return names;
}

void addAccelJson(nlohmann::json& j, const Acceleration& accel) {
    if (!accel.estimate.empty()) {
        j["accel_estimate"] = nlohmann::json::object();
        for (const auto& [name, cost] : accel.estimate) j["accel_estimate"][name] = cost;
    }
    const std::vector<std::pair<std::string, double>> figures = accel.structure->figures();
    if (!figures.empty()) {
        nlohmann::json& f = j[std::string(accel.name())] = nlohmann::json::object();
        for (const auto& [name, value] : figures) {
            if (value == std::floor(value) && std::abs(value) < 1e15) f[name] = int64_t(value);  // counts stay integers
            else f[name] = value;
        }
    }
}

std::string estimateText(const Acceleration& accel) {
    std::string text;
    char number[32];
    for (const auto& [name, cost] : accel.estimate) {
        std::snprintf(number, sizeof number, " %.1f", cost);
        text += (text.empty() ? "" : ", ") + name + number;
    }
    return text;
}

void TracerCliOptions::add(CLI::App& cmd) {
    cmd.add_option("--kernel", kernel,
                   "How the passes are split (gl): megakernel (a pass takes each path through several "
                   "bounces: trace, shading and shadow rays in one kernel), fused (a pass a stage of the "
                   "integrator, traversal and intersection in one kernel) or split (the Purcell/Christen "
                   "traverser and intersector pair); default: the faster on the renderer "
                   "(docs/PERFORMANCE.md; environment variable GPURT_KERNEL=wavefront|megakernel)")
        ->check(CLI::IsMember({"megakernel", "fused", "split"}));
    cmd.add_option("--megakernel-bounces", megakernelBounces,
                   "Megakernel: the bounces a pass takes each path through before the live paths are packed "
                   "(0 = default)")
        ->check(CLI::Range(0, 1 << 20));
    cmd.add_option("--traverse-steps", traverseSteps,
                   "Grid cells per trace pass (0 = default: whole traversal when fused, 16 when split; "
                   "1 with split = the seed)")
        ->check(CLI::Range(0, 1 << 20));
    cmd.add_option("--mask", mask, "Masking mode of the trace loop: earlyz|stencil|exit (default: fastest)")
        ->check(kNotEmpty);
    cmd.add_option("--wait-threshold", waitThreshold,
                   "Split kernels: run the intersector once this fraction of live rays wait (0: every iteration)")
        ->check(CLI::Range(0.0f, 1.0f));
    cmd.add_flag("--mask-paths", maskPaths,
                 "Path integrator: mask each round's passes to the live paths (--mask's mode) instead of "
                 "each kernel's early exit (slower on llvmpipe: docs/PERFORMANCE.md)");
}

GpuTracerOptions TracerCliOptions::options() const {
    GpuTracerOptions options;
    if (!mask.empty() && !parseMaskMode(mask, options.mask))
        throw InputError("--mask: unknown mode '" + mask + "' (earlyz, stencil, exit)");
    if (!kernel.empty()) {  // unset: the integrators' default kernels (IntegratorKernel::Auto)
        options.integratorKernel = kernel == "megakernel" ? IntegratorKernel::Megakernel : IntegratorKernel::Wavefront;
        parseTraceKernel(kernel == "megakernel" ? "fused" : kernel, options.kernel);
    }
    options.megakernelBounces = megakernelBounces;
    options.traverseSteps = traverseSteps;
    options.waitThreshold = waitThreshold;
    options.maskPaths = maskPaths;
    return options;
}

void PictureCliOptions::add(CLI::App& cmd) {
    sppOption = cmd.add_option("--spp", spp, "Samples per pixel, stratified over the pixel (render: default 1, the pixel centre; view: a still "
                    "camera's samples, default --frames or 256)")
                    ->check(kNotEmpty);
    cmd.add_option("--seed", seed, "Seed of the samples' random numbers (default 0)")->check(kNotEmpty);
    cmd.add_option("--sampler", sampler,
                   "Where the samples' numbers come from: sobol (Owen-scrambled Sobol points, any prefix well "
                   "spread; default), stratified (correlated multi-jittered for the --spp count) or random")
        ->check(CLI::IsMember({"sobol", "stratified", "random"}));
    cmd.add_option("--noise-threshold", noiseThreshold,
                   "Adaptive sampling (path integrator): a pixel stops once its estimated relative error is "
                   "below T (Cycles' meaning; 0.01 is typical; default 0: off); --spp is then the most a pixel takes")
        ->check(kNotEmpty);
    cmd.add_option("--clamp-direct", clampDirect,
                   "Path integrator: scale each sample's direct light (what the camera ray finds and the light "
                   "at its first hit) so that its largest channel is at most X (Cycles' meaning; default 0: off)")
        ->check(kNotEmpty);
    cmd.add_option("--clamp-indirect", clampIndirect,
                   "Path integrator: the same for indirect light, found after the first bounce (default 10, as "
                   "Cycles; 0: off)")
        ->check(kNotEmpty);
    cmd.add_option("--min-spp", minSpp,
                   "Adaptive sampling: the samples every pixel takes before it may stop (default as Cycles: "
                   "max(4, ceil(16 / T^0.3)), at most --spp)")
        ->check(kNotEmpty);
    cmd.add_option("--smooth", smooth,
                   "Smooth shading: crease angle in degrees for meshes without normals (default 60), or off (faceted)")
        ->check(kNotEmpty);
    cmd.add_option("--exposure", exposure, "Exposure in EV: the linear colour is scaled by 2^EV (default 0)")
        ->check(kNotEmpty);
    cmd.add_option("--tonemap", tonemap, "Tone map of the PNG: aces (filmic, default), reinhard or clamp")
        ->check(CLI::IsMember({"aces", "reinhard", "clamp"}));
    cmd.add_option("--env", env,
                   "Environment light: a latitude-longitude map (.hdr or .exr) around the scene, or 'none' (no "
                   "environment, and no default light for a scene without a light of its own)")
        ->check(kNotEmpty);
    cmd.add_option("--env-strength", envStrength, "Scale of the environment's radiance (default 1; also the default light's)")
        ->check(kNotEmpty);
    cmd.add_option("--env-rotate", envRotate,
                   "Turn the environment about +Y by DEG degrees, positive counter-clockwise seen from above (default 0)")
        ->check(kNotEmpty);
    cmd.add_option("--env-sampling", envSampling,
                   "Path integrator: mis (next-event estimation of the environment by its luminance, weighed by MIS "
                   "with BSDF sampling; default) or bsdf (only BSDF directions find it; for comparison)")
        ->check(CLI::IsMember({"mis", "bsdf"}));
    std::string help;
    std::vector<std::string> names;
    for (const IntegratorInfo* info : integrators()) {
        help += (help.empty() ? "" : ", ") + info->help;
        names.emplace_back(info->id.name());
        for (const IntegratorOption& option : info->options)
            cmd.add_option("--" + option.name, integratorOptions[option.uniform], option.help)->check(kNotEmpty);
    }
    cmd.add_option("--integrator", integrator, help)->check(CLI::IsMember(names));
}

RenderSettings PictureCliOptions::settings(const Values& values, glm::ivec2 size, int given, const Scene& scene,
                                           int scaleExponent) {
    RenderSettings settings;
    for (const IntegratorOption& option : integratorInfo(values.integrator).options) {
        auto given = values.integratorOptions.find(option.uniform);
        if (given != values.integratorOptions.end())  // lengths scale with the scene
            settings.integratorOptions[option.uniform] =
                option.sceneUnits ? std::ldexp(given->second, -scaleExponent) : given->second;
    }
    settings.width = size.x;
    settings.height = size.y;
    settings.maxBounces = bounces(given, scene, values.integrator);
    settings.integrator = values.integrator;
    settings.samples = values.samples;
    settings.seed = values.seed;
    settings.sampler = values.sampler;
    settings.noiseThreshold = values.noiseThreshold;
    settings.minSamples = values.minSamples;
    settings.clampDirect = values.clampDirect;
    settings.clampIndirect = values.clampIndirect;
    return settings;
}

int PictureCliOptions::bounces(int given, const Scene& scene, Integrator integrator) {
    if (given >= 0) return given;
    const int own = integratorInfo(integrator).defaultBounces;
    return own >= 0 ? own : scene.maxBounces;
}

PictureCliOptions::Values PictureCliOptions::values() const {
    Values v;
    v.colour.exposure = parseFiniteFloat("--exposure", exposure);
    if (std::abs(v.colour.exposure) > 64.0f)
        throw InputError("--exposure: " + exposure + " is outside [-64, 64]");
    parseToneMap(tonemap, v.colour.toneMap);
    const IntegratorInfo* chosen = findIntegrator(integrator);
    if (!chosen) throw InputError("--integrator: no integrator named '" + integrator + "'");
    v.integrator = chosen->id;
    for (const IntegratorInfo* info : integrators())
        for (const IntegratorOption& option : info->options) {
            const std::string& text = integratorOptions.at(option.uniform);
            if (text.empty()) continue;
            const std::string flag = "--" + option.name;
            if (info != chosen)
                throw InputError(flag + ": only with --integrator " + std::string(info->id.name()));
            const float value = text == "unlimited" ? std::numeric_limits<float>::infinity() : parseFiniteFloat(flag, text);
            if (!(value > option.above)) {
                std::ostringstream above;
                above << option.above;
                throw InputError(flag + ": " + text + " is not above " + above.str());
            }
            v.integratorOptions[option.uniform] = value;
        }
    // The per-pixel sums take the same memory for any sample count; the bound keeps sample
    // indices and counts exact in float (2^24).
    v.samples = parseCount("--spp", spp, 1, 1u << 24);
    v.seed = parseCount("--seed", seed, 0, UINT32_MAX);
    v.sampler = sampler == "stratified" ? SamplerKind::Stratified
                : sampler == "random"   ? SamplerKind::Random
                                        : SamplerKind::Sobol;
    v.noiseThreshold = parseFiniteFloat("--noise-threshold", noiseThreshold);
    if (v.noiseThreshold < 0.0f || v.noiseThreshold >= 1.0f)
        throw InputError("--noise-threshold: " + noiseThreshold + " is not in [0, 1) (0: off)");
    if (v.noiseThreshold > 0.0f && !chosen->adaptive)
        throw InputError("--noise-threshold: adaptive sampling needs --integrator path");
    for (auto [option, text, value] : {std::tuple{"--clamp-direct", &clampDirect, &v.clampDirect},
                                       std::tuple{"--clamp-indirect", &clampIndirect, &v.clampIndirect}}) {
        *value = parseFiniteFloat(option, *text);
        if (*value < 0.0f) throw InputError(std::string(option) + ": " + *text + " is negative (0: off)");
    }
    if (!minSpp.empty()) {
        if (!(v.noiseThreshold > 0.0f)) throw InputError("--min-spp: only with --noise-threshold");
        v.minSamples = parseCount("--min-spp", minSpp, 1, 1u << 24);
        if (v.minSamples > v.samples)
            throw InputError("--min-spp: " + minSpp + " is above --spp " + std::to_string(v.samples));
    } else {
        v.minSamples = std::min(defaultMinSamples(v.noiseThreshold), v.samples);
    }
    v.env = env;
    if (!envStrength.empty()) {
        v.envStrength = parseFiniteFloat("--env-strength", envStrength);
        if (*v.envStrength < 0.0f || *v.envStrength > 1e6f)
            throw InputError("--env-strength: " + envStrength + " is outside [0, 1e6]");
    }
    if (!envRotate.empty()) {
        v.envRotate = parseFiniteFloat("--env-rotate", envRotate);
        if (std::abs(*v.envRotate) > 1e6f) throw InputError("--env-rotate: " + envRotate + " is outside [-1e6, 1e6]");
    }
    v.envSampled = envSampling != "bsdf";
    v.crease = -1.0f;  // --smooth off
    if (smooth != "off") {
        v.crease = parseFiniteFloat("--smooth", smooth);
        if (v.crease < 0.0f || v.crease > 180.0f)
            throw InputError("--smooth: " + smooth + " is not a crease angle from 0 to 180 degrees or 'off'");
    }
    return v;
}

void addUpAxisOption(CLI::App& cmd, std::string& upAxis) {
    cmd.add_option("--up-axis", upAxis,
                   "The axis that is up in the scene file: y (default), z (CAD, scans), x, -y, -z or -x; the "
                   "scene is turned so that it is up before the camera is placed (a JSON scene may say "
                   "\"up_axis\")")
        ->check(kNotEmpty);
}

std::optional<UpAxis> upAxisOf(const std::string& upAxisOption) {
    if (upAxisOption.empty()) return std::nullopt;
    UpAxis axis;
    if (!parseUpAxis(upAxisOption, axis))
        throw InputError("--up-axis: '" + upAxisOption + "' is not one of y, z, x, -y, -z, -x");
    return axis;
}

void turnSceneUp(LoadedScene& loaded, const std::string& upAxisOption) {
    turnSceneUp(loaded, upAxisOf(upAxisOption).value_or(loaded.scene.upAxis));
}

void applyEnvironmentOptions(Scene& scene, const PictureCliOptions::Values& values) {
    if (values.env == "none") {
        scene.environment.reset();
        return;
    }
    if (!values.env.empty()) {
        Environment env;
        env.image = std::make_shared<const EnvironmentImage>(readEnvironmentImage(values.env));
        env.file = values.env;
        scene.environment = env;
    }
    addDefaultLight(scene);
    if (!scene.environment) return;
    if (values.envStrength) scene.environment->strength = *values.envStrength;
    if (values.envRotate) scene.environment->rotation = *values.envRotate;
    scene.environment->sampled = values.envSampled;
}

LoadedScene loadSceneToRender(const std::string& path, const std::string& upAxisOption, float crease,
                              int& scaleExponent, double* normalsMs) {
    return prepareScene(path, upAxisOf(upAxisOption), crease, scaleExponent, normalsMs);
}

}  // namespace gpurt
