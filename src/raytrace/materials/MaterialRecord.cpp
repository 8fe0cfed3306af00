#include "raytrace/materials/MaterialRecord.h"

#include "raytrace/materials/SurfaceTexture.h"

namespace gpurt {

namespace {

// A texture channel's value at t (glsl/scene/shading.glsl textureChannel): 1 without the texture
// or without texture coordinates in the scene (the kernels compile textures out then).
float channelAt(const Scene& scene, TextureChannel c, glm::vec2 t) {
    if (!c.given() || scene.texcoords.empty()) return 1.0f;
    return sampleChannel(scene.textures[size_t(c.texture)], t, c.channel);
}

// KHR_materials_anisotropy's direction in scene space of triangle prim at barycentrics (u, v)
// (common/shading.h anisotropyFrameDirection; shading.glsl fetchAnisotropyDirection): `direction`
// in the frame of its vertex tangent or of its texture coordinates or around the up axis, about the
// front side's shading normal.
glm::vec3 anisotropyDirectionAt(const Scene& scene, uint32_t prim, float u, float v, glm::vec2 direction) {
    const Triangle& tri = scene.triangles[prim];
    const glm::vec3 e1 = tri.v1 - tri.v0, e2 = tri.v2 - tri.v0;
    glm::vec3 ns = raymath::facingNormal(e1, e2, -glm::cross(e1, e2));
    if (!scene.normals.empty()) {
        const TriangleNormals& n = scene.normals[prim];
        ns = raymath::shadingNormal(n.n0, n.n1, n.n2, u, v, ns);
    }
    glm::vec2 dt1, dt2;
    texcoordEdgesAt(scene, prim, dt1, dt2);
    return raymath::anisotropyFrameDirection(ns, !scene.tangents.empty(), vertexTangentAt(scene, prim, u, v), e1, e2, dt1,
                                             dt2, direction);
}

}  // namespace

raymath::MaterialRecord materialRecord(const Scene& scene, uint32_t prim, float u, float v) {
    const Material& m = scene.materials[scene.materialIds[prim]];
    raymath::MaterialRecord r = materialRecord(m);
    r.kd = diffuseAt(scene, m, prim, u, v);
    r.kd = r.kd * vertexColorAt(scene, prim, u, v);
    if (m.model == GPURT_MODEL_GLTF) {  // shading.glsl: SCENE_MODEL_2
        const glm::vec2 t = texcoordAt(scene, prim, u, v);
        r.metallic = m.metallic * channelAt(scene, m.metallicTexture, t);
        r.roughness = m.roughness * channelAt(scene, m.roughnessTexture, t);
        r.occlusion = 1.0f + m.occlusionStrength * (channelAt(scene, m.occlusionTexture, t) - 1.0f);
        r.tf = m.transmission * channelAt(scene, m.transmissionTexture, t);  // shading.glsl: SCENE_TRANSMISSION_MAPS
        r.specularWeight = m.specularFactor * channelAt(scene, m.specularTexture, t);  // SCENE_SPECULAR_LAYER
        if (m.specularColorTexture >= 0 && !scene.texcoords.empty())
            r.specularColor = m.specularColor * sampleTexture(scene.textures[size_t(m.specularColorTexture)], t);
        r.coat = m.clearcoat * channelAt(scene, m.clearcoatTexture, t);  // SCENE_CLEARCOAT
        r.coatRoughness = m.clearcoatRoughness * channelAt(scene, m.clearcoatRoughnessTexture, t);
        r.sheenRoughness = m.sheenRoughness * channelAt(scene, m.sheenRoughnessTexture, t);  // SCENE_SHEEN
        if (m.sheenColorTexture >= 0 && !scene.texcoords.empty())
            r.sheenColor = m.sheenColor * sampleTexture(scene.textures[size_t(m.sheenColorTexture)], t);
        if (m.hasAnisotropy()) {  // SCENE_ANISOTROPY
            glm::vec3 texel(1.0f, 0.5f, 1.0f);
            if (m.anisotropyTexture >= 0 && !scene.texcoords.empty())
                texel = sampleLinear(scene.textures[size_t(m.anisotropyTexture)], t);
            const glm::vec3 a = raymath::gltfAnisotropyAt(m.anisotropyStrength, m.anisotropyTurn(), texel);
            r.anisotropy = a.z;
            if (r.anisotropy > 0.0f) {
                r.anisotropyDirection = anisotropyDirectionAt(scene, prim, u, v, glm::vec2(a.x, a.y));
                if (r.anisotropyDirection == glm::vec3(0.0f)) r.anisotropy = 0.0f;  // n along the up axis: isotropic
            }
        }
        r.iridescence = r.iridescence * channelAt(scene, m.iridescenceTexture, t);  // SCENE_IRIDESCENCE
        r.iridescenceThickness = glm::mix(m.iridescenceThicknessMin, m.iridescenceThicknessMax,
                                          channelAt(scene, m.iridescenceThicknessTexture, t));
        if (m.emissiveTexture >= 0) {
            r.emitterLight = false;
            if (!scene.texcoords.empty()) r.emission = m.emission * sampleTexture(scene.textures[size_t(m.emissiveTexture)], t);
        }
    }
    return r;
}

raymath::MaterialRecord materialRecord(const Material& m) {
    raymath::MaterialRecord r;
    r.model = m.model;
    r.kd = m.diffuse;
    r.ks = m.specular;
    r.ns = m.shininess;
    r.reflectivity = m.reflectivity;
    r.tf = m.transmission;
    r.ior = m.ior;
    r.thin = m.thin();
    r.emission = m.emission;
    r.emitterLight = true;
    r.metallic = m.model == GPURT_MODEL_GLTF ? m.metallic : 0.0f;
    r.roughness = m.model == GPURT_MODEL_GLTF ? m.roughness : 1.0f;
    r.occlusion = 1.0f;
    const bool gltf = m.model == GPURT_MODEL_GLTF;
    r.specularColor = gltf ? m.specularColor : glm::vec3(1.0f);
    r.specularWeight = gltf ? m.specularFactor : 1.0f;
    r.coat = gltf ? m.clearcoat : 0.0f;
    r.coatRoughness = gltf ? m.clearcoatRoughness : 0.0f;
    r.coatNormal = glm::vec3(0.0f, 0.0f, 1.0f);  // CpuScene::surfaceAt: the surface's
    r.sheenColor = gltf ? m.sheenColor : glm::vec3(0.0f);
    r.sheenRoughness = gltf ? m.sheenRoughness : 0.0f;
    r.iridescence = m.hasIridescence() ? m.iridescenceFactor : 0.0f;
    r.iridescenceIor = m.iridescenceIor;
    r.iridescenceThickness = m.iridescenceThicknessMax;
    r.anisotropy = 0.0f;  // materialRecord(scene, ...): in the tangent frame at the hit
    r.anisotropyDirection = glm::vec3(1.0f, 0.0f, 0.0f);
    r.absorption = m.absorption();  // SCENE_VOLUME
    r.dispersion = m.disperses() ? m.dispersion : 0.0f;  // SCENE_DISPERSION
    return r;
}

}  // namespace gpurt
