// The CPU backend: the same accelerator, traversal and shading as the GL kernels, evaluated ray by
// ray in C++ with the shared code of glsl/common. It is the reference the GL backend is tested
// against and the fallback with --backend cpu.
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "raytrace/camera/Camera.h"
#include "raytrace/lights/EmitterTable.h"
#include "raytrace/lights/EnvironmentTable.h"
#include "raytrace/common/RayMath.h"
#include "raytrace/accel/CpuAccelerator.h"
#include "raytrace/common/RenderTypes.h"
#include "scene/Scene.h"
#include "raytrace/accel/grid/UniformGrid.h"

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

// Adaptive sampling's convergence pass over a width x height image (glsl/integrators/converge.frag
// on the cpu): each active pixel (active[i] != 0) stays active while one of its 3 x 3
// neighbourhood's errors (common/adaptive.h, from the sums of all and of the odd samples and the
// counts) is at or above the threshold; on `threads` threads. Returns the pixels still active.
uint64_t convergencePass(int width, int height, const std::vector<glm::vec3>& sums,
                         const std::vector<glm::vec3>& oddSums, const std::vector<float>& counts, float threshold,
                         int threads, std::vector<uint8_t>& active);

class CpuTracer {
  public:
    // Keeps references to both: they must outlive the tracer.
    CpuTracer(const Scene& scene, const UniformGrid& grid);
    // Over any accelerator of the scene; rayOffset: how far secondary rays start off a surface.
    CpuTracer(const Scene& scene, std::unique_ptr<CpuAccelerator> accel, float rayOffset);

    // First hit of o + t d with 0 < t < tLimit; d must be normalised. coverageKey: the ray's
    // sample (PixelSample::coverageKey) for surfaces with alpha (CpuAccelerator::closestHit).
    TraceHit trace(glm::vec3 o, glm::vec3 d, float tLimit, uint32_t coverageKey = 0u) const;
    // Any hit with 0 < t < tLimit (shadow rays): the traversal ends at the first triangle hit, so
    // prim is some blocker, not necessarily the nearest. Blocked exactly when trace() hits.
    TraceHit traceAny(glm::vec3 o, glm::vec3 d, float tLimit, uint32_t coverageKey = 0u) const;

    // Traces every ray of `rays` (elements with tLimit < 0 are skipped) on `threads` threads
    // (0: all cores), closest or any hit, into hits[i] = (t, u, v, triangle | -1); returns the
    // rays traced (gpurt bench).
    uint64_t traceStream(const RayStream& rays, bool anyHit, int threads, std::vector<glm::vec4>& hits) const;

    // Renders the camera's image (its width x height) under settings.integrator with the AOVs, on
    // settings.threads threads (0: all cores), rows handed out dynamically.
    RenderOutput render(const CameraBasis& camera, const RenderSettings& settings) const;

    // What the integrators' samples use (integrators/whitted/WhittedCpu, integrators/path/PathCpu).
    struct PreparedTriangle {
        glm::vec3 v0, e1, e2;  // e1 = v1 - v0, e2 = v2 - v0 in float, as the GL side stores them
    };
    const Scene& scene() const { return scene_; }
    const PreparedTriangle& triangle(uint32_t id) const { return triangles_[id]; }
    // How far secondary rays start off a surface (UniformGrid::rayOffset).
    float rayOffset() const { return rayOffset_; }
    const EmitterTable& emitters() const { return emitters_; }
    const EnvironmentTable& environment() const { return environment_; }
    // The surface at a hit of the ray from o along d: the point, the facing geometric normal, the
    // shading normal (common/shading.h), the side and the material record (common/material.h).
    raymath::SurfaceHit surfaceAt(const TraceHit& hit, glm::vec3 o, glm::vec3 d) const;
    // Traces one shadow ray (counted in stats); true when nothing blocks it.
    bool unblocked(glm::vec3 origin, glm::vec3 dir, float limit, uint32_t coverageKey, RenderStats& stats) const;

  private:
    const Scene& scene_;
    std::unique_ptr<CpuAccelerator> accel_;
    std::vector<PreparedTriangle> triangles_;
    float rayOffset_;
    EmitterTable emitters_;
    EnvironmentTable environment_;
};

}  // namespace gpurt
