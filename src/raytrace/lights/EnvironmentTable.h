// The scene's environment light as both backends use it (glsl/common/environment.h): the map's
// texels (radiance times strength, and each texel's density in (u, v)), the distribution that
// next-event estimation samples (luminance x sin(theta): the rows' marginal cumulative
// distribution and each row's conditional one), the rotation, and the 9 spherical-harmonic
// coefficients of Whitted's ambient term. The GL side uploads these arrays as scene textures
// (SceneTextures) and searches them in the kernels (glsl/scene/environment.glsl); the CPU side
// searches them here, the same way.
#pragma once

#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "base/LargeArray.h"
#include "scene/Scene.h"

namespace gpurt {

struct EnvironmentTable {
    int width = 0, height = 0;              // 0: no environment
    LargeArray<glm::vec4> texels;           // width * height, top row first: (radiance, uvPdf)
    // The distribution, only where `sampled` (empty otherwise: nothing searches it):
    std::vector<float> marginal;            // height: cumulative share of rows 0..j (last exactly 1)
    LargeArray<float> conditional;          // width * height: per row, cumulative share of its columns
    glm::vec2 rotation{1.0f, 0.0f};         // (cos, sin) of the rotation about +Y
    std::array<glm::vec3, 9> harmonics{};   // environment.h environmentIrradiance's c0..c8
    bool sampled = false;                   // next-event estimation samples it (some light, and asked)

    bool empty() const { return width == 0; }
    // The filtered radiance seen along d (environment.glsl environmentRadiance).
    glm::vec3 radiance(glm::vec3 d) const;
    // The solid-angle pdf of sample() drawing d; 0 when not sampled.
    float pdf(glm::vec3 d) const;
    // A direction for the random pair u and its pdf; false when there is none (pdf 0).
    bool sample(glm::vec2 u, glm::vec3& dir, float& pdf) const;
    // The irradiance at unit normal n from the spherical harmonics.
    glm::vec3 irradiance(glm::vec3 n) const;
};

// The table of the scene's environment (empty without one). The environment's `sampled` asks for
// the sampling distribution (false: BSDF sampling alone finds the environment); a map without
// light (or with an infinite total) has none either.
EnvironmentTable buildEnvironmentTable(const Scene& scene);

}  // namespace gpurt
