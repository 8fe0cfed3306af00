#include "raytrace/integrators/GlRegistry.h"

#include "stream/StreamErrors.h"

#include <string>
#include <string_view>

namespace gpurt {

std::unique_ptr<GlIntegrator> makeGlIntegrator(const IntegratorInfo& integrator, const GlIntegratorSetup& setup) {
    static constexpr struct {
        std::string_view name;
        std::unique_ptr<GlIntegrator> (*make)(const GlIntegratorSetup&);
    } kFactories[] = {{"whitted", makeWhittedGl}, {"path", makePathGl}, {"ao", makeAoGl}};
    for (const auto& f : kFactories)
        if (f.name == integrator.id.name()) return f.make(setup);
    throw UsageError("integrator " + std::string(integrator.id.name()) + " has no gl form");
}

}  // namespace gpurt
