#include "raytrace/materials/AlphaCoverage.h"

#include "raytrace/common/RayMath.h"
#include "raytrace/materials/SurfaceTexture.h"

#include <algorithm>
#include <vector>

namespace gpurt {

namespace {

// Whether a triangle's material has `property`.
template <typename Property>
bool someTriangleHas(const Scene& scene, Property property) {
    std::vector<bool> has(scene.materials.size());
    bool any = false;
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        has[m] = property(scene.materials[m]);
        any = any || has[m];
    }
    return any && std::any_of(scene.materialIds.begin(), scene.materialIds.end(), [&](uint32_t m) { return has[m]; });
}

}  // namespace

bool sceneUsesAlpha(const Scene& scene) {
    return someTriangleHas(scene, [](const Material& m) { return m.hasAlpha(); });
}

bool sceneCullsBackFaces(const Scene& scene) {
    return someTriangleHas(scene, [](const Material& m) { return m.cullsBackFaces(); });
}

bool sceneHasShadowless(const Scene& scene) {
    return someTriangleHas(scene, [](const Material& m) { return m.castsNoShadow(); });
}

std::unique_ptr<const AlphaCoverage> AlphaCoverage::of(const Scene& scene) {
    return sceneUsesAlpha(scene) || sceneCullsBackFaces(scene) || sceneHasShadowless(scene)
               ? std::make_unique<const AlphaCoverage>(scene)
               : nullptr;
}

// glsl/scene/alpha.glsl hitCovered.
bool AlphaCoverage::covers(int prim, float u, float v, uint32_t key, glm::vec3 d, glm::vec3 e1, glm::vec3 e2,
                           bool shadowRay) const {
    const Material& m = scene_.materials[scene_.materialIds[size_t(prim)]];
    if (shadowRay && m.castsNoShadow()) return false;
    if (m.cullsBackFaces() && raymath::backFacing(d, e1, e2)) return false;
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
