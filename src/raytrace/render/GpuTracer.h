// The gl backend: the ray tracer as a chain of stream kernels on the GL context (Purcell et al.
// 2002; Christen 2005, chapter 5). It owns the scene textures, the accelerator (accel/: its
// kernels trace the ray streams), the shared streams (GpuPipeline) and the integrators
// (integrators/whitted, integrators/path: their rounds of passes), and runs the sample loop, the
// sums, the AOVs and the viewer's progressive rendering around them.
#pragma once

#include "raytrace/camera/Camera.h"
#include "raytrace/common/GlOptions.h"
#include "raytrace/common/RenderTypes.h"
#include "scene/Scene.h"
#include "raytrace/textures/SceneTextures.h"
#include "raytrace/accel/GlAccelerator.h"
#include "raytrace/accel/grid/UniformGrid.h"
#include "raytrace/denoise/DenoiseGl.h"
#include "stream/GPUMask.h"

#include <memory>
#include <set>
#include <string>
#include <vector>

namespace gpurt {

struct GpuPipeline;
class GlIntegrator;
class WhittedGl;
class MegakernelAovs;
struct IntegratorInfo;

class GpuTracer {
  public:
    // Uploads the scene textures; `scene` and `grid` must outlive the tracer.
    GpuTracer(const Scene& scene, const UniformGrid& grid, GpuTracerOptions options = {});
    // Over any accelerator of the scene; rayOffset: how far secondary rays start off a surface.
    GpuTracer(const Scene& scene, std::unique_ptr<GlAccelerator> accel, float rayOffset, GpuTracerOptions options = {});
    ~GpuTracer();

    // The whole image: colour (the mean of settings.samples samples a pixel) and the primary AOVs
    // (pixel centres).
    RenderOutput render(const CameraBasis& camera, const RenderSettings& settings);

    const SceneTextures& textures() const { return textures_; }

    // Progressive rendering (gpurt view): beginProgressive traces the camera's pixel centres and
    // keeps their AOVs in the pipeline's aov streams, and clears the sample sums; each addSample
    // adds sample s of n of every pixel to the pipeline's sampleSum (as render does). Nothing is
    // read back. The rays traced so far count in progressiveStats().
    void beginProgressive(const CameraBasis& camera, const RenderSettings& settings);
    void addSample(uint32_t s, uint32_t n);
    const RenderStats& progressiveStats() const { return progressive_.output.stats; }
    // The progressive sums and AOVs as inputs of a display pass (samplers sampleSum, aovHit,
    // aovCells, aovNormal).
    void bindDisplay(GPUKernel& display);
    // The denoiser over the progressive sums (beginProgressive with settings.features), into the
    // display's `denoised`.
    void denoiseProgressive();
    // The pixel centre's hit distance (ProgressiveRenderer::hitDistance).
    float progressiveHitDistance(int x, int y) const;

    // The names of the accelerator's passes (the trace phase of --stats; the others shade).
    std::set<std::string> accelerationPasses();

    // Tracing only (gpurt bench). tracePrimary traces the camera's rays: with the default fused
    // kernel in one pass that generates them itself (traceCamera), otherwise raygen and the trace
    // loop; setRays uploads rays and traceRays traces them (closest hit, or any hit for shadow
    // rays). Both return the rays traced once the GL has finished. hits() reads the result:
    // (t, u, v, triangle | -1) per element.
    uint64_t tracePrimary(const CameraBasis& camera);
    void setRays(const RayStream& rays);
    uint64_t traceRays(bool anyHit);
    std::vector<glm::vec4> hits();
    // Reads the counts and timings of the passes so far into KernelStats.
    void flushStats();

  private:
    // The pipeline and integrator for this size, ray stacks and integrator (its passes and streams;
    // none: for the accelerator's traces alone, gpurt bench; progressive: the viewer's AOV
    // copies; sums: more than one sample).
    // adaptive: adaptive sampling's streams and passes (GpuPipeline::beginAdaptive).
    // variance: the samples' squares summed too (the variance AOV).
    // features: the denoiser's features (the path integrators write and sum them).
    GpuPipeline& pipeline(int width, int height, int stackSlots = 0, const IntegratorInfo* integrator = nullptr,
                          bool progressive = false, bool sums = false, bool aovs = true, bool adaptive = false,
                          bool variance = false, bool features = false);
    // The pixel centres' AOVs into `out` (when given) and the rays into stats.
    void pixelCentreAovs(const std::vector<Light>& lights, RenderOutput* out, RenderStats& stats);
    // The integrator the pipeline was made for.
    GlIntegrator& integrator();
    void setRenderUniforms(const RenderSettings& settings);
    // Sets the camera on the pipeline and every integrator's kernels (the tile's first row).
    void setCamera(const CameraBasis& camera);
    void setSample(uint32_t s, uint32_t n, uint32_t seed);
    // render's samples of more than one: each sample's passes and its accumulate pass, and with
    // adaptive sampling the convergence passes between rounds (until no pixel is active).
    void sampleRounds(const std::vector<Light>& lights, const RenderSettings& settings, RenderOutput& out);
    // The pixels' sums read back and divided into out's colour, features, samples and variance.
    void readSums(RenderOutput& out);
    // The accelerators' coverage keys (scene/alpha.glsl): sample s of --seed `seed`.
    void setCoverageSample(uint32_t s, uint32_t seed);
    // Rays a pixel's stack holds for Whitted's ray tree (0 without glass, where nothing splits,
    // and for the path integrator, which takes one direction a hit).
    int stackSlots(const RenderSettings& settings) const;
    std::vector<GPUKernel*> allKernels();
    // The integrators' kernels (the wavefront chain's or the megakernels').
    std::vector<GPUKernel*> integratorKernels();

    const Scene& scene_;
    GpuTracerOptions options_;
    SceneTextures textures_;
    std::unique_ptr<GlAccelerator> accel_;
    std::unique_ptr<GpuPipeline> pipeline_;
    // The pipeline's integrator (integrators/Registry.h): its entry and its passes, as the
    // wavefront chain or a megakernel. The pixel centres' AOVs: with megakernels a pass of their
    // own, else Whitted's first round (centres_: the integrator itself or whittedAovs_).
    const IntegratorInfo* integrator_ = nullptr;
    std::unique_ptr<GlIntegrator> chosen_;
    std::unique_ptr<MegakernelAovs> megakernelAovs_;
    std::unique_ptr<WhittedGl> whittedAovs_;
    WhittedGl* centres_ = nullptr;
    int stackSlots_ = -1;  // the pipeline's: the stack slots it was made for
    IntegratorKernel kernel_;  // options_.integratorKernel, Auto resolved
    bool splits_ = false;  // some material may spawn two rays (glass): the ray tree needs its stacks
    bool spawns_ = false;  // some material spawns rays (mirror, glass)
    // The viewer's denoiser over the progressive sums of the pipeline of generation
    // denoiserGeneration_ (pipelineGeneration_ counts the pipelines made).
    std::unique_ptr<DenoiserGl> denoiser_;
    uint64_t pipelineGeneration_ = 0, denoiserGeneration_ = 0;
    struct Progressive {
        RenderSettings settings;
        std::vector<Light> lights;
        RenderOutput output;  // only its stats are used
    } progressive_;
};

}  // namespace gpurt
