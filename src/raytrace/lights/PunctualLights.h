// A scene's light (scene/Scene.h Light) as the shared integrators read it (glsl/common/shading.h
// PunctualLight): the cpu hooks, the megakernels' light texture and the wavefront's light passes
// all take it from here, so that a spot's cone falloff is computed once, in C++, for both backends.
#pragma once

#include "raytrace/common/RayMath.h"
#include "scene/Scene.h"

#include <vector>

namespace gpurt {

inline raymath::PunctualLight punctualOf(const Light& l) {
    raymath::PunctualLight p;
    p.kind = int(l.kind);
    p.position = l.position;
    p.direction = l.direction;
    p.color = l.color;
    p.intensity = l.intensity;
    p.cone = l.kind == LightKind::Spot ? raymath::spotCone(l.innerCone, l.outerCone) : glm::vec2(0.0f);
    p.range = l.range;
    return p;
}

// The cpu backend's lights, converted once a render (CpuTracer), not once a sample.
using PunctualLights = std::vector<raymath::PunctualLight>;
inline PunctualLights punctualLights(const std::vector<Light>& lights) {
    PunctualLights out;
    out.reserve(lights.size());
    for (const Light& l : lights) out.push_back(punctualOf(l));
    return out;
}

// The megakernels' light texture (integrators/megakernel.glsl punctualLight): four texels a
// light, (position, intensity), (colour, kind), (direction, range), (cone, 0, 0).
constexpr int kTexelsPerLight = 4;
inline std::vector<float> lightTexels(const std::vector<Light>& lights, size_t slots) {
    std::vector<float> texels(4 * kTexelsPerLight * slots, 0.0f);
    for (size_t k = 0; k < lights.size() && k < slots; ++k) {
        const raymath::PunctualLight l = punctualOf(lights[k]);
        const float light[4 * kTexelsPerLight] = {
            l.position.x,  l.position.y,  l.position.z,  l.intensity, l.color.r, l.color.g, l.color.b, float(l.kind),
            l.direction.x, l.direction.y, l.direction.z, l.range,     l.cone.x,  l.cone.y,  0.0f,      0.0f};
        std::copy(light, light + 4 * kTexelsPerLight, texels.begin() + std::ptrdiff_t(4 * kTexelsPerLight * k));
    }
    return texels;
}

}  // namespace gpurt
