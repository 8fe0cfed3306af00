// KHR_materials_sheen's albedo table: E(mu, r), the directional albedo of the Charlie sheen lobe
// of colour 1 (glsl/common/materials/gltf.h sheenLobe) for a view at cosine mu and roughness r,
// on a GPURT_SHEEN_TABLE x GPURT_SHEEN_TABLE grid (sqrt(mu) along a row, r down, both 0 to 1), which the
// albedo scaling of the layers under the sheen reads (sheenAlbedo). Computed once, on first use,
// by quadrature of the shared lobe, each entry at most 1; the cpu backend reads it, the gl
// backend uploads it (SceneTextures, scenes with a sheen).
#pragma once

#include <vector>

namespace gpurt {

const std::vector<float>& sheenAlbedoTable();

}  // namespace gpurt
