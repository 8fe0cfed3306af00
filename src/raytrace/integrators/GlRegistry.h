// The integrators' gl forms, by their registry entries (integrators/Registry.h): what the gl
// backend gives an integrator's passes, and the factory each integrator's folder defines
// (GlRegistry.cpp lists them, one line each).
#pragma once

#include "raytrace/common/GlOptions.h"
#include "raytrace/integrators/GlIntegrator.h"
#include "raytrace/integrators/Registry.h"

#include <memory>

namespace gpurt {

struct GpuPipeline;
class SceneTextures;
class MegakernelAovs;

struct GlIntegratorSetup {
    GpuPipeline& pipeline;
    const SceneTextures& textures;
    bool megakernel;            // the megakernel form (else the wavefront chain, where it has one)
    MaskMode mask;              // the wavefront chain's masking
    bool maskPaths;             // --mask-paths
    int stackSlots;             // the ray tree's pending rays (GpuTracer::stackSlots)
    bool spawns;                // some material spawns rays (mirror, glass)
    size_t maxLights;           // the most point lights a sample is given
    MegakernelAovs* aovs;       // a megakernel's AOV streams (none: no AOVs)
    int megakernelBounces;      // --megakernel-bounces (0: default)
};

// The passes of `integrator` for the pipeline; UsageError for an integrator without a gl form.
std::unique_ptr<GlIntegrator> makeGlIntegrator(const IntegratorInfo& integrator, const GlIntegratorSetup& setup);

// Each integrator's gl factory, defined in its folder.
std::unique_ptr<GlIntegrator> makeWhittedGl(const GlIntegratorSetup& setup);
std::unique_ptr<GlIntegrator> makePathGl(const GlIntegratorSetup& setup);
std::unique_ptr<GlIntegrator> makeAoGl(const GlIntegratorSetup& setup);

}  // namespace gpurt
