// The uniform grid as the gl backend's accelerator (Purcell et al. 2002; Christen 2005, chapter
// 5): its scene textures (voxel index, cell triangle lists), its per-ray DDA state, and the trace
// loop of its kernels (glsl/accel/grid/): the fused traverser-intersector in one pass (the
// default), in passes of N cells under the active mask, or the split precalc / traverse /
// intersect chain of the papers, each loop ended by occlusion counts.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "raytrace/common/GlOptions.h"
#include "raytrace/accel/GlAccelerator.h"
#include "raytrace/accel/grid/UniformGrid.h"
#include "scene/Scene.h"

namespace gpurt {

class GridGl final : public GlAccelerator {
  public:
    // Uploads the grid's textures; `grid` must outlive it. Throws EnvironmentError when they do
    // not fit the GL limits.
    GridGl(const Scene& scene, const UniformGrid& grid, const GpuTracerOptions& options);
    ~GridGl() override;

    void attach(const GlRayStreams& rays, MaskMode mask) override;
    uint64_t trace(bool anyHit, GPUMask* mask = nullptr) override;
    std::optional<uint64_t> traceCamera() override;
    void setRect(std::optional<StreamRect> rect) override;
    const GPUFloatArray& steps() const override;
    int stepLimit() const override;
    bool needsRayStates() const override { return !onePass(); }
    size_t bytes() const override;
    size_t bytesPerRay() const override;
    std::vector<GPUKernel*> kernels() override;
    void bindTrace(GPUKernel& kernel) const override;

    // The grid's textures and uniforms as inputs of `kernel` (voxelIndex, cellTriangles, gridMin,
    // gridMax, cellSize, gridRes, cellTolerance, maxCellSteps).
    void bind(GPUKernel& kernel) const;
    const GPUFloatArray& voxelIndex() const { return voxelIndex_; }
    const GPUFloatArray& cellTriangles() const { return cellTriangles_; }

    // The kernels and per-ray streams for one ray stream size (kernel tests drive them).
    struct Passes;
    Passes& passes() { return *passes_; }

  private:
    // The fused kernel from the start with the whole traversal in one pass (the default).
    bool onePass() const;
    uint64_t traceLoop(bool anyHit);

    const UniformGrid& grid_;
    GpuTracerOptions options_;
    GPUFloatArray voxelIndex_, cellTriangles_;
    std::unique_ptr<Passes> passes_;
};

// The grid's passes over ray streams of one size. dda and voxel are each ray's DDA state
// ((tMax, state), (cell, cells visited)); dda is 1 x 1 where only one-pass traces run.
struct GridGl::Passes {
    GPUFloatArray dda, voxel;
    GPUMask activeMask, waitMask;
    GPUKernel precalc, traverse, intersect;
    // The fused traverser-intersector (trace.frag), closest and any hit; their variants under a
    // caller's mask (one pass only); the whole primary trace generating its own rays.
    GPUKernel trace, traceAny, traceMasked, traceAnyMasked, traceCamera;

    Passes(const GridGl& grid, const GlRayStreams& rays, MaskMode mask, bool rayStates, int traverseSteps,
           int fusedSteps);
    std::vector<GPUKernel*> all() {
        return {&precalc, &traverse, &intersect, &trace, &traceAny, &traceMasked, &traceAnyMasked, &traceCamera};
    }
};

}  // namespace gpurt
