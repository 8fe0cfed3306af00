#include "raytrace/render/Renderer.h"

#include "raytrace/integrators/Registry.h"

#include "raytrace/render/CpuTracer.h"
#include "raytrace/render/GpuTracer.h"
#include "raytrace/accel/GlRegistry.h"
#include "raytrace/accel/grid/GridCpu.h"
#include "raytrace/accel/grid/GridGl.h"
#include "stream/KernelStats.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>

namespace gpurt {

namespace {

class CpuRenderer final : public Renderer {
  public:
    CpuRenderer(const RendererConfig& config, const Scene& scene, std::unique_ptr<CpuAccelerator> accel,
                float rayOffset)
        : config_(config), tracer_(scene, std::move(accel), rayOffset) {}

    RenderOutput render(const CameraBasis& camera, const RenderSettings& settings) override {
        RenderSettings s = settings;
        s.integrator = config_.integrator;
        const auto start = std::chrono::steady_clock::now();
        RenderOutput out = tracer_.render(camera, s);
        phases_.trace = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        return out;
    }
    RenderPhases phases() const override { return phases_; }

  private:
    RendererConfig config_;
    CpuTracer tracer_;
    RenderPhases phases_;
};

class GlRenderer final : public Renderer, public ProgressiveRenderer {
  public:
    GlRenderer(const RendererConfig& config, const Scene& scene, std::unique_ptr<GlAccelerator> accel,
               float rayOffset)
        : config_(config), tracer_(scene, std::move(accel), rayOffset, config.gl) {}

    RenderOutput render(const CameraBasis& camera, const RenderSettings& settings) override {
        RenderSettings s = settings;
        s.integrator = config_.integrator;
        KernelStats& kernels = KernelStats::global();
        kernels.reset();
        const double compileBefore = kernels.compileMs, readBackBefore = kernels.readBackMs;
        RenderOutput out = tracer_.render(camera, s);
        phases_ = RenderPhases{};
        phases_.compile = kernels.compileMs - compileBefore;
        phases_.readBack = kernels.readBackMs - readBackBefore;
        const std::set<std::string> tracing = tracer_.accelerationPasses();
        for (const auto& [name, p] : kernels.passes()) (tracing.count(name) ? phases_.trace : phases_.shade) += p.gpuMs;
        return out;
    }
    RenderPhases phases() const override { return phases_; }
    ProgressiveRenderer* progressive() override { return this; }

    void begin(const CameraBasis& camera, const RenderSettings& settings) override {
        RenderSettings s = settings;
        s.integrator = config_.integrator;
        tracer_.beginProgressive(camera, s);
    }
    void addSample(uint32_t s, uint32_t n) override { tracer_.addSample(s, n); }
    void bindDisplay(GPUKernel& display) override { tracer_.bindDisplay(display); }
    void denoise() override { tracer_.denoiseProgressive(); }
    float hitDistance(int x, int y) override { return tracer_.progressiveHitDistance(x, y); }
    const RenderStats& stats() const override { return tracer_.progressiveStats(); }

  private:
    RendererConfig config_;
    GpuTracer tracer_;
    RenderPhases phases_;
};

}  // namespace

TimedRender renderWithinTime(Renderer& renderer, const CameraBasis& camera, const RenderSettings& settings,
                             double seconds, uint32_t maxSamples) {
    const auto start = std::chrono::steady_clock::now();
    auto secondsSince = [](std::chrono::steady_clock::time_point t) {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    };
    // The fraction shown is the time spent of the limit (below 1 until the last render is done).
    RenderSettings round = settings;
    if (settings.progress)
        round.progress = [&](double) { settings.progress(std::min(0.99, secondsSince(start) / seconds)); };
    round.samples = 1;
    TimedRender result{renderer.render(camera, round), 1};
    double lastSeconds = secondsSince(start);
    maxSamples = std::max(1u, maxSamples);
    for (;;) {
        // Seconds a sample took in the last render (its pixel-centre pass counted as one more
        // sample when it had two or more), and the most samples a render fits in 95% of what is
        // left (samples vary in cost: the cpu backend's jittered samples measured 7% dearer than
        // its pixel-centre one on the glass box).
        const double passes = double(result.samples) + (result.samples >= 2 ? 1.0 : 0.0);
        const double perSample = std::max(1e-9, lastSeconds / passes);
        const double fits = std::floor(0.95 * (seconds - secondsSince(start)) / perSample) - 1.0;
        const uint32_t samples = uint32_t(std::clamp(fits, 0.0, double(maxSamples)));
        if (samples <= result.samples || samples < 2) break;
        round.samples = samples;
        const auto roundStart = std::chrono::steady_clock::now();
        result.output = renderer.render(camera, round);
        result.samples = samples;
        lastSeconds = secondsSince(roundStart);
    }
    if (settings.progress) settings.progress(1.0);
    return result;
}

// Peak resident memory measured at 1024x1024 and 2048x2048 with every AOV (llvmpipe, Mesa 22.3):
// about 232 bytes a pixel for GL (eleven RGBA32F streams, masks, read-backs), 48 for the CPU
// backend, plus a fixed part; rounded up. The pictures' streams (sample sums, light samples, path
// state, shading normals, the viewer's AOV copies: 7 x 16 bytes) are added by count, not
// measured, as are the path integrator's packed streams on GL (7 x 16 bytes and 4); a glass
// scene's ray stacks (48 bytes a slot, up to 8) are not counted.
double renderBytes(Backend backend, Integrator integrator, double pixels) {
    const bool paths = integratorInfo(integrator).pathStreams;
    const double perPixel = backend == Backend::Gl ? 256.0 + 112.0 + (paths ? 116.0 : 0.0) : 64.0;
    return perPixel * pixels + 256e6;
}

std::unique_ptr<Renderer> makeRenderer(const RendererConfig& config, const Scene& scene, const Acceleration& accel) {
    if (config.backend == Backend::Cpu)
        return std::make_unique<CpuRenderer>(config, scene, makeCpuAccelerator(scene, accel), accel.rayOffset());
    return std::make_unique<GlRenderer>(config, scene, makeGlAccelerator(scene, accel, config.gl), accel.rayOffset());
}

std::unique_ptr<Renderer> makeRenderer(const RendererConfig& config, const Scene& scene, const UniformGrid& grid) {
    if (config.backend == Backend::Cpu)
        return std::make_unique<CpuRenderer>(config, scene, std::make_unique<GridCpu>(scene, grid), grid.rayOffset());
    return std::make_unique<GlRenderer>(config, scene, std::make_unique<GridGl>(scene, grid, config.gl), grid.rayOffset());
}

}  // namespace gpurt
