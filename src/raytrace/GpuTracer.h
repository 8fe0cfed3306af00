// The ray tracer as a chain of stream kernels on the GL context (Purcell et al. 2002; Christen
// 2005, chapter 5): ray generation, voxel precalculation, a traverse/intersect loop under
// occlusion-query control, then Whitted shading with shadow rays and mirror bounces, each a
// GPUKernel over image-sized streams.
#pragma once

#include "raytrace/Camera.h"
#include "raytrace/RenderTypes.h"
#include "raytrace/Scene.h"
#include "raytrace/SceneTextures.h"
#include "raytrace/UniformGrid.h"
#include "stream/GPUMask.h"

#include <memory>

namespace gpurt {

struct GpuPipeline;

struct GpuTracerOptions {
    MaskMode mask = MaskMode::None;  // None: defaultMaskMode() of the driver
    int traverseSteps = 16;          // cells per traverser pass (1 = the seed)
    // Load balancing (Christen 2005, 5.6): the intersector runs only once at least this fraction
    // of the live rays wait (or none is active any more). 0: after every traverser pass.
    float waitThreshold = 0.0f;
};

class GpuTracer {
  public:
    // Uploads the scene textures; `scene` and `grid` must outlive the tracer.
    GpuTracer(const Scene& scene, const UniformGrid& grid, GpuTracerOptions options = {});
    ~GpuTracer();

    // The whole image: colour and the primary AOVs.
    RenderOutput render(const CameraBasis& camera, const RenderSettings& settings);

    const SceneTextures& textures() const { return textures_; }

  private:
    GpuPipeline& pipeline(int width, int height);
    uint64_t traceLoop(GpuPipeline& p);

    const Scene& scene_;
    const UniformGrid& grid_;
    GpuTracerOptions options_;
    SceneTextures textures_;
    std::unique_ptr<GpuPipeline> pipeline_;
};

}  // namespace gpurt
