// The integrators' registry: each integrator declares itself once, in its own folder
// (integrators/<name>/<Name>Integrator.cpp: name, help, what it can do, its options, its cpu
// sample), and Registry.cpp lists it; GlRegistry.cpp lists its gl passes (the gl layer: the
// registry itself builds without GL, as the fuzz targets build the cpu backend). The tracers, the commands' options and
// --help, and the benchmarks read the registry; docs/ARCHITECTURE.md says how to add one.
#pragma once

#include "raytrace/common/RenderTypes.h"
#include "raytrace/integrators/CpuIntegrator.h"

#include <string>
#include <vector>

namespace gpurt {

// One sample of pixel px through the camera ray eye + t d on the cpu; with `features`, the
// sample's features there (integrators with IntegratorInfo::features). settings.integratorOptions
// holds every option of the integrator (CpuTracer::render resolves them).
using CpuSample = glm::vec3 (*)(const CpuScene& tracer, const PixelSample& px, glm::vec3 eye, glm::vec3 d,
                                const PunctualLights& lights, const RenderSettings& settings, PixelAovs aovs,
                                RenderStats& stats, SampleFeatures* features);

// An option of an integrator's own: --NAME VALUE on the commands, uniform `uniform` of its kernels
// and RenderSettings::integratorOptions[uniform] on the cpu. A value above `above`, up to infinity
// ("unlimited" reads as infinity, which the kernels receive as GPURT_FAR).
struct IntegratorOption {
    std::string name;
    std::string uniform;
    std::string help;
    float defaultValue;
    float above;
    bool sceneUnits;  // a length in scene units: it scales with the scene (SceneScale.h)
};

struct IntegratorInfo {
    IntegratorInfo(Integrator id, std::string help) : id(id), help(std::move(help)) {}

    Integrator id;
    std::string help;             // --integrator's help: one line
    bool rayTree = false;         // its rays split (Whitted's tree: the pipeline's ray stacks)
    bool pathStreams = false;     // the path integrator's per-ray state and packed streams
    bool adaptive = false;        // --noise-threshold (adaptive sampling)
    bool features = false;        // records the denoiser's features (--denoise, albedo AOVs)
    bool clamps = false;          // --clamp-direct, --clamp-indirect
    int defaultBounces = -1;      // --bounces when none is given (-1: the scene's)
    std::vector<IntegratorOption> options;
    CpuSample cpuSample = nullptr;
    // The gl form (integrators/GlRegistry.h makes it): the megakernel always; the wavefront chain
    // when hasWavefront (else --kernel fused and split run the megakernel too).
    bool hasWavefront = false;
};

// Every integrator, in --help's order (Whitted, the default, first).
const std::vector<const IntegratorInfo*>& integrators();
// The entry of `integrator`; UsageError for a name the registry does not hold.
const IntegratorInfo& integratorInfo(Integrator integrator);
// The entry named `name`, or nullptr.
const IntegratorInfo* findIntegrator(const std::string& name);
// The value of option `uniform` of the settings' integrator (its default when not given).
float integratorOption(const RenderSettings& settings, const std::string& uniform);

}  // namespace gpurt
