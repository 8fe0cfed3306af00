#include "raytrace/integrators/Registry.h"

#include "stream/StreamErrors.h"

namespace gpurt {

// Each integrator's declaration, in its folder.
const IntegratorInfo& whittedIntegrator();
const IntegratorInfo& pathIntegrator();
const IntegratorInfo& aoIntegrator();

const std::vector<const IntegratorInfo*>& integrators() {
    static const std::vector<const IntegratorInfo*> all = {&whittedIntegrator(), &pathIntegrator(), &aoIntegrator()};
    return all;
}

const IntegratorInfo* findIntegrator(const std::string& name) {
    for (const IntegratorInfo* info : integrators())
        if (info->id.name() == name) return info;
    return nullptr;
}

const IntegratorInfo& integratorInfo(Integrator integrator) {
    const IntegratorInfo* info = findIntegrator(std::string(integrator.name()));
    if (!info) throw UsageError("no integrator named '" + std::string(integrator.name()) + "'");
    return *info;
}

float integratorOption(const RenderSettings& settings, const std::string& uniform) {
    auto given = settings.integratorOptions.find(uniform);
    if (given != settings.integratorOptions.end()) return given->second;
    for (const IntegratorOption& option : integratorInfo(settings.integrator).options)
        if (option.uniform == uniform) return option.defaultValue;
    throw UsageError("integrator " + std::string(settings.integrator.name()) + " has no option '" + uniform + "'");
}

}  // namespace gpurt
