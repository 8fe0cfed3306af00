#include "raytrace/materials/SurfaceTexture.h"

#include "raytrace/common/RayMath.h"

namespace gpurt::raymath {
#include "../../../glsl/common/texture.h"
}  // namespace gpurt::raymath

namespace gpurt {

static_assert(kWrapRepeat == GPURT_WRAP_REPEAT && kWrapClamp == GPURT_WRAP_CLAMP && kWrapMirror == GPURT_WRAP_MIRROR);

const std::array<float, 256>& srgbDecodeTable() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int code = 0; code < 256; ++code) t[size_t(code)] = raymath::srgbDecode8(code);
        return t;
    }();
    return table;
}

glm::vec3 sampleTexture(const Texture& texture, glm::vec2 t) {
    const Rgba8Image& image = texture.image;
    glm::ivec2 columns, rows;
    glm::vec2 f;
    raymath::bilinearFootprint(t, image.width, image.height, int(texture.wrapS), int(texture.wrapT), columns, rows, f);
    const std::array<float, 256>& decode = srgbDecodeTable();
    auto texel = [&](int x, int y) {
        const uint32_t c = image.texels[size_t(y) * size_t(image.width) + size_t(x)];
        return glm::vec3(decode[c & 0xffu], decode[(c >> 8) & 0xffu], decode[(c >> 16) & 0xffu]);
    };
    return raymath::bilinearBlend(texel(columns.x, rows.x), texel(columns.y, rows.x), texel(columns.x, rows.y),
                                  texel(columns.y, rows.y), f);
}

float sampleChannel(const Texture& texture, glm::vec2 t, int channel) {
    const Rgba8Image& image = texture.image;
    glm::ivec2 columns, rows;
    glm::vec2 f;
    raymath::bilinearFootprint(t, image.width, image.height, int(texture.wrapS), int(texture.wrapT), columns, rows, f);
    const uint32_t shift = 8u * uint32_t(channel);
    auto texel = [&](int x, int y) {
        const uint32_t c = image.texels[size_t(y) * size_t(image.width) + size_t(x)];
        return glm::vec3(float((c >> shift) & 0xffu));
    };
    return raymath::bilinearBlend(texel(columns.x, rows.x), texel(columns.y, rows.x), texel(columns.x, rows.y),
                                  texel(columns.y, rows.y), f).x /
           255.0f;
}

glm::vec2 texcoordAt(const Scene& scene, uint32_t prim, float u, float v) {
    if (scene.texcoords.empty()) return glm::vec2(0.0f);
    const TriangleTexcoords& c = scene.texcoords[prim];
    return raymath::interpolateTexcoord(c.t0, c.t1, c.t2, u, v);
}

glm::vec3 diffuseAt(const Scene& scene, const Material& m, uint32_t prim, float u, float v) {
    if (m.diffuseTexture < 0 || scene.texcoords.empty()) return m.diffuse;
    const TriangleTexcoords& c = scene.texcoords[prim];
    const glm::vec2 t = raymath::interpolateTexcoord(c.t0, c.t1, c.t2, u, v);
    return m.diffuse * sampleTexture(scene.textures[size_t(m.diffuseTexture)], t);
}

glm::vec3 sampleLinear(const Texture& texture, glm::vec2 t) {
    return {sampleChannel(texture, t, 0), sampleChannel(texture, t, 1), sampleChannel(texture, t, 2)};
}

void texcoordEdgesAt(const Scene& scene, uint32_t prim, glm::vec2& dt1, glm::vec2& dt2) {
    dt1 = dt2 = glm::vec2(0.0f);
    if (scene.texcoords.empty()) return;
    const TriangleTexcoords& c = scene.texcoords[prim];
    dt1 = c.t1 - c.t0;
    dt2 = c.t2 - c.t0;
}

glm::vec4 vertexTangentAt(const Scene& scene, uint32_t prim, float u, float v) {
    if (scene.tangents.empty()) return glm::vec4(0.0f);
    const TriangleTangents& g = scene.tangents[prim];
    return raymath::interpolateTangent(g.t0, g.t1, g.t2, u, v);
}

glm::vec3 vertexColorAt(const Scene& scene, uint32_t prim, float u, float v) {
    if (scene.colors.empty()) return glm::vec3(1.0f);
    const TriangleColors& c = scene.colors[prim];
    return raymath::interpolateVertexColor(c.c0, c.c1, c.c2, u, v);
}

}  // namespace gpurt
