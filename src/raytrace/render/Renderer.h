// One renderer interface for the commands (gpurt render, view, the tests): built by makeRenderer
// from (backend, integrator) over an acceleration structure (accel/Acceleration.h). The commands never see kernels, streams or tracers:
// a renderer renders images, renders progressively where it can (the viewer), says where its
// time went and how much memory a render needs.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "raytrace/camera/Camera.h"
#include "raytrace/common/GlOptions.h"
#include "raytrace/common/RenderTypes.h"
#include "raytrace/accel/Acceleration.h"
#include "raytrace/accel/grid/UniformGrid.h"
#include "scene/Scene.h"

namespace gpurt {

class GPUKernel;
class GlAccelerator;

struct RendererConfig {
    Backend backend = Backend::Gl;
    Integrator integrator = Integrator::Whitted;
    GpuTracerOptions gl;               // the gl backend's masks and trace kernels
};

// Where the latest render's time went, in milliseconds: trace and shade are the kernel passes
// (the accelerator's and the integrator's), compile the GL programs' builds, readBack the
// downloads. The CPU backend's render is all trace.
struct RenderPhases {
    double compile = 0, trace = 0, shade = 0, readBack = 0;
};

// Progressive rendering on the GL context (gpurt view): sample after sample into per-pixel sums
// that stay on the GPU, shown by a display pass.
class ProgressiveRenderer {
  public:
    virtual ~ProgressiveRenderer() = default;
    // Traces the camera's pixel centres (their AOVs are kept) and clears the sums.
    virtual void begin(const CameraBasis& camera, const RenderSettings& settings) = 0;
    // Adds sample s of n of every pixel to the sums.
    virtual void addSample(uint32_t s, uint32_t n) = 0;
    // The sums and the AOVs as inputs of a display pass (samplers sampleSum, aovHit, aovCells,
    // aovNormal, and denoised: the last denoise's colour), valid until a begin with another image
    // size.
    virtual void bindDisplay(GPUKernel& display) = 0;
    // Denoises the sums so far into the display's `denoised` (common/denoise.h; begin's settings
    // asked for the features and variance: RenderSettings::features, variance).
    virtual void denoise() = 0;
    // The rays traced since the first begin.
    virtual const RenderStats& stats() const = 0;
    // The distance along its ray to what the centre of pixel (x, y) (x from the left, y from the
    // top) sees, from begin's AOVs; +infinity where it sees nothing or lies outside the image.
    virtual float hitDistance(int x, int y) = 0;
};

class Renderer {
  public:
    virtual ~Renderer() = default;
    // The whole image (or the camera's tile of rows): colour, the mean of settings.samples
    // samples a pixel, and the primary AOVs. settings.integrator is the renderer's.
    virtual RenderOutput render(const CameraBasis& camera, const RenderSettings& settings) = 0;
    virtual RenderPhases phases() const = 0;
    // nullptr where the backend cannot render progressively (cpu).
    virtual ProgressiveRenderer* progressive() { return nullptr; }
};

// A render within a time budget (--time-limit): as many whole samples a pixel as fit, and exactly
// the image render() gives for that many (the sample pattern depends on the count: sampling.h).
struct TimedRender {
    RenderOutput output;
    uint32_t samples = 1;
};

// Renders the pixel-centre image (--spp 1) and times it; then, while a render of more samples
// than the last fits in what is left of `seconds` at the last render's rate a sample, renders
// the most that fit (at most maxSamples) from the start. The rate of the first render, slowed by
// the kernels' first use (llvmpipe compiles at the first pass), is refined by the later ones.
// The renders before the last are spent; a render slower than its estimate can pass the limit
// (samples are whole). settings.samples is ignored; settings.progress sees the time spent of
// the limit, then 1.
TimedRender renderWithinTime(Renderer& renderer, const CameraBasis& camera, const RenderSettings& settings,
                             double seconds, uint32_t maxSamples);

// The bytes a render of `pixels` pixels needs (its streams or buffers, masks, read-backs, and a
// fixed part): what the commands check against the free memory before they start.
double renderBytes(Backend backend, Integrator integrator, double pixels);

// The renderer for `config` over `scene` and its acceleration structure,
// which must outlive it. The gl backend needs a current GL context and uploads the scene textures
// now.
std::unique_ptr<Renderer> makeRenderer(const RendererConfig& config, const Scene& scene, const Acceleration& accel);
// The same over the uniform grid.
std::unique_ptr<Renderer> makeRenderer(const RendererConfig& config, const Scene& scene, const UniformGrid& grid);

}  // namespace gpurt
