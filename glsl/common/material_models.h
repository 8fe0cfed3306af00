// The material models' ids (a MaterialRecord's and a scene Material's `model`; a packed file's MODL
// values), shared word for word by the kernels, the CPU backend and the scene readers. Each model
// is declared once in src/scene/MaterialModels.cpp (its name and file) and dispatched in
// material.h; docs/ARCHITECTURE.md says how to add one.
#ifndef GPURT_MATERIAL_MODELS_H
#define GPURT_MATERIAL_MODELS_H

#define GPURT_MODEL_CLASSIC 0       // Phong lobes, mirror, smooth glass (materials/classic.h)
#define GPURT_MODEL_DEBUG_NORMAL 1  // the shading normal as a colour (materials/debug_normal.h)
#define GPURT_MODEL_GLTF 2          // glTF 2.0 metallic-roughness (materials/gltf.h)
#define GPURT_MODEL_UNLIT 3         // KHR_materials_unlit: its base colour, whatever lights it
#define GPURT_MODEL_COUNT 4         // the models this gpurt knows (a packed file's are checked)

#endif
