// The path integrator on the gl backend (common/path.h): each sample one path per pixel, as rounds
// of passes over the paths still alive. Round b traces the rays of the paths at depth b, shades
// their hits, gathers light by next-event estimation (a shadow ray per point light, one to an
// emitter point, one along a direction of the environment), and samples each path's next direction, packing the survivors to the front of
// the streams once many have ended (stream compaction, Purcell et al. 2002). CPU twin: PathCpu.
#pragma once

#include "raytrace/common/GlOptions.h"
#include "raytrace/integrators/GpuPipeline.h"
#include "raytrace/integrators/GlIntegrator.h"

#include <optional>

namespace gpurt {

class PathGl final : public GlIntegrator {
  public:
    // paths: the render uses this integrator (its streams full size, else 1 x 1); maskPaths: the
    // rounds' passes under masks of the live paths (GpuTracerOptions::maskPaths).
    PathGl(GpuPipeline& pipeline, const SceneTextures& textures, MaskMode mask, bool paths, bool maskPaths);

    void setSample(uint32_t s, uint32_t n, uint32_t seed) override;
    void sample(const std::vector<Light>& lights, int maxBounces, RenderOutput* aovs, RenderStats& stats) override;
    const GPUFloatArray& colour() const override { return pixelColor_; }
    void accumulate() override { accumulate_.dispatch(); }
    std::vector<GPUKernel*> kernels() override;

  private:
    void startPaths();
    uint64_t traceRays(bool anyHit);
    void shadeSurfaces(bool masked);
    void lightPointLights(const std::vector<Light>& lights, RenderStats& stats);
    void sampleEmitters(int depth, RenderStats& stats);
    void lightEnvironment(int depth, RenderStats& stats);
    void continuePaths(int depth);
    uint64_t packPaths(int depth);
    void depositPaths(int depth);
    void setPathRows(std::optional<int> rows);
    void maskPasses(bool on);

    GpuPipeline& p_;
    bool masked_;  // the rounds run under masks (a mask mode with a mask pass, and maskPaths)
    int rows_ = 0;  // the rows that hold the live paths
    // The live paths packed for the next round (ray, throughput, path state, colour so far),
    // their counter, each pixel's colour once its path has ended, and the bounce pass's own output
    // (whether the element's path lives on).
    GPUFloatArray nextOrigin_, nextDir_, nextWeight_, nextState_, nextColor_, pathCount_, pixelColor_, pathLives_;
    // Paths alive at the start of a round (its trace, surface and bounce passes) and paths with a
    // hit in it (the shadow rays' passes).
    GPUMask aliveMask_, surfaceMask_;
    GPUKernel surface_, shadowgen_, light_, emitterShadowgen_, bounce_, pack_, deposit_, accumulate_;
    // Next-event estimation of the environment light (built only when the scene's is sampled).
    bool emitters_, environment_;
    GPUKernel environmentShadowgen_, environmentLight_;
};

}  // namespace gpurt
