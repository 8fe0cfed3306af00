#include "raytrace/accel/GlRegistry.h"

#include <string>
#include <string_view>

#include "stream/StreamErrors.h"

namespace gpurt {

std::unique_ptr<GlAccelerator> makeGlAccelerator(const Scene& scene, const AccelStructure& structure,
                                                 const GpuTracerOptions& options) {
    static constexpr struct {
        std::string_view name;
        std::unique_ptr<GlAccelerator> (*make)(const Scene&, const AccelStructure&, const GpuTracerOptions&);
    } kFactories[] = {{"grid", makeGridGl}, {"bvh", makeBvhGl}};
    for (const auto& f : kFactories)
        if (f.name == structure.accelerator().name) return f.make(scene, structure, options);
    throw UsageError("accelerator " + std::string(structure.accelerator().name) + " has no gl form");
}

}  // namespace gpurt
