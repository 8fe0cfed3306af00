// The material-model registry: each model declares itself once (MaterialModels.cpp: its id, the
// name the tools and messages use, the file of glsl/common that holds its BSDF, what it is), and
// everything that names a model reads it: the scene readers (the ids, glsl/common/
// material_models.h), the packed format's MODL check, the kernels' SCENE_MODEL_<id> defines
// (raytrace/textures/SceneTextures), `gpurt info`. Its shading is dispatched on the id in
// glsl/common/material.h, one line a model in each material* function.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "../../glsl/common/material_models.h"

namespace gpurt {

struct MaterialModelInfo {
    int id;                     // GPURT_MODEL_*
    std::string_view name;      // "classic", "gltf", ...
    std::string_view source;    // its file under glsl/common/ ("" where material.h holds it whole)
    std::string_view summary;   // one line: what it is
};

// The models in id order (models()[id].id == id).
const std::vector<MaterialModelInfo>& materialModels();
// The model of id `id`, or null for an id no model has.
const MaterialModelInfo* findMaterialModel(int id);
// "0 classic, 1 debug_normal, 2 gltf, 3 unlit": what a message about an unknown id lists.
std::string materialModelList();

}  // namespace gpurt
