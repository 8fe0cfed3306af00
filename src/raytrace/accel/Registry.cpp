#include "raytrace/accel/Accelerator.h"

namespace gpurt {

const std::vector<const AcceleratorInfo*>& accelerators() {
    static const std::vector<const AcceleratorInfo*> list = {&gridAccelerator(), &bvhAccelerator()};
    return list;
}

const AcceleratorInfo* findAccelerator(std::string_view name) {
    for (const AcceleratorInfo* a : accelerators())
        if (a->name == name) return a;
    return nullptr;
}

std::string acceleratorNames(std::string_view separator) {
    std::string names;
    for (const AcceleratorInfo* a : accelerators()) names += (names.empty() ? "" : std::string(separator)) + std::string(a->name);
    return names;
}

}  // namespace gpurt
