// Textured diffuse colour on the CPU: what glsl/scene/shading.glsl's texturedDiffuse does in the
// kernels, with the filtering of glsl/common/texture.h shared word for word.
#pragma once

#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "scene/Scene.h"

namespace gpurt {

// The linear value of each 8-bit sRGB code (common/texture.h srgbDecode8); the kernels read the
// same 256 floats from a table texture.
const std::array<float, 256>& srgbDecodeTable();

// The bilinearly filtered linear colour of `texture` at image coordinates t.
glm::vec3 sampleTexture(const Texture& texture, glm::vec2 t);

// Channel `channel` (0 R .. 3 A) of `texture` at image coordinates t, bilinearly filtered, as a
// linear number in [0, 1] (glsl/scene/shading.glsl textureChannel).
float sampleChannel(const Texture& texture, glm::vec2 t, int channel);

// The linear values of `texture`'s red, green and blue channels at t (a normal or anisotropy
// map; glsl/scene/shading.glsl textureLinear).
glm::vec3 sampleLinear(const Texture& texture, glm::vec2 t);

// The texture coordinates of triangle `prim` at barycentrics (u, v) (zeros without any).
glm::vec2 texcoordAt(const Scene& scene, uint32_t prim, float u, float v);

// The differences of triangle `prim`'s texture coordinates along its edges, t1 - t0 and t2 - t0
// (zeros without any; shading.glsl fetchTexcoordEdges).
void texcoordEdgesAt(const Scene& scene, uint32_t prim, glm::vec2& dt1, glm::vec2& dt2);

// Triangle `prim`'s vertex tangent at barycentrics (u, v) (common/shading.h interpolateTangent;
// zero without any; shading.glsl fetchVertexTangent).
glm::vec4 vertexTangentAt(const Scene& scene, uint32_t prim, float u, float v);

// Material m's diffuse colour at barycentrics (u, v) of triangle `prim`: m.diffuse, times its
// texture's colour at the interpolated texture coordinates when it has one.
glm::vec3 diffuseAt(const Scene& scene, const Material& m, uint32_t prim, float u, float v);

// The vertex colour of triangle `prim` at barycentrics (u, v) (common/shading.h
// interpolateVertexColor, as the kernels' fetchVertexColor); white when the scene has none.
glm::vec3 vertexColorAt(const Scene& scene, uint32_t prim, float u, float v);

}  // namespace gpurt
