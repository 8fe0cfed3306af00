// The BVH as the gl backend's accelerator: its scene textures (the nodes and the leaf-ordered
// triangle list) and the one-pass trace kernel (glsl/accel/bvh/trace.frag), closest and any hit,
// with and without a caller's mask, and the camera variant. It keeps no ray state between passes.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "raytrace/common/GlOptions.h"
#include "raytrace/accel/GlAccelerator.h"
#include "raytrace/accel/bvh/Bvh.h"
#include "scene/Scene.h"

namespace gpurt {

class BvhGl final : public GlAccelerator {
  public:
    // Uploads the tree's textures; `bvh` must outlive it. Throws EnvironmentError when they do
    // not fit the GL limits.
    BvhGl(const Scene& scene, const Bvh& bvh, const GpuTracerOptions& options);
    ~BvhGl() override;

    void attach(const GlRayStreams& rays, MaskMode mask) override;
    uint64_t trace(bool anyHit, GPUMask* mask = nullptr) override;
    std::optional<uint64_t> traceCamera() override;
    void setRect(std::optional<StreamRect> rect) override;
    const GPUFloatArray& steps() const override;
    int stepLimit() const override;
    bool needsRayStates() const override { return false; }
    size_t bytes() const override;
    size_t bytesPerRay() const override { return 16; }  // the steps stream
    std::vector<GPUKernel*> kernels() override;
    void bindTrace(GPUKernel& kernel) const override;

  private:
    // The tree's textures and uniforms as inputs of `kernel` (bvhNodes, bvhTriangles, bvhBoxMin,
    // bvhBoxStep, maxNodeSteps).
    void bind(GPUKernel& kernel) const;
    struct Passes;

    const Bvh& bvh_;
    GpuTracerOptions options_;
    GPUFloatArray nodes_, triangles_;
    std::unique_ptr<Passes> passes_;
};

}  // namespace gpurt
