#include "raytrace/textures/SceneTextureLayout.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/glm.hpp>

#include "raytrace/common/RayMath.h"  // common/alpha.h GPURT_COVER_*
#include "raytrace/materials/SheenTable.h"
#include "raytrace/materials/SurfaceTexture.h"

namespace gpurt {

namespace {
using namespace glm;
#include "../../../glsl/common/scene_layout.h"
}  // namespace

TextureTexels emptyTexture(const char* name, size_t width, size_t rows, int channels,
                           bool isFloat) {
    TextureTexels t;
    t.name = name;
    t.width = int(width);
    t.rows = int(rows);
    t.channels = channels;
    t.isFloat = isFloat;
    const size_t values = t.texels() * size_t(channels);
    // Zeros explicitly (the padding after the last entry and the unused channels are read as 0):
    // resize() of a LargeArray leaves its values unwritten.
    if (isFloat)
        t.floats.assign(values, 0.0f);
    else
        t.uints.assign(values, 0u);
    return t;
}

const char* TextureTexels::formatName() const {
    if (isFloat) return channels == 4 ? "RGBA32F" : channels == 2 ? "RG32F" : "R32F";
    return channels == 4 ? "RGBA32UI" : channels == 2 ? "RG32UI" : "R32UI";
}

size_t textureRowsFor(size_t count, size_t perRow) {
    return std::max<size_t>(1, (count + perRow - 1) / perRow);
}

namespace {
// Three texels for triangle t at `out` (the triangle texture, for shading): (v0, w), (e1, 0),
// (e2, 0), with the same float edges as the CPU backend (e = v - v0, rounded once).
void writeTriangle(const Triangle& tri, float w, float* out) {
    const vec3 e1 = tri.v1 - tri.v0;
    const vec3 e2 = tri.v2 - tri.v0;
    const vec4 texel[3] = {vec4(tri.v0, w), vec4(e1, 0.0f), vec4(e2, 0.0f)};
    for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 4; ++c) out[k * 4 + c] = texel[k][c];
}
}  // namespace

// The coverage flags of a material's triangles (common/alpha.h GPURT_COVER_CULL, _ALPHA, _SHADOWLESS).
static float coverageFlags(const Material& m) {
    return float((m.cullsBackFaces() ? GPURT_COVER_CULL : 0) | (m.hasAlpha() ? GPURT_COVER_ALPHA : 0) |
                 (m.castsNoShadow() ? GPURT_COVER_SHADOWLESS : 0));
}

TextureTexels triangleListTexels(const Scene& scene, const std::vector<uint32_t>& ids, const char* name) {
    const size_t refs = ids.size();
    TextureTexels list = emptyTexture(name, 3 * GPURT_REFS_PER_ROW, textureRowsFor(refs, GPURT_REFS_PER_ROW), 4, true);
    std::vector<float> flags(scene.materials.size());
    for (size_t m = 0; m < flags.size(); ++m) flags[m] = coverageFlags(scene.materials[m]);
    for (size_t k = 0; k < refs; ++k) {
        const uint32_t id = ids[k];
        const Triangle& tri = scene.triangles[id];
        const glm::vec4 texel[3] = {glm::vec4(tri.v0, float(id)), glm::vec4(tri.v1, flags[scene.materialIds[id]]),
                                    glm::vec4(tri.v2, 0.0f)};
        std::memcpy(&list.floats[k * 12], texel, sizeof(texel));
    }
    return list;
}

TextureTexels triangleTexels(const Scene& scene) {
    const size_t n = scene.triangles.size();
    TextureTexels triangles = emptyTexture("triangles", 3 * GPURT_TRIANGLES_PER_ROW,
                                           textureRowsFor(n, GPURT_TRIANGLES_PER_ROW), 4, true);
    for (size_t t = 0; t < n; ++t)  // rows hold whole triangles: texel 3t is row-major too
        writeTriangle(scene.triangles[t], float(scene.materialIds[t]), &triangles.floats[t * 12]);
    return triangles;
}

TextureTexels materialTexels(const Scene& scene) {
    const size_t n = std::max<size_t>(1, scene.materials.size());
    const size_t perRow = std::min<size_t>(n, GPURT_MATERIALS_PER_ROW);
    TextureTexels materials =
        emptyTexture("materials", perRow * GPURT_MATERIAL_TEXELS, textureRowsFor(n, GPURT_MATERIALS_PER_ROW), 4, true);
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& mat = scene.materials[m];
        // A texture channel as one number (glsl/scene/shading.glsl textureChannel): 4 texture +
        // channel, -1 none.
        auto channel = [](TextureChannel c) { return c.given() ? float(4 * c.texture + c.channel) : -1.0f; };
        const glm::vec2 turn = mat.anisotropyTurn();
        const vec4 texel[GPURT_MATERIAL_TEXELS] = {
            vec4(mat.diffuse, mat.shininess),
            vec4(mat.specular, float(mat.diffuseTexture)),
            vec4(mat.reflectivity, float(mat.model)),
            vec4(mat.emission, channel(mat.occlusionTexture)),
            vec4(mat.transmission, mat.thin() ? -mat.ior : mat.ior),  // a thin wall's index negated
            vec4(mat.metallic, mat.roughness, mat.normalScale, mat.occlusionStrength),
            vec4(channel(mat.roughnessTexture), channel(mat.metallicTexture), float(mat.normalTexture),
                 float(mat.emissiveTexture)),
            vec4(float(mat.alphaMode), mat.alphaFactor, mat.alphaCutoff,
                 channel(mat.alphaTexture)),
            vec4(channel(mat.transmissionTexture), channel(mat.specularTexture), float(mat.specularColorTexture),
                 mat.specularFactor),
            vec4(mat.specularColor, mat.clearcoat),
            vec4(mat.clearcoatRoughness, channel(mat.clearcoatTexture), channel(mat.clearcoatRoughnessTexture),
                 float(mat.clearcoatNormalTexture)),
            vec4(mat.clearcoatNormalScale, mat.sheenRoughness, float(mat.sheenColorTexture),
                 channel(mat.sheenRoughnessTexture)),
            vec4(mat.sheenColor, channel(mat.iridescenceTexture)),
            vec4(mat.absorption(), channel(mat.iridescenceThicknessTexture)),
            vec4(mat.hasIridescence() ? mat.iridescenceFactor : 0.0f, mat.iridescenceIor, mat.iridescenceThicknessMin,
                 mat.iridescenceThicknessMax),
            vec4(mat.hasAnisotropy() ? mat.anisotropyStrength : 0.0f, turn.x, turn.y, float(mat.anisotropyTexture)),
            vec4(mat.disperses() ? mat.dispersion : 0.0f, 0.0f, 0.0f, 0.0f)};
        // Row m / GPURT_MATERIALS_PER_ROW, from texel GPURT_MATERIAL_TEXELS (m % GPURT_MATERIALS_PER_ROW).
        const size_t first = (m / GPURT_MATERIALS_PER_ROW) * size_t(materials.width) +
                             (m % GPURT_MATERIALS_PER_ROW) * GPURT_MATERIAL_TEXELS;
        for (int k = 0; k < GPURT_MATERIAL_TEXELS; ++k)
            for (int c = 0; c < 4; ++c) materials.floats[(first + size_t(k)) * 4 + size_t(c)] = texel[k][c];
    }
    return materials;
}

TextureTexels vertexNormalTexels(const Scene& scene) {
    const size_t n = scene.normals.size();
    TextureTexels normals = emptyTexture("vertexNormals", n == 0 ? 3 : 3 * GPURT_TRIANGLES_PER_ROW,
                                         textureRowsFor(n, GPURT_TRIANGLES_PER_ROW), 4, true);
    for (size_t t = 0; t < n; ++t) {
        const TriangleNormals& v = scene.normals[t];
        const vec3 corner[3] = {v.n0, v.n1, v.n2};
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 3; ++c) normals.floats[t * 12 + size_t(4 * k + c)] = corner[k][c];
    }
    return normals;
}

TextureTexels vertexColorTexels(const Scene& scene) {
    const size_t n = scene.colors.size();
    TextureTexels colors = emptyTexture("vertexColors", n == 0 ? 3 : 3 * GPURT_TRIANGLES_PER_ROW,
                                        textureRowsFor(n, GPURT_TRIANGLES_PER_ROW), 4, true);
    for (size_t t = 0; t < n; ++t) {
        const TriangleColors& v = scene.colors[t];
        const vec3 corner[3] = {v.c0, v.c1, v.c2};
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 3; ++c) colors.floats[t * 12 + size_t(4 * k + c)] = corner[k][c];
    }
    return colors;
}

TextureTexels vertexTangentTexels(const Scene& scene) {
    const size_t n = scene.tangents.size();
    TextureTexels tangents = emptyTexture("vertexTangents", n == 0 ? 3 : 3 * GPURT_TRIANGLES_PER_ROW,
                                          textureRowsFor(n, GPURT_TRIANGLES_PER_ROW), 4, true);
    for (size_t t = 0; t < n; ++t) {
        const TriangleTangents& v = scene.tangents[t];
        const vec4 corner[3] = {v.t0, v.t1, v.t2};
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 4; ++c) tangents.floats[t * 12 + size_t(4 * k + c)] = corner[k][c];
    }
    return tangents;
}

TextureTexels texcoordTexels(const Scene& scene) {
    const size_t n = scene.texcoords.size();
    TextureTexels texcoords = emptyTexture("triangleTexcoords", n == 0 ? GPURT_TEXCOORD_TEXELS : GPURT_TEXCOORD_TEXELS * GPURT_TRIANGLES_PER_ROW,
                                           textureRowsFor(n, GPURT_TRIANGLES_PER_ROW), 4, true);
    for (size_t t = 0; t < n; ++t) {
        const TriangleTexcoords& c = scene.texcoords[t];
        const float values[8] = {c.t0.x, c.t0.y, c.t1.x, c.t1.y, c.t2.x, c.t2.y, 0.0f, 0.0f};
        std::copy(values, values + 8, &texcoords.floats[t * 8]);
    }
    return texcoords;
}

TextureTexels textureImageTexels(const Scene& scene) {
    size_t n = 0;
    for (const Texture& t : scene.textures) n += t.image.texels.size();
    TextureTexels texels = emptyTexture("textureTexels", GPURT_INDEX_WIDTH, textureRowsFor(n, GPURT_INDEX_WIDTH), 1, false);
    size_t at = 0;
    for (const Texture& t : scene.textures) {
        std::copy(t.image.texels.begin(), t.image.texels.end(), texels.uints.begin() + std::ptrdiff_t(at));
        at += t.image.texels.size();
    }
    return texels;
}

TextureTexels textureTableTexels(const Scene& scene) {
    TextureTexels table = emptyTexture("textureTable", std::max<size_t>(1, scene.textures.size()), 1, 4, false);
    table.uints[1] = table.uints[2] = 1;
    size_t first = 0;
    for (size_t k = 0; k < scene.textures.size(); ++k) {
        const Texture& t = scene.textures[k];
        table.uints[4 * k] = uint32_t(first);
        table.uints[4 * k + 1] = uint32_t(t.image.width);
        table.uints[4 * k + 2] = uint32_t(t.image.height);
        table.uints[4 * k + 3] = t.wrapS | t.wrapT << 8;
        first += t.image.texels.size();
    }
    return table;
}

TextureTexels srgbTableTexels() {
    TextureTexels table = emptyTexture("srgbTable", 256, 1, 1, true);
    const std::array<float, 256>& decode = srgbDecodeTable();
    std::copy(decode.begin(), decode.end(), table.floats.begin());
    return table;
}

TextureTexels sheenTableTexels() {
    TextureTexels table = emptyTexture("sheenTable", GPURT_SHEEN_TABLE * GPURT_SHEEN_TABLE, 1, 1, true);
    const std::vector<float>& albedo = sheenAlbedoTable();
    std::copy(albedo.begin(), albedo.end(), table.floats.begin());
    return table;
}

TextureTexels emitterTexels(const EmitterTable& emitters) {
    const size_t n = std::max<size_t>(1, emitters.triangles.size());
    TextureTexels table = emptyTexture("emitters", n, 1, 2, true);
    table.floats[0] = 1.0f;
    table.floats[1] = -1.0f;
    for (size_t k = 0; k < emitters.triangles.size(); ++k) {
        table.floats[2 * k] = emitters.cdf[k];
        table.floats[2 * k + 1] = float(emitters.triangles[k]);  // exact: ids are below 2^24
    }
    return table;
}

std::vector<TextureTexels> integratorTextureTexels(const Scene& scene) {
    std::vector<TextureTexels> all;
    all.push_back(triangleTexels(scene));
    all.push_back(materialTexels(scene));
    all.push_back(vertexNormalTexels(scene));
    all.push_back(emitterTexels(buildEmitterTable(scene)));
    all.push_back(texcoordTexels(scene));
    all.push_back(textureImageTexels(scene));
    all.push_back(textureTableTexels(scene));
    all.push_back(srgbTableTexels());
    all.push_back(vertexColorTexels(scene));
    if (!scene.tangents.empty()) all.push_back(vertexTangentTexels(scene));
    if (std::any_of(scene.materials.begin(), scene.materials.end(),
                    [](const Material& m) { return m.model == GPURT_MODEL_GLTF && m.hasSheen(); }))
        all.push_back(sheenTableTexels());
    return all;
}

}  // namespace gpurt
