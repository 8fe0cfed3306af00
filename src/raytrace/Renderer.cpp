#include "raytrace/Renderer.h"

#include "raytrace/CpuTracer.h"
#include "raytrace/GpuTracer.h"
#include "raytrace/accel/bvh/BvhGl.h"
#include "raytrace/accel/grid/GridCpu.h"
#include "raytrace/accel/grid/GridGl.h"
#include "stream/KernelStats.h"

#include <chrono>
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
    const RenderStats& stats() const override { return tracer_.progressiveStats(); }

  private:
    RendererConfig config_;
    GpuTracer tracer_;
    RenderPhases phases_;
};

}  // namespace

// Peak resident memory measured at 1024x1024 and 2048x2048 with every AOV (llvmpipe, Mesa 22.3):
// about 232 bytes a pixel for GL (eleven RGBA32F streams, masks, read-backs), 48 for the CPU
// backend, plus a fixed part; rounded up. The pictures' streams (sample sums, light samples, path
// state, shading normals, the viewer's AOV copies: 7 x 16 bytes) are added by count, not
// measured, as are the path integrator's packed streams on GL (7 x 16 bytes and 4); a glass
// scene's ray stacks (48 bytes a slot, up to 8) are not counted.
double renderBytes(Backend backend, Integrator integrator, double pixels) {
    const bool paths = integrator == Integrator::Path;
    const double perPixel = backend == Backend::Gl ? 256.0 + 112.0 + (paths ? 116.0 : 0.0) : 64.0;
    return perPixel * pixels + 256e6;
}

std::unique_ptr<Renderer> makeRenderer(const RendererConfig& config, const Scene& scene, const Acceleration& accel) {
    if (config.backend == Backend::Cpu)
        return std::make_unique<CpuRenderer>(config, scene, makeCpuAccelerator(scene, accel), accel.rayOffset());
    return std::make_unique<GlRenderer>(config, scene, makeGlAccelerator(scene, accel, config.gl), accel.rayOffset());
}

std::unique_ptr<GlAccelerator> makeGlAccelerator(const Scene& scene, const Acceleration& accel,
                                                 const GpuTracerOptions& options) {
    if (accel.kind == AccelKind::Bvh) return std::make_unique<BvhGl>(scene, *accel.bvh, options);
    return std::make_unique<GridGl>(scene, *accel.grid, options);
}

std::unique_ptr<Renderer> makeRenderer(const RendererConfig& config, const Scene& scene, const UniformGrid& grid) {
    if (config.backend == Backend::Cpu)
        return std::make_unique<CpuRenderer>(config, scene, std::make_unique<GridCpu>(scene, grid), grid.rayOffset());
    return std::make_unique<GlRenderer>(config, scene, std::make_unique<GridGl>(scene, grid, config.gl), grid.rayOffset());
}

}  // namespace gpurt
