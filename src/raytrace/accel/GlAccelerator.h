// The accelerator seam on the gl backend (accel/CpuAccelerator.h says what the seam is).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "stream/GPUFloatArray.h"
#include "stream/GPUKernel.h"
#include "stream/GPUMask.h"

namespace gpurt {

// The streams a GlAccelerator traces: the rays and the hits, all the same size.
struct GlRayStreams {
    GPUFloatArray* origin;
    GPUFloatArray* dir;
    GPUFloatArray* hit;
};

class GlAccelerator {
  public:
    virtual ~GlAccelerator() = default;
    // Its per-ray streams and kernels for `rays` (their size), masks of the given mode; again
    // whenever the streams change. rayStates false: only one-pass traces are asked for.
    virtual void attach(const GlRayStreams& rays, MaskMode mask) = 0;
    // Traces every element that carries a ray (within the rect, and under `mask` when it has a
    // mask pass and the accelerator traces in one pass): the closest hit, or any hit (shadow
    // rays). Returns the rays traced.
    virtual uint64_t trace(bool anyHit, GPUMask* mask = nullptr) = 0;
    // The camera's primary rays into the hit stream, generated inside the trace where the
    // accelerator can (gpurt bench); std::nullopt where it cannot (the caller traces raygen's).
    virtual std::optional<uint64_t> traceCamera() = 0;
    // The traces' passes over `rect` only (the box of the elements with rays), or all.
    virtual void setRect(std::optional<StreamRect> rect) = 0;
    // Per element, w: the cells or nodes the latest trace visited (the steps AOV); RGBA32I.
    virtual const GPUFloatArray& steps() const = 0;
    // A ray that visits this many is stopped (RAY_OVERFLOW) and counted.
    virtual int stepLimit() const = 0;
    // Whether the structure keeps ray state between passes (a stepped trace loop).
    virtual bool needsRayStates() const = 0;
    // Bytes of its scene textures; bytes per ray of its per-ray streams.
    virtual size_t bytes() const = 0;
    virtual size_t bytesPerRay() const = 0;
    // Its textures and uniforms, and the define naming it, on a kernel of another pass that
    // traces inside (glsl/accel/trace.glsl: the integrators' megakernels).
    virtual void bindTrace(GPUKernel& kernel) const = 0;
    // Its kernels (statistics, the image row of the streams' row 0, camera uniforms).
    virtual std::vector<GPUKernel*> kernels() = 0;
};

}  // namespace gpurt
