// `gpurt bench SCENE --rays primary|shadow`: the tracing speed of the stream kernels (gl), the
// same algorithm in C++ (cpu) and Intel Embree (embree), on the same rays in the same run.
// Only the tracing is timed: the scene is loaded, the grid built, the kernels compiled and one
// warm-up run done first; the figure is the median of --runs runs.
#include "Commands.h"
#include "CommonOptions.h"

#include "raytrace/accel/BenchRays.h"
#include "raytrace/render/CpuTracer.h"
#include "raytrace/render/GpuTracer.h"
#include "raytrace/render/Renderer.h"
#include "base/Parallel.h"
#include "raytrace/scene/SceneLoader.h"
#include "raytrace/accel/GlRegistry.h"
#include "raytrace/accel/grid/GridAccelerator.h"
#include "stream/KernelStats.h"
#ifdef GPURT_HAVE_EMBREE
#include "raytrace/accel/EmbreeTracer.h"
#endif

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <optional>

namespace gpurt {

namespace {

struct BenchOptions {
    std::string scene;
    std::string rays = "primary";
    std::vector<std::string> backends;
    bool json = false;
    int runs = 5;
    int threads = 0;
    TracerCliOptions tracer;
    GridCliOptions grid;
    CameraOptions camera;
    ContextOptions context;
};

struct BenchResult {
    std::string backend;
    std::string renderer;
    int threads = 0;
    uint64_t rays = 0;
    double ms = 0.0;  // median
    std::vector<double> runMs;
    nlohmann::json passes = nlohmann::json::object();
    std::vector<glm::vec4> hits;
    double agreement = -1.0;  // fraction of rays whose result matches the reference backend's
};

double elapsedMs(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// One warm-up call, then `runs` timed calls; sets rays, runMs and the median ms.
void measure(BenchResult& r, int runs, const std::function<uint64_t()>& traceOnce) {
    r.rays = traceOnce();
    r.runMs.clear();
    for (int i = 0; i < runs; ++i) {
        const auto start = std::chrono::steady_clock::now();
        traceOnce();
        r.runMs.push_back(elapsedMs(start));
    }
    std::vector<double> sorted = r.runMs;
    std::sort(sorted.begin(), sorted.end());
    const size_t m = sorted.size() / 2;
    r.ms = sorted.size() % 2 ? sorted[m] : 0.5 * (sorted[m - 1] + sorted[m]);
}

double mraysPerSecond(const BenchResult& r) { return r.ms > 0.0 ? double(r.rays) / (r.ms * 1e3) : 0.0; }

std::string glRenderer() {
    for (const auto& [name, value] : glInfo())
        if (name == "renderer") return value;
    return "unknown";
}

// llvmpipe's rasterizer threads (LP_NUM_THREADS, else one per core); 0 for a hardware GPU.
int glThreads() {
    if (!isSoftwareRenderer()) return 0;
    if (const char* env = std::getenv("LP_NUM_THREADS")) return std::max(0, std::atoi(env));
    return resolveThreads(0);
}

struct BenchInput {
    const Scene& scene;
    const Acceleration& accel;
    const CameraBasis& camera;
    bool shadow;
    const RayStream& rays;
};

BenchResult benchGl(const BenchOptions& o, const BenchInput& in) {
    BenchResult r;
    r.backend = "gl";
    GLContext context = o.context.makeContext();
    r.renderer = glRenderer();
    r.threads = glThreads();
    const GpuTracerOptions options = o.tracer.options();
    GpuTracer tracer(in.scene, makeGlAccelerator(in.scene, in.accel, options), in.accel.rayOffset(), options);
    std::function<uint64_t()> traceOnce = [&] { return tracer.tracePrimary(in.camera); };
    if (in.shadow) {
        tracer.setRays(in.rays);
        traceOnce = [&] { return tracer.traceRays(true); };
    }
    KernelStats::global().setTiming(false);
    measure(r, o.runs, traceOnce);
    r.hits = tracer.hits();
    // One more run with per-pass GPU timers, for the pass table (timers cost a little).
    tracer.flushStats();
    KernelStats::global().reset();
    KernelStats::global().setTiming(true);
    traceOnce();
    tracer.flushStats();
    KernelStats::global().setTiming(false);
    for (const auto& [name, p] : KernelStats::global().passes())
        if (p.calls > 0) r.passes[name] = {{"calls", p.calls}, {"fragments", p.fragments}, {"ms", p.gpuMs}};
    r.renderer += std::string(", ") + std::string(in.accel.name());
    if (gridOf(in.accel.structure)) r.renderer += std::string(", ") + traceKernelName(options.kernel) + " kernel";
    return r;
}

BenchResult benchCpu(const BenchOptions& o, const BenchInput& in) {
    BenchResult r;
    r.backend = "cpu";
    r.threads = resolveThreads(o.threads);
    r.renderer = std::string("gpurt C++ ") + std::string(in.accel.name()) + " tracer";
    const CpuTracer tracer(in.scene, makeCpuAccelerator(in.scene, in.accel), in.accel.rayOffset());
    measure(r, o.runs, [&] { return tracer.traceStream(in.rays, in.shadow, r.threads, r.hits); });
    return r;
}

#ifdef GPURT_HAVE_EMBREE
// Embree's best of single rays and 8- and 16-ray packets (packets are its fastest way for
// coherent rays; 16 wide uses AVX-512 where the CPU has it).
BenchResult benchEmbree(const BenchOptions& o, const BenchInput& in) {
    const EmbreeTracer tracer(in.scene, resolveThreads(o.threads));
    BenchResult best;
    for (const auto& [mode, width] : {std::pair{EmbreeMode::Single, "1"}, {EmbreeMode::Packet8, "8"},
                                      {EmbreeMode::Packet16, "16"}}) {
        BenchResult r;
        r.backend = "embree";
        r.threads = tracer.threads();
        const std::string call = std::string(in.shadow ? "rtcOccluded" : "rtcIntersect") + width;
        r.renderer = "Embree " + EmbreeTracer::version() + ", " + call + ", high-quality BVH";
        measure(r, o.runs, [&] { return tracer.trace(in.rays, in.shadow, mode, r.hits); });
        if (best.rays == 0 || r.ms < best.ms) best = std::move(r);
    }
    return best;
}
#endif

std::vector<std::string> availableBackends() {
#ifdef GPURT_HAVE_EMBREE
    return {"embree", "cpu", "gl"};
#else
    return {"cpu", "gl"};
#endif
}

// The fraction of rays whose outcome agrees: the same triangle for closest hits, the same
// blocked / unblocked answer for shadow rays.
double agreement(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b, const RayStream& rays, bool shadow) {
    uint64_t same = 0, total = 0;
    for (size_t i = 0; i < rays.tLimit.size() && i < a.size() && i < b.size(); ++i) {
        if (rays.tLimit[i] < 0.0f) continue;
        ++total;
        same += shadow ? (a[i].w >= 0.0f) == (b[i].w >= 0.0f) : a[i].w == b[i].w;
    }
    return total ? double(same) / double(total) : 1.0;
}

nlohmann::json resultJson(const BenchResult& r, const BenchResult* embree) {
    nlohmann::json j;
    j["backend"] = r.backend;
    j["mrays_per_s"] = mraysPerSecond(r);
    j["rays"] = r.rays;
    j["ms"] = r.ms;
    j["runs_ms"] = r.runMs;
    j["passes"] = r.passes;
    j["threads"] = r.threads;
    j["renderer"] = r.renderer;
    if (embree) j["ratio_to_embree"] = mraysPerSecond(*embree) > 0 ? mraysPerSecond(r) / mraysPerSecond(*embree) : 0.0;
    if (r.agreement >= 0.0) j["agreement"] = r.agreement;
    return j;
}

// The results as one JSON object (--json): the backend's fields at the top for one backend, a
// list of them for several.
void printBenchJson(const BenchOptions& o, const BenchInput& in, double gridMs, const std::vector<BenchResult>& results,
                    const BenchResult* embree) {
    nlohmann::json j;
    if (results.size() == 1) j = resultJson(results.front(), embree);
    j["scene"] = o.scene;
    j["triangles"] = in.scene.triangles.size();
    const glm::ivec3 grid = in.accel.gridResolution;
    j["grid"] = {grid.x, grid.y, grid.z};
    j["grid_ms"] = gridMs;  // the acceleration structure's build (both, for auto)
    j["accel"] = in.accel.name();
    j["accel_source"] = in.accel.source;
    addAccelJson(j, in.accel);
    j["width"] = in.camera.width;
    j["height"] = in.camera.height;
    j["ray_kind"] = o.rays;
    j["runs"] = o.runs;
    if (results.size() > 1) {
        j["backends"] = nlohmann::json::array();
        for (const BenchResult& r : results) j["backends"].push_back(resultJson(r, embree));
    }
    std::printf("%s\n", j.dump().c_str());
}

// The results as a table, then each backend's passes.
void printBenchTable(const BenchOptions& o, const BenchInput& in, double gridMs,
                     const std::vector<BenchResult>& results, const BenchResult* embree) {
    const CameraBasis& camera = in.camera;
    const uint64_t rayCount = in.rays.rays();
    const Acceleration& a = in.accel;
    std::printf("scene    %s: %zu triangles, %s (%s in %.0f ms)\n", o.scene.c_str(), in.scene.triangles.size(),
                a.structure->summary().c_str(), a.source.c_str(), gridMs);
    if (!a.estimate.empty()) std::printf("auto     estimated cost per ray: %s\n", estimateText(a).c_str());
    std::printf("rays     %s, %llu rays (%dx%d image), median of %d runs after a warm-up\n", o.rays.c_str(),
                (unsigned long long)rayCount, camera.width, camera.height, o.runs);
    std::printf("%-8s %7s %10s %10s %9s %9s  %s\n", "backend", "threads", "ms", "Mrays/s", "x embree", "agree",
                "renderer");
    for (const BenchResult& r : results) {
        char ratio[32] = "-", agree[32] = "-";
        if (embree) std::snprintf(ratio, sizeof ratio, "%.3f", mraysPerSecond(r) / std::max(1e-12, mraysPerSecond(*embree)));
        if (r.agreement >= 0.0) std::snprintf(agree, sizeof agree, "%.4f%%", 100.0 * r.agreement);
        std::printf("%-8s %7d %10.2f %10.2f %9s %9s  %s\n", r.backend.c_str(), r.threads, r.ms, mraysPerSecond(r),
                    ratio, agree, r.renderer.c_str());
    }
    for (const BenchResult& r : results) {
        if (r.passes.empty()) continue;
        std::printf("%s passes (one extra run with GPU timers)\n", r.backend.c_str());
        std::printf("  %-14s %8s %14s %10s\n", "pass", "calls", "fragments", "ms");
        for (const auto& [name, p] : r.passes.items())
            std::printf("  %-14s %8llu %14llu %10.2f\n", name.c_str(), (unsigned long long)p["calls"].get<uint64_t>(),
                        (unsigned long long)p["fragments"].get<uint64_t>(), p["ms"].get<double>());
    }
}

int runBench(const BenchOptions& o) {
    o.tracer.options();  // refuses a bad --mask before any work
    std::vector<std::string> backends = o.backends.empty() ? availableBackends() : o.backends;
    const std::vector<std::string> available = availableBackends();
    for (const std::string& b : backends)
        if (std::find(available.begin(), available.end(), b) == available.end())
            throw InputError("--backend: '" + b + "' is not available in this build (embree needs GPURT_WITH_EMBREE)");

    LoadedScene loaded = loadScene(o.scene);
    turnSceneUp(loaded, o.camera.upAxis);
    const Scene& scene = loaded.scene;
    const glm::ivec2 size = o.camera.imageSize(loaded.size);
    const CameraBasis camera = o.camera.camera(scene, size);
    const bool shadow = o.rays == "shadow";

    auto start = std::chrono::steady_clock::now();
    const Acceleration accel = o.grid.accelerate(loaded, camera);
    const double gridMs = elapsedMs(start);

    RayStream rays = primaryRays(camera);
    if (shadow) {
        // Shadow rays from the primary hits (found by the C++ tracer, untimed) to the scene's
        // first light, or the headlight at the eye.
        std::vector<glm::vec4> hits;
        CpuTracer(scene, makeCpuAccelerator(scene, accel), accel.rayOffset()).traceStream(rays, false, o.threads, hits);
        rays = shadowRays(scene, accel.rayOffset(), rays, hits, shadowRayTarget(scene, camera.eye));
    }
    const BenchInput input{scene, accel, camera, shadow, rays};

    std::vector<BenchResult> results;
    for (const std::string& b : backends) {
        if (b == "gl") results.push_back(benchGl(o, input));
        if (b == "cpu") results.push_back(benchCpu(o, input));
#ifdef GPURT_HAVE_EMBREE
        if (b == "embree") results.push_back(benchEmbree(o, input));
#endif
    }
    const BenchResult* embree = nullptr;
    for (const BenchResult& r : results)
        if (r.backend == "embree") embree = &r;
    const BenchResult& reference = embree ? *embree : results.front();
    if (results.size() > 1)
        for (BenchResult& r : results)
            if (&r != &reference) r.agreement = agreement(r.hits, reference.hits, rays, shadow);

    if (o.json) printBenchJson(o, input, gridMs, results, embree);
    else printBenchTable(o, input, gridMs, results, embree);
    return 0;
}

}  // namespace

void addBenchCommand(CLI::App& app, std::function<int()>& run) {
    auto o = std::make_shared<BenchOptions>();
    auto* cmd = app.add_subcommand("bench", "Time tracing alone: the stream kernels beside the C++ tracer and Embree");
    cmd->add_option("scene", o->scene, "Scene file: .obj, .json, .gltf, .glb, .ply or .gpscene (gpurt pack)")->required();
    cmd->add_option("--rays", o->rays, "primary (one per pixel) or shadow (one per primary hit, to one light)")
        ->check(CLI::IsMember({"primary", "shadow"}));
    cmd->add_option("--backend", o->backends, "gl, cpu or embree (repeatable; default: all available)")
        ->check(CLI::IsMember({"gl", "cpu", "embree"}));
    cmd->add_flag("--json", o->json, "Print one JSON object instead of the table");
    cmd->add_option("--runs", o->runs, "Timed runs after the warm-up (the median is reported)")->check(CLI::Range(1, 1000));
    cmd->add_option("--threads", o->threads, "Threads of the cpu and embree backends (0: one per core)")
        ->check(CLI::Range(0, 1024));
    o->tracer.add(*cmd);
    o->grid.add(*cmd);
    o->camera.add(*cmd);
    addContextOptions(*cmd, o->context);
    cmd->callback([&run, o] { run = [o] { return runBench(*o); }; });
}

}  // namespace gpurt
