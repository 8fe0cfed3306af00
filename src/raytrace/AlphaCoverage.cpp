#include "raytrace/AlphaCoverage.h"

#include "raytrace/RayMath.h"
#include "raytrace/SurfaceTexture.h"

#include <algorithm>
#include <vector>

namespace gpurt {

bool sceneUsesAlpha(const Scene& scene) {
    std::vector<bool> alpha(scene.materials.size());
    bool any = false;
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        alpha[m] = scene.materials[m].hasAlpha();
        any = any || alpha[m];
    }
    return any && std::any_of(scene.materialIds.begin(), scene.materialIds.end(), [&](uint32_t m) { return alpha[m]; });
}

std::unique_ptr<const AlphaCoverage> AlphaCoverage::of(const Scene& scene) {
    return sceneUsesAlpha(scene) ? std::make_unique<const AlphaCoverage>(scene) : nullptr;
}

// glsl/scene/alpha.glsl hitCovered.
bool AlphaCoverage::covers(int prim, float u, float v, uint32_t key) const {
    const Material& m = scene_.materials[scene_.materialIds[size_t(prim)]];
    if (m.alphaMode == GPURT_ALPHA_OPAQUE) return true;
    float alpha = m.alphaFactor;
    if (m.alphaTexture.given() && !scene_.texcoords.empty()) {
        const glm::vec2 t = texcoordAt(scene_, uint32_t(prim), u, v);
        alpha = alpha * sampleChannel(scene_.textures[size_t(m.alphaTexture.texture)], t,
                                      m.alphaTexture.channel);
    }
    return raymath::alphaCovers(m.alphaMode, alpha, m.alphaCutoff, key, prim);
}

}  // namespace gpurt
