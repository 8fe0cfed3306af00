#include "raytrace/AlphaCoverage.h"

#include "raytrace/RayMath.h"
#include "raytrace/SurfaceTexture.h"

namespace gpurt {

std::unique_ptr<const AlphaCoverage> AlphaCoverage::of(const Scene& scene) {
    for (const Material& m : scene.materials)
        if (m.hasAlpha()) return std::make_unique<const AlphaCoverage>(scene);
    return nullptr;
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
