// Intel Embree 3 as the baseline of gpurt bench: the scene's triangles in one Embree scene
// (primID = the contract's triangle index) and the same rays, traced on a fixed number of
// threads. Built only with GPURT_WITH_EMBREE (GPURT_HAVE_EMBREE defined).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/Scene.h"

namespace gpurt {

struct RayStream;

// How rays are handed to Embree: one at a time (rtcIntersect1 / rtcOccluded1) or in packets of
// 8 or 16 consecutive rays (rtcIntersect8/16, rtcOccluded8/16).
enum class EmbreeMode { Single, Packet8, Packet16 };

class EmbreeTracer {
  public:
    // Builds the BVH (high quality: the baseline gets Embree's best) with `threads` threads.
    // Throws EnvironmentError when Embree cannot make a device.
    EmbreeTracer(const Scene& scene, int threads);
    ~EmbreeTracer();
    EmbreeTracer(const EmbreeTracer&) = delete;
    EmbreeTracer& operator=(const EmbreeTracer&) = delete;

    // Traces every ray of `rays` (elements with tLimit < 0 are skipped) on the tracer's threads.
    // Closest hit: hits[i] = (t, u, v, triangle | -1); any hit (anyHit): hits[i].w = 0 when
    // blocked, -1 otherwise. Returns the rays traced.
    uint64_t trace(const RayStream& rays, bool anyHit, EmbreeMode mode, std::vector<glm::vec4>& hits) const;

    int threads() const { return threads_; }
    static std::string version();

  private:
    struct Handles;
    std::unique_ptr<Handles> handles_;
    int threads_;
};

}  // namespace gpurt
