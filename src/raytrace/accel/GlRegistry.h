// The accelerators' gl forms, by their registry entries (accel/Accelerator.h): the factory each
// accelerator's folder defines (GlRegistry.cpp lists them, one line each), apart from the registry
// because that builds without GL (the fuzz targets' cpu backend).
#pragma once

#include <memory>

#include "raytrace/accel/Acceleration.h"
#include "raytrace/accel/GlAccelerator.h"
#include "raytrace/common/GlOptions.h"

namespace gpurt {

// The gl backend's accelerator over `structure`, which must outlive it, as the scene. Needs a
// current GL context (it uploads the structure's textures).
std::unique_ptr<GlAccelerator> makeGlAccelerator(const Scene& scene, const AccelStructure& structure,
                                                 const GpuTracerOptions& options);
inline std::unique_ptr<GlAccelerator> makeGlAccelerator(const Scene& scene, const Acceleration& accel,
                                                        const GpuTracerOptions& options) {
    return makeGlAccelerator(scene, *accel.structure, options);
}

// Each accelerator's gl factory, defined in its folder.
std::unique_ptr<GlAccelerator> makeGridGl(const Scene& scene, const AccelStructure& structure,
                                          const GpuTracerOptions& options);
std::unique_ptr<GlAccelerator> makeBvhGl(const Scene& scene, const AccelStructure& structure,
                                         const GpuTracerOptions& options);

}  // namespace gpurt
