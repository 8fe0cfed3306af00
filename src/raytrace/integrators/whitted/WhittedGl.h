// Whitted's integrator on the gl backend (Whitted 1980; Christen 2005, 5.5): each sample a ray
// tree per pixel, one ray of each tree a round (common/raytree.h): trace, surface records, a
// shadow ray and light pass per point light and one for an emitter point, then the bounce pass
// that adds the local colour and spawns the mirror and glass rays. CPU twin: WhittedCpu.
#pragma once

#include "raytrace/integrators/GpuPipeline.h"
#include "raytrace/integrators/GlIntegrator.h"

#include <optional>

namespace gpurt {

class WhittedGl final : public GlIntegrator {
  public:
    // stackSlots: rays a pixel's stack can hold (0 where nothing splits: a scene without glass);
    // spawns: some material has children (mirror, glass), so rounds after the first can follow.
    WhittedGl(GpuPipeline& pipeline, const SceneTextures& textures, int stackSlots, bool spawns);

    void setSample(uint32_t s, uint32_t n, uint32_t seed) override;
    // maxBounces < 0: the primary trace and surface pass only (the pixel centres' AOVs).
    void sample(const std::vector<Light>& lights, int maxBounces, RenderOutput* aovs, RenderStats& stats) override;
    const GPUFloatArray& colour() const override { return p_.color; }
    void accumulate() override { accumulate_.dispatch(); }
    std::vector<GPUKernel*> kernels() override;

  private:
    void startTrees(int maxBounces);
    uint64_t traceRays();
    void shadeSurfaces();
    void lightPointLights(const std::vector<Light>& lights, RenderStats& stats);
    void lightEmitters(int round, RenderStats& stats);
    void finishTrees();
    bool spawnRays(bool boxed);
    void setRoundRect(std::optional<StreamRect> rect);

    GpuPipeline& p_;
    bool emitters_;
    bool spawns_;
    // Each pixel's stack of pending rays, `stackSlots` slots of image size one above the other
    // (1 x 1 without slots); the box of the elements with a ray in the next round.
    GPUFloatArray stackOrigin_, stackDir_, stackWeight_, rayBounds_;
    GPUKernel surface_, shadowgen_, light_, emitterShadowgen_, emitterLight_, bounce_, lastBounce_, accumulate_;
};

}  // namespace gpurt
