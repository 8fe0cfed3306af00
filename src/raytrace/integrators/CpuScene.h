// What a sample of the cpu backend asks of the scene (the integrators' hooks, integrators/CpuHooks.h):
// hits of rays through the accelerator, the surface and material record at a hit, shadow rays, the
// emitters and the environment, and the pixel sample's numbers. The render loop around it is
// render/CpuTracer.
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "raytrace/accel/CpuAccelerator.h"
#include "raytrace/common/RayMath.h"
#include "raytrace/common/RenderTypes.h"
#include "raytrace/lights/EmitterTable.h"
#include "raytrace/lights/EnvironmentTable.h"
#include "scene/Scene.h"

namespace gpurt {

// Sample `index` of `count` of pixel (i, j) of the image (its random numbers: common/sampling.h,
// from `sampler`).
struct PixelSample {
    int i, j;
    uint32_t index, count, seed;
    SamplerKind sampler = SamplerKind::Sobol;

    // The sampler's numbers of this sample in the 2D dimension `dimension` (sampling.h sample2D),
    // and its pair for lobe and roulette choices (sampleChoice).
    glm::vec2 sample2D(uint32_t dimension) const {
        return raymath::sample2D(uint32_t(sampler), uint32_t(i), uint32_t(j), index, count, seed, dimension);
    }
    glm::vec2 sampleChoice(uint32_t dimension) const {
        return raymath::sampleChoice(uint32_t(sampler), uint32_t(i), uint32_t(j), index, count, seed, dimension);
    }
    // The coverage key of its rays (common/alpha.h): the accelerators' alpha coverage.
    uint32_t coverageKey() const { return raymath::coverageKey(uint32_t(i), uint32_t(j), index, seed); }
};

class CpuScene {
  public:
    // Keeps a reference to the scene: it must outlive this. rayOffset: how far secondary rays
    // start off a surface.
    CpuScene(const Scene& scene, std::unique_ptr<CpuAccelerator> accel, float rayOffset);

    // First hit of o + t d with 0 < t < tLimit; d must be normalised. coverageKey: the ray's
    // sample (PixelSample::coverageKey) for surfaces with alpha (CpuAccelerator::closestHit).
    TraceHit trace(glm::vec3 o, glm::vec3 d, float tLimit, uint32_t coverageKey = 0u) const;
    // Any hit with 0 < t < tLimit (shadow rays): the traversal ends at the first triangle hit, so
    // prim is some blocker, not necessarily the nearest. Blocked exactly when trace() hits.
    TraceHit traceAny(glm::vec3 o, glm::vec3 d, float tLimit, uint32_t coverageKey = 0u) const;

    struct PreparedTriangle {
        glm::vec3 v0, e1, e2;  // e1 = v1 - v0, e2 = v2 - v0 in float, as the GL side stores them
    };
    const Scene& scene() const { return scene_; }
    const PreparedTriangle& triangle(uint32_t id) const { return triangles_[id]; }
    // How far secondary rays start off a surface (AccelStructure::rayOffset).
    float rayOffset() const { return rayOffset_; }
    const EmitterTable& emitters() const { return emitters_; }
    const EnvironmentTable& environment() const { return environment_; }
    // The surface at a hit of the ray from o along d: the point, the facing geometric normal, the
    // shading normal (common/shading.h), the side and the material record (common/material.h).
    raymath::SurfaceHit surfaceAt(const TraceHit& hit, glm::vec3 o, glm::vec3 d) const;
    // Traces one shadow ray (counted in stats); true when nothing blocks it.
    bool unblocked(glm::vec3 origin, glm::vec3 dir, float limit, uint32_t coverageKey, RenderStats& stats) const;

  private:
    // ns at the hit bent by normal map `map` (-1: none) of scale `scale` (the base's, a coat's).
    glm::vec3 normalMappedAt(const TraceHit& hit, glm::vec3 d, glm::vec3 ng, glm::vec3 ns, int map, float scale) const;

    const Scene& scene_;
    std::unique_ptr<CpuAccelerator> accel_;
    std::vector<PreparedTriangle> triangles_;
    float rayOffset_;
    EmitterTable emitters_;
    EnvironmentTable environment_;
};

}  // namespace gpurt
