// A toy material model (GPURT_MODEL_DEBUG_NORMAL), used by a test to show that a model is its
// file, its id and its lines in common/material.h (docs/ARCHITECTURE.md, "Adding a material
// model"): the surface shows its shading normal as a colour, 0.5 n + 0.5, whatever lights it. It
// scatters nothing and no light reaches it, under both integrators.
#ifndef GPURT_MATERIALS_DEBUG_NORMAL_H
#define GPURT_MATERIALS_DEBUG_NORMAL_H

GPURT_FN vec3 debugNormalEmitted(vec3 ns) { return ns * 0.5f + vec3(0.5f); }

#endif
