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

// How an integrator's sample is split into passes (docs/PERFORMANCE.md measures both).
enum class IntegratorKernel {
    Auto,        // the faster of the two on the renderer (defaultIntegratorKernel)
    Wavefront,   // a pass a stage: trace, surface, each light's shadow rays and term, bounce
    Megakernel,  // a pass takes each path through several depths (glsl/integrators/*/megakernel.frag)
};
// The kernel Auto stands for: GPURT_KERNEL (wavefront or megakernel) where it is set, else the
// faster on the current context's renderer, as measured in docs/PERFORMANCE.md. Throws
// EnvironmentError for any other value of GPURT_KERNEL.
IntegratorKernel defaultIntegratorKernel();

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
    // The integrators' passes: a pass a stage, or megakernels (Auto: defaultIntegratorKernel).
    IntegratorKernel integratorKernel = IntegratorKernel::Auto;
    // The depths a path megakernel pass takes each path through before the live paths are
    // packed; 0: the measured default.
    int megakernelBounces = 0;
};

}  // namespace gpurt
