#include "raytrace/textures/SceneTextures.h"

#include "raytrace/materials/AlphaCoverage.h"
#include "raytrace/textures/SceneTextureLayout.h"
#include "stream/StreamErrors.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <span>
#include <string>

namespace gpurt {

namespace {
using namespace glm;
#include "../../../glsl/common/scene_layout.h"
}  // namespace

void checkFits(const char* what, size_t width, size_t rows) {
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (width > size_t(maxSize) || rows > size_t(maxSize))
        throw EnvironmentError(std::string("scene too large for this GL: the ") + what +
                               " texture needs " + std::to_string(width) + "x" +
                               std::to_string(rows) + " texels, GL_MAX_TEXTURE_SIZE is " +
                               std::to_string(maxSize));
}

// The tables the traversal gathers from most (the voxel index, the cell triangles) are buffer
// textures: the same texels, row after row, addressed in 1D (cheaper on llvmpipe).
void checkFitsBuffer(const char* what, size_t width, size_t rows) {
    GLint maxTexels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
    if (width * rows > size_t(maxTexels))
        throw EnvironmentError(std::string("scene too large for this GL: the ") + what +
                               " table needs " + std::to_string(width * rows) +
                               " texels, GL_MAX_TEXTURE_BUFFER_SIZE is " +
                               std::to_string(maxTexels));
}

GPUFloatArray uploadTexels(const TextureTexels& texels, GPUFormat format, GPUStorage storage) {
    GPUFloatArray array(texels.width, texels.rows, format, texels.name, storage);
    if (texels.isFloat)
        array.upload(texels.floats);
    else
        array.upload(texels.uints);
    return array;
}

namespace {

// Each texture's size is checked against the GL before its texels are laid out.
GPUFloatArray makeTriangles(const Scene& scene) {
    const size_t n = scene.triangles.size();
    if (n > kMaxTextureTriangles)
        throw EnvironmentError("scene has " + std::to_string(n) +
                               " triangles; the GL backend carries triangle ids as float32, exact "
                               "only below 16777216 (2^24)");
    checkFits("triangle", 3 * GPURT_TRIANGLES_PER_ROW, textureRowsFor(n, GPURT_TRIANGLES_PER_ROW));
    return uploadTexels(triangleTexels(scene), GPUFormat::RGBA32F, GPUStorage::Texture2D);
}

GPUFloatArray makeMaterials(const Scene& scene) {
    const size_t n = std::max<size_t>(1, scene.materials.size());
    checkFits("material", std::min<size_t>(n, GPURT_MATERIALS_PER_ROW) * GPURT_MATERIAL_TEXELS,
              textureRowsFor(n, GPURT_MATERIALS_PER_ROW));
    return uploadTexels(materialTexels(scene), GPUFormat::RGBA32F, GPUStorage::Texture2D);
}

GPUFloatArray makeVertexNormals(const Scene& scene) {
    checkFits("vertex normal", 3 * GPURT_TRIANGLES_PER_ROW, textureRowsFor(scene.normals.size(), GPURT_TRIANGLES_PER_ROW));
    return uploadTexels(vertexNormalTexels(scene), GPUFormat::RGBA32F, GPUStorage::Texture2D);
}

GPUFloatArray makeVertexColors(const Scene& scene) {
    checkFits("vertex colour", 3 * GPURT_TRIANGLES_PER_ROW, textureRowsFor(scene.colors.size(), GPURT_TRIANGLES_PER_ROW));
    return uploadTexels(vertexColorTexels(scene), GPUFormat::RGBA32F, GPUStorage::Texture2D);
}

GPUFloatArray makeVertexTangents(const Scene& scene) {
    checkFits("vertex tangent", 3 * GPURT_TRIANGLES_PER_ROW, textureRowsFor(scene.tangents.size(), GPURT_TRIANGLES_PER_ROW));
    return uploadTexels(vertexTangentTexels(scene), GPUFormat::RGBA32F, GPUStorage::Texture2D);
}

GPUFloatArray makeEmitters(const EmitterTable& emitters) {
    checkFitsBuffer("emitter", std::max<size_t>(1, emitters.triangles.size()), 1);
    return uploadTexels(emitterTexels(emitters), GPUFormat::RG32F, GPUStorage::Buffer);
}

GPUFloatArray makeTexcoords(const Scene& scene) {
    checkFits("texture coordinate", GPURT_TEXCOORD_TEXELS * GPURT_TRIANGLES_PER_ROW,
              textureRowsFor(scene.texcoords.size(), GPURT_TRIANGLES_PER_ROW));
    return uploadTexels(texcoordTexels(scene), GPUFormat::RGBA32F, GPUStorage::Texture2D);
}

GPUFloatArray makeTextureTexels(const Scene& scene) {
    size_t n = 0;
    for (const Texture& t : scene.textures) n += t.image.texels.size();
    checkFitsBuffer("texture image", GPURT_INDEX_WIDTH, textureRowsFor(n, GPURT_INDEX_WIDTH));
    return uploadTexels(textureImageTexels(scene), GPUFormat::R32UI, GPUStorage::Buffer);
}

GPUFloatArray makeTextureTable(const Scene& scene) {
    checkFitsBuffer("texture", std::max<size_t>(1, scene.textures.size()), 1);
    return uploadTexels(textureTableTexels(scene), GPUFormat::RGBA32UI, GPUStorage::Buffer);
}

// The environment's textures (1 x 1 zeros without one): the map (radiance, uvPdf), the marginal
// and conditional cumulative distributions (1 x 1 where the table has none: not sampled), the 9
// spherical-harmonic coefficients. The table's arrays go up as they are, without a copy.
GPUFloatArray makeEnvironmentArray(const EnvironmentTable& t, int which) {
    static_assert(sizeof(glm::vec4) == 4 * sizeof(float), "texels are 4 packed floats");
    const bool has = !t.empty(), sampled = has && t.sampled;
    const int w = has ? t.width : 1, h = has ? t.height : 1;
    if (has) checkFits("environment map", size_t(t.width), size_t(t.height));
    static const float stand[4] = {0.0f, 0.0f, 0.0f, 0.0f}, one = 1.0f;
    std::vector<float> data;
    switch (which) {
        case 0: {
            GPUFloatArray a(w, h, GPUFormat::RGBA32F, "environmentMap");
            a.upload(has ? std::span<const float>(&t.texels[0].x, 4 * t.texels.size()) : std::span<const float>(stand, 4));
            return a;
        }
        case 1: {
            GPUFloatArray a(sampled ? t.height : 1, 1, GPUFormat::R32F, "environmentMarginal");
            a.upload(sampled ? std::span<const float>(t.marginal) : std::span<const float>(&one, 1));
            return a;
        }
        case 2: {
            GPUFloatArray a(sampled ? t.width : 1, sampled ? t.height : 1, GPUFormat::R32F, "environmentConditional");
            a.upload(sampled ? std::span<const float>(t.conditional) : std::span<const float>(&one, 1));
            return a;
        }
        default: {
            GPUFloatArray a(9, 1, GPUFormat::RGBA32F, "environmentHarmonics");
            data.assign(36, 0.0f);
            for (size_t k = 0; k < 9; ++k)
                for (int c = 0; c < 3; ++c) data[4 * k + size_t(c)] = t.harmonics[k][c];
            a.upload(data);
            return a;
        }
    }
}

}  // namespace

SceneTextures::SceneTextures(const Scene& scene, float rayOffset)
    : rayOffset_(rayOffset),
      triangles_(makeTriangles(scene)),
      materials_(makeMaterials(scene)),
      vertexNormals_(makeVertexNormals(scene)),
      hasVertexNormals_(!scene.normals.empty()),
      emitterTable_(buildEmitterTable(scene)),
      emitters_(makeEmitters(emitterTable_)),
      vertexColors_(makeVertexColors(scene)),
      hasVertexColors_(!scene.colors.empty()),
      vertexTangents_(makeVertexTangents(scene)),
      hasVertexTangents_(!scene.tangents.empty()),
      texcoords_(makeTexcoords(scene)),
      hasTexcoords_(!scene.texcoords.empty()),
      textureTexels_(makeTextureTexels(scene)),
      textureTable_(makeTextureTable(scene)),
      srgbTable_(uploadTexels(srgbTableTexels(), GPUFormat::R32F, GPUStorage::Buffer)),
      environmentTable_(buildEnvironmentTable(scene)),
      environmentMap_(makeEnvironmentArray(environmentTable_, 0)),
      environmentMarginal_(makeEnvironmentArray(environmentTable_, 1)),
      environmentConditional_(makeEnvironmentArray(environmentTable_, 2)),
      environmentHarmonics_(makeEnvironmentArray(environmentTable_, 3)) {
    for (const Material& m : scene.materials) {
        if (m.model != 0) models_.insert(m.model);
        if ((m.normalTexture >= 0 || (m.hasClearcoat() && m.clearcoatNormalTexture >= 0)) && hasTexcoords_)
            hasNormalMaps_ = true;
        if (m.model == GPURT_MODEL_GLTF && m.hasSpecularLayer()) hasSpecularLayer_ = true;
        if (m.model == GPURT_MODEL_GLTF && m.hasClearcoat()) hasClearcoat_ = true;
        if (m.hasVolume()) hasVolume_ = true;
        if (m.thin()) hasThinWalls_ = true;
        if (m.hasIridescence()) hasIridescence_ = true;
        if (m.hasAnisotropy()) hasAnisotropy_ = true;
        if (m.disperses()) hasDispersion_ = true;
        if (m.model == GPURT_MODEL_GLTF && m.hasSheen() && !sheenTable_)
            sheenTable_.emplace(uploadTexels(sheenTableTexels(), GPUFormat::R32F, GPUStorage::Buffer));
        if (m.model == GPURT_MODEL_GLTF && m.transmits()) {
            hasTransmission_ = true;
            if (m.transmissionTexture.given() && hasTexcoords_) hasTransmissionMaps_ = true;
        }
    }
    hasAlpha_ = sceneUsesAlpha(scene);
    cullsBackFaces_ = sceneCullsBackFaces(scene);
    shadowless_ = sceneHasShadowless(scene);
    lightKinds_ = std::any_of(scene.lights.begin(), scene.lights.end(), [](const Light& l) { return !l.plainPoint(); });
}

void SceneTextures::bind(GPUKernel& kernel) const {
    // What the scene has, as defines: llvmpipe runs both sides of a branch under masks, so code
    // for a feature the scene lacks costs its full price unless it is compiled out.
    if (hasVertexNormals_) kernel.addDefine("SCENE_VERTEX_NORMALS");
    if (hasTexcoords_) kernel.addDefine("SCENE_TEXTURES");
    if (hasNormalMaps_) kernel.addDefine("SCENE_NORMAL_MAPS");
    if (hasTransmission_) kernel.addDefine("SCENE_TRANSMISSION");  // integrators/light.frag
    if (hasTransmissionMaps_) kernel.addDefine("SCENE_TRANSMISSION_MAPS");  // shading.glsl fetchMaterialRecord
    if (hasSpecularLayer_) kernel.addDefine("SCENE_SPECULAR_LAYER");  // common/materials/gltf.h
    if (hasClearcoat_) kernel.addDefine("SCENE_CLEARCOAT");
    if (hasVolume_) kernel.addDefine("SCENE_VOLUME");  // common/material.h materialTransmittance
    if (hasThinWalls_) kernel.addDefine("SCENE_THIN_WALLS");  // common/materials/gltf.h gltfThin
    if (hasIridescence_) kernel.addDefine("SCENE_IRIDESCENCE");  // common/materials/gltf.h thinFilmFresnel
    if (hasAnisotropy_) kernel.addDefine("SCENE_ANISOTROPY");  // common/materials/anisotropic_ggx.h
    if (hasDispersion_) kernel.addDefine("SCENE_DISPERSION");  // common/material.h materialDisperses
    if (sheenTable_) kernel.addDefine("SCENE_SHEEN").addInput(*sheenTable_, "sheenTable");  // gltf.h sheenAlbedo
    if (!emitterTable_.triangles.empty()) kernel.addDefine("SCENE_EMITTERS");
    for (int model : models_) kernel.addDefine("SCENE_MODEL_" + std::to_string(model));  // common/material.h
    if (lightKinds_) kernel.addDefine("SCENE_LIGHT_KINDS");  // common/shading.h punctualAsPoint
    if (hasVertexColors_) kernel.addDefine("SCENE_VERTEX_COLORS");
    // The vertex tangents only where a normal map or anisotropy reads them (shading.glsl
    // fetchMappedNormal, fetchAnisotropyDirection): the kernels of other scenes neither declare nor
    // bind them.
    if (hasVertexTangents_ && (hasNormalMaps_ || hasAnisotropy_)) {
        kernel.addDefine("SCENE_VERTEX_TANGENTS");
        kernel.addInput(vertexTangents_, "vertexTangents");
    }
    kernel.addInput(triangles_, "triangles")
        .addInput(materials_, "materials")
        .addInput(vertexNormals_, "vertexNormals")
        .addInput(emitters_, "emitters")
        .setUniform("emitterCount", int(emitterTable_.triangles.size()))
        .setUniform("emitterArea", emitterTable_.totalArea)
        .addInput(texcoords_, "triangleTexcoords")
        .addInput(textureTexels_, "textureTexels")
        .addInput(textureTable_, "textureTable")
        .addInput(srgbTable_, "srgbTable")
        .addInput(vertexColors_, "vertexColors")
        .setUniform("rayOffset", rayOffset_);
    if (!environmentTable_.empty()) {
        kernel.addDefine("SCENE_ENVIRONMENT");
        kernel.addInput(environmentMap_, "environmentMap")
            .addInput(environmentMarginal_, "environmentMarginal")
            .addInput(environmentConditional_, "environmentConditional")
            .addInput(environmentHarmonics_, "environmentHarmonics")
            .setUniform("environmentRotation", environmentTable_.rotation)
            .setUniform("environmentSize", glm::ivec2(environmentTable_.width, environmentTable_.height));
    }
}

void SceneTextures::bindCoverageDefines(GPUKernel& kernel) const {
    if (hasAlpha_) kernel.addDefine("SCENE_ALPHA");
    if (cullsBackFaces_) kernel.addDefine("SCENE_CULL_BACK");
    if (shadowless_) kernel.addDefine("SCENE_SHADOWLESS");
}

void SceneTextures::bindCoverage(GPUKernel& kernel) const {
    if (!hasCoverage()) return;
    bindCoverageDefines(kernel);
    if (hasTexcoords_) kernel.addDefine("SCENE_TEXTURES");
    kernel.addInput(triangles_, "triangles")
        .addInput(materials_, "materials")
        .addInput(texcoords_, "triangleTexcoords")
        .addInput(textureTexels_, "textureTexels")
        .addInput(textureTable_, "textureTable")
        .addInput(srgbTable_, "srgbTable");
}

size_t SceneTextures::bytes() const {
    auto size = [](const GPUFloatArray& a) { return a.elements() * size_t(a.channels()) * 4; };
    return size(triangles_) + size(materials_) + size(vertexNormals_) + size(emitters_) +
           size(texcoords_) + size(textureTexels_) + size(textureTable_) + size(srgbTable_) + size(vertexColors_) +
           (hasVertexTangents_ ? size(vertexTangents_) : 0) +
           (environmentTable_.empty() ? 0  // the 1 x 1 stand-ins of a scene without an environment
                                      : size(environmentMap_) + size(environmentMarginal_) +
                                            size(environmentConditional_) + size(environmentHarmonics_));
}

}  // namespace gpurt
