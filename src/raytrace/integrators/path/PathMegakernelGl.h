// The path integrator on the gl backend as a megakernel (--kernel megakernel): each pass takes
// every live path through several depths inside one kernel (glsl/integrators/path/megakernel.frag:
// trace, shading, shadow rays and the next direction in registers, as PathCpu does per pixel),
// then packs the paths still alive to the front of the streams (stream compaction, Purcell et
// al. 2002); their count ends the loop. Same samples and sums as the wavefront chain (PathGl).
#pragma once

#include "raytrace/integrators/GpuPipeline.h"
#include "raytrace/integrators/GlIntegrator.h"
#include "raytrace/integrators/Megakernel.h"

namespace gpurt {

class PathMegakernelGl final : public GlIntegrator {
  public:
    // maxLights: the most point lights a sample is given; aovs: the streams the first pass
    // writes the primary AOVs to when it takes them (none: renders without AOVs).
    PathMegakernelGl(GpuPipeline& pipeline, const SceneTextures& textures, size_t maxLights, MegakernelAovs* aovs);

    void setSample(uint32_t s, uint32_t n, uint32_t seed) override;
    void sample(const std::vector<Light>& lights, int maxBounces, RenderOutput* aovs, RenderStats& stats) override;
    const GPUFloatArray& colour() const override { return pixelColor_; }
    void accumulate() override { accumulate_.dispatch(); }
    std::vector<GPUKernel*> kernels() override;
    // The depths a pass takes each path through (0: all of them in the first pass).
    void setBouncesPerPass(int bounces) { bouncesPerPass_ = bounces; }

  private:
    // The streams a pass reads its live paths from, or packs them into.
    struct PathStreams {
        GPUFloatArray *origin, *dir, *weight, *state, *color;
    };
    void declarePass(GPUKernel& k, const SceneTextures& textures, const PathStreams* in, const PathStreams& out);
    // Runs `k` over `rows` rows with the pass's counters zeroed; returns the paths it packed and
    // adds its rays to stats.
    uint64_t runPass(GPUKernel& k, int depth, int rows, RenderStats& stats);

    GpuPipeline& p_;
    MegakernelInputs inputs_;
    int bouncesPerPass_ = 0;
    uint32_t sampleCount_ = 1;
    // The second set of path streams (the pipeline's ray, weight, path state and colour streams
    // are the first): the passes read one set and pack into the other.
    GPUFloatArray origin_, dir_, weight_, state_, color_;
    GPUFloatArray pixelColor_, lives_;
    MegakernelAovs* aovs_;  // its streams: the AOV variant's outputs (none: no AOVs)
    // The first pass from the camera rays (sample points or pixel centres; with AOVs), and the
    // passes from each stream set into the other.
    GPUKernel camera_, cameraCentre_, cameraAovs_, fromPipeline_, fromOwn_, accumulate_;
    // Adaptive sampling: the first pass over the packed list of active pixels (PIXEL_LIST), once
    // a convergence pass has made one.
    GPUKernel cameraList_;
};

}  // namespace gpurt
