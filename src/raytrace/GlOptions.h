// The gl backend's options (gpurt render/view/bench --mask, --kernel, --traverse-steps,
// --mask-paths): how the accelerator's trace loop and the integrators' passes are masked and split.
#pragma once

#include <string>

#include "stream/GPUMask.h"

namespace gpurt {

// How the trace loop is split into kernels (docs/PERFORMANCE.md measures both).
enum class TraceKernel {
    Fused,  // trace.frag: traversal and intersection in one kernel (the default)
    Split,  // traverse.frag then intersect.frag, the Purcell/Christen pair
};

const char* traceKernelName(TraceKernel kernel);
bool parseTraceKernel(const std::string& text, TraceKernel& kernel);

struct GpuTracerOptions {
    MaskMode mask = MaskMode::None;  // None: defaultMaskMode() of the driver
    // Grid cells per pass; 0: the kernel's default (split: 16 per traverser pass, fused: the
    // whole traversal in one pass). 1 with Split is the seed.
    int traverseSteps = 0;
    // Load balancing (Christen 2005, 5.6), Split only: the intersector runs only once at least
    // this fraction of the live rays wait (or none is active any more). 0: after every traverser
    // pass.
    float waitThreshold = 0.0f;
    TraceKernel kernel = TraceKernel::Fused;
    // Cells a ray may visit before it is stopped (RAY_OVERFLOW) and counted in
    // RenderStats::overflowRays; 0: UniformGrid::maxCellSteps(), which no ray reaches. Tests
    // lower it to see that reaching it is reported.
    int maxCellSteps = 0;
    // The path integrator's rounds: run the trace and shading passes under masks of the live
    // paths (the pipeline's mask mode) rather than leaving dead paths to each kernel's early exit.
    // Off by default: slower on llvmpipe (docs/PERFORMANCE.md).
    bool maskPaths = false;
};

}  // namespace gpurt
