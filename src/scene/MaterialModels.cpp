#include "scene/MaterialModels.h"

namespace gpurt {

const std::vector<MaterialModelInfo>& materialModels() {
    static const std::vector<MaterialModelInfo> models = {
        {GPURT_MODEL_CLASSIC, "classic", "materials/classic.h",
         "Phong lobes, a mirror and smooth glass (OBJ/MTL, JSON scenes)"},
        {GPURT_MODEL_DEBUG_NORMAL, "debug_normal", "materials/debug_normal.h",
         "the shading normal as a colour (a model for tests)"},
        {GPURT_MODEL_GLTF, "gltf", "materials/gltf.h",
         "glTF 2.0 metallic-roughness, with transmission and ior (Appendix B's BRDF)"},
        {GPURT_MODEL_UNLIT, "unlit", "", "KHR_materials_unlit: its base colour, whatever lights it"},
    };
    return models;
}

const MaterialModelInfo* findMaterialModel(int id) {
    for (const MaterialModelInfo& m : materialModels())
        if (m.id == id) return &m;
    return nullptr;
}

std::string materialModelList() {
    std::string list;
    for (const MaterialModelInfo& m : materialModels())
        list += (list.empty() ? "" : ", ") + std::to_string(m.id) + " " + std::string(m.name);
    return list;
}

}  // namespace gpurt
