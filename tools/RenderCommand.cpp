// `gpurt render SCENE -o OUT.png`: renders a scene with the GL stream kernels (default) or the
// CPU backend, writes the PNG and the requested AOVs (PFM), and prints statistics. A packed scene
// is rendered with the grid it carries.
#include "Commands.h"
#include "CommonOptions.h"
#include "raytrace/integrators/Registry.h"
#include "Progress.h"
#include "raytrace/scene/SceneLoader.h"

#include "image/AtomicFile.h"
#include "image/Colour.h"
#include "image/ExrIO.h"
#include "raytrace/render/Renderer.h"
#include "raytrace/denoise/DenoiseGl.h"
#include "image/ImageIO.h"
#include "raytrace/scene/SceneScale.h"
#include "scene/SmoothNormals.h"
#include "image/Tiles.h"
#include "raytrace/accel/grid/UniformGrid.h"
#include "stream/KernelStats.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <utility>

namespace gpurt {

namespace {

struct RenderOptions {
    std::string scene;
    std::string output;
    std::vector<std::string> aovs;
    std::string backend = "gl";
    std::string stats;  // "", "text" or "json"
    bool statsGiven = false;
    TracerCliOptions tracer;
    GridCliOptions grid;
    int bounces = -1;
    std::string tile;  // --tile I/N
    std::string frames;  // --frames A:B
    std::string timeLimit;  // --time-limit SECONDS
    bool denoise = false;   // --denoise
    ProgressCliOptions progress;
    PictureCliOptions picture;
    CameraOptions camera;
    ContextOptions context;
};

// --tile I/N: tile I of N of an image `height` rows high; InputError naming the option otherwise.
void parseTile(const std::string& text, int height, int& index, int& count) {
    const size_t slash = text.find('/');
    if (slash == std::string::npos) throw InputError("--tile: '" + text + "' is not I/N");
    count = int(parseCount("--tile", text.substr(slash + 1), 1, uint32_t(height)));
    index = int(parseCount("--tile", text.substr(0, slash), 0, uint32_t(count - 1)));
}

// A fingerprint of everything that decides a render's pixels: the scene as loaded, the camera and
// image size, the grid, the samples and the picture options, the backend. Tiles of one image
// share it (stitch refuses others).
std::string renderFingerprint(const Scene& scene, const CameraBasis& camera, const Acceleration& accel,
                              const RenderSettings& settings, const PictureCliOptions& picture,
                              const std::string& backend) {
    uint32_t crc = 0;
    auto add = [&](const void* data, size_t bytes) { crc = crc32Of(data, bytes, crc); };
    add(scene.triangles.data(), scene.triangles.size() * sizeof(Triangle));
    add(scene.materialIds.data(), scene.materialIds.size() * sizeof(uint32_t));
    add(scene.normals.data(), scene.normals.size() * sizeof(TriangleNormals));
    add(scene.colors.data(), scene.colors.size() * sizeof(TriangleColors));
    add(scene.tangents.data(), scene.tangents.size() * sizeof(TriangleTangents));
    for (const Material& m : scene.materials) {
        const float v[] = {m.diffuse.x, m.diffuse.y, m.diffuse.z, m.specular.x, m.specular.y, m.specular.z,
                           m.shininess, m.reflectivity.x, m.reflectivity.y, m.reflectivity.z, m.emission.x,
                           m.emission.y, m.emission.z, m.ior, m.transmission.x, m.transmission.y, m.transmission.z};
        add(v, sizeof(v));
    }
    add(scene.lights.data(), scene.lights.size() * sizeof(Light));
    add(&scene.background, sizeof(scene.background));
    if (scene.environment) {  // the map's texels, strength, rotation and sampling
        const Environment& env = *scene.environment;
        add(env.image->texels.data(), env.image->texels.size() * sizeof(glm::vec3));
        const float e[] = {float(env.image->width), float(env.image->height), env.strength, env.rotation,
                           env.sampled ? 1.0f : 0.0f};
        add(e, sizeof(e));
    }
    const float c[] = {camera.eye.x, camera.eye.y, camera.eye.z, camera.forward.x, camera.forward.y, camera.forward.z,
                       camera.right.x, camera.right.y, camera.right.z, camera.upOrtho.x, camera.upOrtho.y,
                       camera.upOrtho.z, camera.tanHalf, camera.aspect};
    add(c, sizeof(c));
    const std::string structure = accel.structure->summary();
    add(structure.data(), structure.size());
    const int ints[] = {camera.width, camera.height, settings.maxBounces, int(settings.samples), int(settings.seed)};
    add(ints, sizeof(ints));
    const std::string text = picture.exposure + "|" + picture.tonemap + "|" + picture.smooth + "|" + backend + "|" +
                             picture.sampler + "|" + std::to_string(settings.noiseThreshold) + "|" +
                             std::to_string(settings.minSamples) + "|" + std::to_string(settings.clampDirect) + "|" +
                             std::to_string(settings.clampIndirect) + "|" + std::string(settings.integrator.name());
    add(text.data(), text.size());
    for (const auto& [name, value] : settings.integratorOptions) {
        add(name.data(), name.size());
        add(&value, sizeof(value));
    }
    char hex[9];
    std::snprintf(hex, sizeof(hex), "%08x", crc);
    return hex;
}

// Where a render's wall time goes (--stats): the phases in order, in milliseconds (load: reading
// the scene; normals: smooth normals; grid: the accelerator's build or choice). trace and shade
// are the kernel passes (traversal and intersection, the rest), compile the GL programs' builds
// (llvmpipe generates a kernel's machine code at its first pass, which counts in that pass), other
// the render's time outside passes, builds and read-backs (stream fills and copies, syncs); the
// CPU backend's render is all trace.
struct Phases {
    double load = 0, normals = 0, grid = 0, context = 0, upload = 0, compile = 0, trace = 0, shade = 0, readBack = 0,
           other = 0, write = 0;
};

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Millions of rays and pixel samples a second over `totalMs`.
std::pair<double, double> ratesOf(const RenderStats& s, double totalMs) {
    const uint64_t rays = s.primaryRays + s.shadowRays + s.secondaryRays;
    return {totalMs > 0 ? double(rays) / (totalMs * 1e3) : 0.0, totalMs > 0 ? double(s.samples) / (totalMs * 1e-3) : 0.0};
}

// --stats=json: one JSON object a frame (CONTRACT.md, "Statistics").
void printJsonStats(const RenderOptions& o, const Scene& scene, const Acceleration& accel, const RenderOutput& out,
                    double totalMs, std::span<const std::pair<const char*, double>> phases, std::optional<int> frame,
                    uint32_t spp) {
    const RenderStats& s = out.stats;
    const auto [mrays, samplesPerS] = ratesOf(s, totalMs);
    nlohmann::json j;
    if (frame) j["frame"] = *frame;
    j["width"] = out.width;
    j["height"] = out.height;
    j["triangles"] = scene.triangles.size();
    const glm::ivec3 grid = accel.gridResolution;
    j["grid"] = {grid.x, grid.y, grid.z};
    j["grid_source"] = accel.source;
    j["accel"] = accel.name();        // the structure traced; grid is the grid's (or would-be) size
    j["accel_source"] = accel.source;  // built, packed, or auto (built and chosen)
    addAccelJson(j, accel);
    j["rays"] = {{"primary", s.primaryRays}, {"shadow", s.shadowRays}, {"secondary", s.secondaryRays}};
    j["passes"] = nlohmann::json::object();
    for (const auto& [name, p] : KernelStats::global().passes())
        j["passes"][name] = {{"calls", p.calls}, {"fragments", p.fragments}, {"ms", p.gpuMs}};
    j["total_ms"] = totalMs;
    j["mrays_per_s"] = mrays;
    j["backend"] = o.backend;
    j["overflow_rays"] = s.overflowRays;
    j["integrator"] = o.picture.integrator;
    j["samples"] = s.samples;  // pixel samples: width x height x spp
    j["spp"] = spp;
    if (s.denoised) j["denoise"] = {{"ms", s.denoiseMs}, {"refused", s.denoiseRefused}};
    j["mean_spp"] = out.width * out.height > 0 ? double(s.samples) / (double(out.width) * out.height) : 0.0;
    j["sampler"] = o.picture.sampler;
    if (!s.adaptive.empty() || !out.spp.empty()) {
        j["noise_threshold"] = std::stod(o.picture.noiseThreshold);
        j["adaptive"] = nlohmann::json::array();
        for (const AdaptiveRound& r : s.adaptive)
            j["adaptive"].push_back({{"samples", r.samples}, {"active", r.active}, {"ms", r.ms}});
    }
    if (!o.timeLimit.empty()) j["time_limit_s"] = std::stod(o.timeLimit);
    j["samples_per_s"] = samplesPerS;
    if (!s.livePaths.empty()) j["paths_per_bounce"] = s.livePaths;  // paths traced in each round
    j["phases_ms"] = nlohmann::json::object();
    for (const auto& [name, ms] : phases) j["phases_ms"][name] = ms;
    std::printf("%s\n", j.dump().c_str());
}

// `frame`: the frame of an animation (--frames prints one line or block per frame).
// `spp`: the samples a pixel the image has (--spp, or what --time-limit fitted).
void printStats(const RenderOptions& o, const Scene& scene, const Acceleration& accel,
                const RenderOutput& out, double totalMs, const Phases& ph,
                std::optional<int> frame, uint32_t spp) {
    const std::pair<const char*, double> phases[] = {
        {"load", ph.load},       {"normals", ph.normals}, {"grid", ph.grid},   {"context", ph.context}, {"upload", ph.upload},
        {"compile", ph.compile}, {"trace", ph.trace}, {"shade", ph.shade},     {"read_back", ph.readBack},
        {"other", ph.other},     {"write", ph.write}};
    const RenderStats& s = out.stats;
    const auto [mrays, samplesPerS] = ratesOf(s, totalMs);
    if (o.stats == "json") {
        printJsonStats(o, scene, accel, out, totalMs, phases, frame, spp);
        return;
    }
    if (frame) std::printf("frame      %d\n", *frame);
    std::printf("image      %dx%d\n", out.width, out.height);
    std::printf("triangles  %zu\n", scene.triangles.size());
    std::printf("accel      %s (%s)\n", accel.structure->summary().c_str(), accel.source.c_str());
    if (!accel.estimate.empty()) std::printf("estimate   per ray: %s (triangle tests)\n", estimateText(accel).c_str());
    std::printf("rays       %llu primary, %llu shadow, %llu secondary\n", (unsigned long long)s.primaryRays,
                (unsigned long long)s.shadowRays, (unsigned long long)s.secondaryRays);
    std::printf("samples    %llu, %.3g per second (%u a pixel%s)\n", (unsigned long long)s.samples, samplesPerS, spp,
                o.timeLimit.empty() ? "" : ", fitted to --time-limit");
    if (!out.spp.empty()) {
        std::printf("adaptive   %.2f samples a pixel on average; active pixels after", double(s.samples) / (double(out.width) * out.height));
        for (const AdaptiveRound& r : s.adaptive) std::printf(" %u: %llu", r.samples, (unsigned long long)r.active);
        std::printf("\n");
    }
    if (!s.livePaths.empty()) {
        std::printf("paths      per bounce:");
        for (uint64_t n : s.livePaths) std::printf(" %llu", (unsigned long long)n);
        std::printf("\n");
    }
    if (s.overflowRays) std::printf("overflow   %llu rays hit the step limit\n", (unsigned long long)s.overflowRays);
    if (!KernelStats::global().passes().empty()) {
        std::printf("%-16s %8s %14s %10s\n", "pass", "calls", "fragments", "ms");
        for (const auto& [name, p] : KernelStats::global().passes())
            std::printf("%-16s %8llu %14llu %10.2f\n", name.c_str(), (unsigned long long)p.calls,
                        (unsigned long long)p.fragments, p.gpuMs);
    }
    std::printf("phases    ");
    for (const auto& [name, ms] : phases) std::printf(" %s %.1f", name, ms);
    std::printf(" ms\n");
    std::printf("total      %.1f ms, %.2f Mrays/s\n", totalMs, mrays);
}

// The files of one frame (or of the only image): the PNG, then each AOV's.
struct OutputFiles {
    std::string png;
    std::map<std::string, std::string> aovs;
};

bool isExr(const std::string& file) { return lowerExtension(file) == ".exr"; }

// Writes a render's outputs (and their tile sidecars when `tile`) together: all appear or none.
// OUT.png: the tone-mapped sRGB picture; OUT.exr: the linear colour times 2^EV as half floats.
// An AOV file: PFM, or EXR (32-bit float channels) by its name.
// spp: the samples a pixel of a render without adaptive sampling (the spp AOV).
// picture: the colour of the PNG or EXR (the denoised one), out.color otherwise.
void writeOutputs(const OutputFiles& files, const RenderOutput& out, const ColourSettings& colour, TileInfo* tile,
                  uint32_t spp, const std::vector<glm::vec3>* picture = nullptr) {
    const std::vector<glm::vec3>& shown = picture ? *picture : out.color;
    AtomicFileSet outputs;
    auto flat3 = [](const std::vector<glm::vec3>& values, float scale) {
        std::vector<float> flat;
        flat.reserve(values.size() * 3);
        for (const glm::vec3& v : values) flat.insert(flat.end(), {v.x * scale, v.y * scale, v.z * scale});
        return flat;
    };
    // An EXR file and its sidecar, whose CRC covers the values as the file stores them.
    auto exr = [&](const std::string& file, const std::string& output, const std::vector<float>& values) {
        const ExrLayout layout = exrLayout(output);
        writeExr(outputs, file, out.width, out.height, layout, values);
        if (tile) {
            const std::vector<float> stored = exrStored(layout, values);
            tile->output = output;
            tile->crc = crc32Of(stored.data(), stored.size() * sizeof(float));
            addTileSidecar(outputs, file, *tile);
        }
    };
    if (isExr(files.png)) {
        exr(files.png, "exr", flat3(shown, exposureScale(colour.exposure)));
    } else {
        const std::vector<glm::vec3> display = toneMapImage(shown, colour);
        writePng(outputs, files.png, out.width, out.height, display);
        if (tile) {
            std::vector<unsigned char> rgb;
            rgb.reserve(display.size() * 3);
            for (const glm::vec3& c : display) rgb.insert(rgb.end(), {linearToSrgb8(c.x), linearToSrgb8(c.y), linearToSrgb8(c.z)});
            tile->output = "png";
            tile->crc = crc32Of(rgb.data(), rgb.size());
            addTileSidecar(outputs, files.png, *tile);
        }
    }
    const std::map<std::string, const std::vector<glm::vec3>*> vectors = {
        {"normal", &out.normal}, {"color", &out.color}, {"variance", &out.variance},
        {"albedo", &out.albedo}, {"shading_normal", &out.shadingNormal}};
    for (const auto& [name, file] : files.aovs) {
        std::vector<float> flat;
        int channels = 1;
        if (name == "depth") flat = out.depth;
        if (name == "prim") flat = out.prim;
        if (name == "steps") flat = out.steps;
        if (name == "spp")  // the samples each pixel took: --spp everywhere without adaptive sampling
            flat = out.spp.empty() ? std::vector<float>(size_t(out.width) * size_t(out.height), float(spp)) : out.spp;
        if (const auto v = vectors.find(name); v != vectors.end()) {
            flat = flat3(*v->second, 1.0f);
            channels = 3;
        }
        if (isExr(file)) {
            exr(file, name, flat);
            continue;
        }
        writePfm(outputs, file, out.width, out.height, channels, flat);
        if (tile) {
            tile->output = name;
            tile->crc = crc32Of(flat.data(), flat.size() * sizeof(float));
            addTileSidecar(outputs, file, *tile);
        }
    }
    outputs.commit();
}

// The files of the render: -o and each --aov NAME=FILE, checked before anything is rendered.
OutputFiles outputNames(const RenderOptions& o) {
    OutputFiles names;
    names.png = o.output;
    for (const std::string& a : o.aovs) {
        const size_t eq = a.find('=');
        const std::string name = a.substr(0, eq);
        if (eq == std::string::npos || eq + 1 == a.size())
            throw InputError("--aov: '" + a + "' is not NAME=FILE");
        if (name != "depth" && name != "prim" && name != "normal" && name != "steps" && name != "color" && name != "spp" &&
            name != "variance" && name != "albedo" && name != "shading_normal")
            throw InputError("--aov: unknown AOV '" + name +
                             "' (depth, prim, normal, steps, color, spp, variance, albedo, shading_normal)");
        if (names.aovs.count(name)) throw InputError("--aov: " + name + " given twice");
        names.aovs[name] = a.substr(eq + 1);
    }
    return names;
}

// --frames A:B, or the only image: which frames and each frame's file names (every name holds
// the frame number when animated).
struct Frames {
    bool animated = false;
    int first = 0, last = 0;
    OutputFiles names;

    OutputFiles files(int frame) const {
        if (!animated) return names;
        OutputFiles f{frameFileName(names.png, frame), {}};
        for (const auto& [name, file] : names.aovs) f.aovs[name] = frameFileName(file, frame);
        return f;
    }
};

// The frames and their names, checked (the first frame's paths must be writable).
Frames renderFrames(const RenderOptions& o) {
    Frames frames;
    frames.names = outputNames(o);
    frames.animated = !o.frames.empty();
    if (frames.animated) {
        parseFrames(o.frames, frames.first, frames.last);
        checkFramePattern("-o", frames.names.png);
        for (const auto& [name, file] : frames.names.aovs) checkFramePattern("--aov " + name, file);
    }
    const OutputFiles first = frames.files(frames.first);
    std::vector<std::filesystem::path> outputPaths = {first.png};
    for (const auto& [name, file] : first.aovs) outputPaths.push_back(file);
    checkOutputPaths(outputPaths);
    return frames;
}

// Every frame's camera, before anything is rendered (an interpolated camera can be unusable), each
// for the tile's rows when `tile` (its place filled in).
std::vector<CameraBasis> frameCameras(const RenderOptions& o, const Frames& frames, const LoadedScene& loaded,
                                      glm::ivec2 size, int scaleExponent, TileInfo* tile) {
    if (tile) parseTile(o.tile, size.y, tile->tile, tile->tiles);
    std::vector<CameraBasis> cameras;
    for (int frame = frames.first; frame <= frames.last; ++frame) {
        try {
            cameras.push_back(o.camera.camera(loaded.scene, size, scaleExponent,
                                              frames.animated ? std::optional(frame) : std::nullopt));
        } catch (const InputError& e) {
            if (!frames.animated) throw;
            throw InputError(o.scene + ": frame " + std::to_string(frame) + ": " + e.what());
        }
        if (tile) tileRows(size.y, tile->tile, tile->tiles, cameras.back().rowBegin, cameras.back().rowCount);
    }
    if (tile) {
        tile->width = size.x;
        tile->height = size.y;
        tile->row = cameras.front().rowBegin;
        tile->rows = cameras.front().rowCount;
    }
    return cameras;
}

// --time-limit SECONDS (> 0), or 0 when not given. Tiles refuse it: the tiles of one image must
// take the same samples, and each tile would fit its own count to the time.
double parseTimeLimit(const RenderOptions& o) {
    if (o.timeLimit.empty()) return 0.0;
    const float seconds = parseFiniteFloat("--time-limit", o.timeLimit);
    if (!(seconds > 0.0f)) throw InputError("--time-limit: " + o.timeLimit + " is not a positive number of seconds");
    if (!o.tile.empty())
        throw InputError("--time-limit: not with --tile (the tiles of one image must take the same samples: give "
                         "--spp, e.g. the count a --time-limit render of the whole image printed)");
    return double(seconds);
}

// The rows [first, first + count) of a render's outputs.
void keepRows(RenderOutput& out, int first, int count) {
    auto crop = [&](auto& values) {
        if (values.empty()) return;
        const auto begin = values.begin() + std::ptrdiff_t(first) * out.width;
        values = std::vector<typename std::decay_t<decltype(values)>::value_type>(begin, begin + std::ptrdiff_t(count) * out.width);
    };
    crop(out.color), crop(out.depth), crop(out.prim), crop(out.normal), crop(out.steps), crop(out.spp), crop(out.variance);
    crop(out.albedo), crop(out.shadingNormal);
    out.height = count;
    if (!out.spp.empty()) {  // the samples of the rows kept
        out.stats.samples = 0;
        for (float n : out.spp) out.stats.samples += uint64_t(n);
    }
}

// A render of the camera's rows. Under adaptive sampling a tile's pixels (--tile) stop as the
// whole image's do only if their neighbours' sums are the whole image's too: a pixel's decision
// looks at its neighbours, theirs at theirs, one row further at each convergence pass. So a tile
// renders as many rows more above and below it as there are passes (within the image) and keeps
// its own.
RenderOutput renderRows(Renderer& renderer, const CameraBasis& camera, const RenderSettings& settings) {
    if (!settings.adaptive() || camera.rowCount == 0 || settings.samples < 2) return renderer.render(camera, settings);
    int passes = 0;
    for (uint32_t taken = settings.minSamples; taken < settings.samples; ++taken) passes += adaptiveCheckAfter(taken, settings);
    CameraBasis wide = camera;
    wide.rowBegin = std::max(0, camera.rowBegin - passes);
    wide.rowCount = std::min(camera.height, camera.rowBegin + camera.rowCount + passes) - wide.rowBegin;
    RenderOutput out = renderer.render(wide, settings);
    keepRows(out, camera.rowBegin - wide.rowBegin, camera.rowCount);
    return out;
}

// One frame's image (or the only image) and its samples a pixel: settings.samples, or with
// --time-limit (timeLimit > 0) the most that fit, printed, with --spp when given as their most.
// `progress` sees the frame's part of all the frames.
RenderOutput renderFrame(const RenderOptions& o, Renderer& renderer, const CameraBasis& camera, RenderSettings settings,
                         const Frames& frames, int frame, double timeLimit, ProgressDisplay& progress, uint32_t& spp) {
    const int index = frame - frames.first, frameCount = frames.last - frames.first + 1;
    if (progress.mode() != ProgressDisplay::Mode::Off)
        settings.progress = [&progress, index, frameCount](double f) {
            progress.update((double(index) + f) / double(frameCount));
        };
    if (progress.mode() != ProgressDisplay::Mode::Off && settings.adaptive())
        settings.adaptiveProgress = [&progress](uint32_t, uint64_t active) { progress.setActive(active); };
    spp = settings.samples;
    if (!(timeLimit > 0)) return renderRows(renderer, camera, settings);
    const bool sppGiven = o.picture.sppOption && o.picture.sppOption->count() > 0;
    TimedRender timed = renderWithinTime(renderer, camera, settings, timeLimit, sppGiven ? settings.samples : 1u << 24);
    spp = timed.samples;
    const std::string which = frames.animated ? "frame " + std::to_string(frame) + ": " : "";
    std::fprintf(stderr, "gpurt: %s%u samples a pixel in the time limit of %s s (--spp %u renders this image)\n",
                 which.c_str(), spp, o.timeLimit.c_str(), spp);
    return std::move(timed.output);
}

// The settings of every frame: the picture options', and what the --aov files and --denoise
// need computed (the AOVs' rays, the squares summed, the path integrator's features); InputError
// for an AOV or --denoise the integrator or --tile cannot give.
RenderSettings frameSettings(const RenderOptions& o, const PictureCliOptions::Values& picture, const Frames& frames,
                             glm::ivec2 size, const Scene& scene, int scaleExponent) {
    RenderSettings settings = PictureCliOptions::settings(picture, size, o.bounces, scene, scaleExponent);
    settings.aovs = !o.aovs.empty();  // the AOVs' rays and read-backs only when an --aov asks for them
    settings.variance = frames.names.aovs.count("variance") > 0;  // the squares summed only for that AOV
    settings.features = frames.names.aovs.count("albedo") > 0 || frames.names.aovs.count("shading_normal") > 0;
    const bool tiled = !o.tile.empty();
    const bool features = integratorInfo(settings.integrator).features;
    if (settings.features && !features)
        throw InputError("--aov albedo, shading_normal: the path integrator's features (--integrator path)");
    if (o.denoise) {  // the filter's guides: these AOVs, as gpurt denoise reads them from files
        if (!features)
            throw InputError("--denoise: needs --integrator path (its features guide the filter)");
        if (tiled)
            throw InputError("--denoise: not with --tile (the filter looks across tiles: stitch the color, albedo, "
                             "shading_normal, depth and variance AOVs, then gpurt denoise; docs/FARM.md)");
        settings.features = settings.variance = settings.aovs = true;
    }
    return settings;
}

// The frame's colour denoised (out's AOVs guide it), its counts in out's statistics.
std::vector<glm::vec3> denoiseFrame(Backend backend, const RenderSettings& settings, RenderOutput& out) {
    DenoiseStats ds;
    std::vector<glm::vec3> denoised = denoise(backend, denoiseImages(out), settings.threads, &ds);
    out.stats.denoised = true;
    out.stats.denoiseRefused = ds.refused;
    out.stats.denoiseMs = ds.ms;
    if (ds.refused > 0)
        std::fprintf(stderr, "gpurt: warning: the denoiser refused %llu pixels that are not finite\n",
                     (unsigned long long)ds.refused);
    return denoised;
}

int runRender(const RenderOptions& o) {
    // Everything that can be refused is checked before anything is rendered or written.
    const Frames frames = renderFrames(o);
    const PictureCliOptions::Values picture = o.picture.values();
    const Backend backend = o.backend == "cpu" ? Backend::Cpu : Backend::Gl;
    const double timeLimit = parseTimeLimit(o);
    const int frameCount = frames.last - frames.first + 1;
    ProgressDisplay progress(o.progress.mode(), timeLimit > 0 ? 0.0 : double(frameCount) * picture.samples, "spp");

    Phases phases;
    auto phaseStart = std::chrono::steady_clock::now();
    int scaleExponent = 0;  // depths are scaled back below
    LoadedScene loaded = loadSceneToRender(o.scene, o.camera.upAxis, picture.crease, scaleExponent, &phases.normals);
    applyEnvironmentOptions(loaded.scene, picture);
    phases.load = msSince(phaseStart) - phases.normals;
    const Scene& scene = loaded.scene;
    if (frames.animated && !scene.animation)
        throw InputError("--frames: " + o.scene + " has no camera animation (a JSON scene's \"animation\")");
    const glm::ivec2 size = o.camera.imageSize(loaded.size);
    checkRenderFitsInMemory(size, backend, picture.integrator);
    TileInfo tile;
    const bool tiled = !o.tile.empty();
    const std::vector<CameraBasis> cameras = frameCameras(o, frames, loaded, size, scaleExponent, tiled ? &tile : nullptr);
    const RenderSettings settings = frameSettings(o, picture, frames, size, scene, scaleExponent);

    const auto start = std::chrono::steady_clock::now();
    const Acceleration accel = o.grid.accelerate(loaded, cameras.front());
    phases.grid = msSince(start);
    // The GL context, the kernels and the scene textures serve every frame.
    std::optional<GLContext> context;
    if (backend == Backend::Gl) {
        phaseStart = std::chrono::steady_clock::now();
        context.emplace(o.context.makeContext());
        phases.context = msSince(phaseStart);
        KernelStats::global().setTiming(o.statsGiven);
    }
    phaseStart = std::chrono::steady_clock::now();
    const std::unique_ptr<Renderer> renderer =
        makeRenderer(RendererConfig{backend, picture.integrator, o.tracer.options()}, scene, accel);
    if (backend == Backend::Gl) phases.upload = msSince(phaseStart);
    for (int frame = frames.first; frame <= frames.last; ++frame) {
        const CameraBasis& camera = cameras[size_t(frame - frames.first)];
        const auto frameStart = std::chrono::steady_clock::now();
        phaseStart = std::chrono::steady_clock::now();
        uint32_t spp = 1;
        RenderOutput out = renderFrame(o, *renderer, camera, settings, frames, frame, timeLimit, progress, spp);
        const double renderMs = msSince(phaseStart);
        const RenderPhases ran = renderer->phases();
        phases.compile = ran.compile;
        phases.trace = ran.trace;
        phases.shade = ran.shade;
        phases.readBack = ran.readBack;
        if (backend == Backend::Gl)
            phases.other = std::max(0.0, renderMs - ran.compile - ran.readBack - ran.trace - ran.shade);
        // The first frame's total counts the set-up (grid, context, upload); later frames their own.
        const double totalMs = msSince(frame == frames.first ? start : frameStart);
        unscaleDepth(out.depth, scaleExponent);
        if (out.stats.overflowRays > 0)  // never for a correct traversal: say so rather than hide it
            std::fprintf(stderr, "gpurt: warning: %llu rays reached the traversal limit of the %s "
                         "and were counted as misses\n", (unsigned long long)out.stats.overflowRays,
                         std::string(accel.name()).c_str());

        const auto writeStart = std::chrono::steady_clock::now();
        if (tiled) tile.fingerprint = renderFingerprint(scene, camera, accel, settings, o.picture, o.backend);
        const std::vector<glm::vec3> denoised = o.denoise ? denoiseFrame(backend, settings, out) : std::vector<glm::vec3>{};
        writeOutputs(frames.files(frame), out, picture.colour, tiled ? &tile : nullptr, spp, o.denoise ? &denoised : nullptr);
        phases.write = msSince(writeStart);
        if (o.statsGiven)
            printStats(o, scene, accel, out, totalMs, phases,
                       frames.animated ? std::optional(frame) : std::nullopt, spp);
        phases = Phases{};
        if (frames.animated) progress.mark();
    }
    progress.finish();
    return 0;
}

}  // namespace

void addRenderCommand(CLI::App& app, std::function<int()>& run) {
    auto o = std::make_shared<RenderOptions>();
    auto* cmd = app.add_subcommand(
        "render", "Render a scene (.obj with its .mtl, .json, .gltf/.glb, .ply or packed .gpscene) to a PNG or EXR");
    cmd->add_option("scene", o->scene, "Scene file: .obj, .json, .gltf, .glb, .ply or .gpscene (gpurt pack)")
        ->required()
        ->check(kNotEmpty);
    cmd->add_option("-o,--output", o->output,
                    "Output: .png (8-bit sRGB, tone mapped) or .exr (linear half-float RGB); with --frames the "
                    "name holds %04d")
        ->required()
        ->check(kNotEmpty);
    cmd->add_option("--aov", o->aovs,
                    "Also write an AOV: depth|prim|normal|steps|color|spp|variance|albedo|shading_normal=FILE, FILE .pfm "
                    "or .exr (32-bit float); spp: the samples each pixel took; variance: of each pixel's mean, per "
                    "channel; albedo, shading_normal: the denoiser's features (path integrator)");
    cmd->add_option("--backend", o->backend, "gl (stream kernels, default) or cpu (same algorithm in C++)")
        ->check(CLI::IsMember({"gl", "cpu"}));
    auto* stats = cmd->add_option("--stats", o->stats, "Print statistics (--stats=json: one JSON object)")
                      ->expected(0, 1)
                      ->check(CLI::IsMember({"", "text", "json"}));
    cmd->add_option("--tile", o->tile,
                    "Render only tile I of N (rows of the image in N balanced bands) with the whole image's "
                    "camera and samples; each output gets a FILE.tile sidecar for gpurt stitch")
        ->check(kNotEmpty);
    cmd->add_option("--frames", o->frames,
                    "Render frames A to B of the scene's camera animation; -o and each --aov file hold the "
                    "frame number as %04d (or %d)")
        ->check(kNotEmpty);
    cmd->add_option("--time-limit", o->timeLimit,
                    "Take as many whole samples a pixel as fit in SECONDS of rendering (at least one; --spp, when "
                    "given, is the most); the count is printed, and the image is the --spp image of that count. "
                    "Not with --tile")
        ->check(kNotEmpty);
    o->progress.add(*cmd);
    cmd->add_flag("--denoise", o->denoise,
                  "Denoise the picture (path integrator): an a-trous filter guided by the albedo, shading normal, "
                  "depth and variance AOVs (the color AOV stays the raw mean); gpurt denoise does the same on files");
    cmd->add_option("--bounces", o->bounces, "Whitted: mirror and glass levels (default: the scene's, 3); path: the longest path in hits (default " + std::to_string(kDefaultPathBounces) + ")")
        ->check(CLI::Range(0, 64));
    o->picture.add(*cmd);
    o->tracer.add(*cmd);
    o->grid.add(*cmd);
    o->camera.add(*cmd);
    addContextOptions(*cmd, o->context);
    cmd->callback([&run, o, stats] {
        o->statsGiven = stats->count() > 0;
        run = [o] { return runRender(*o); };
    });
}

}  // namespace gpurt
