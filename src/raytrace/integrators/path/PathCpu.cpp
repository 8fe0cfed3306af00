#include "raytrace/integrators/path/PathCpu.h"

#include "raytrace/integrators/CpuHooks.h"

namespace gpurt {

namespace raymath {
namespace {

// One path sample on the cpu: glsl/common/integrators/path.h over the cpu's hooks.
struct PathHooks : CpuHooks {
    PathHooks(const CpuScene& tracer, const PixelSample& px, const PunctualLights& lights, PixelAovs aovs,
              RenderStats& stats, int maxDepth, PathClamp clamp, SampleFeatures* features)
        : CpuHooks(tracer, px, lights, aovs, stats), maxDepth(maxDepth), clampDirect(clamp.direct),
          clampIndirect(clamp.indirect), features(features) {}

    int maxDepth;
    float clampDirect;
    float clampIndirect;
    SampleFeatures* features;

    vec4 integratorTrace(vec3 o, vec3 d, int b) {
        stats.addLivePaths(size_t(b), 1);
        return traceClosest(o, d, b);
    }
    void recordFeatures(vec3 albedo, vec3 n) const { *features = {albedo, n}; }

#include "../../../../glsl/common/integrators/path.h"
};

}  // namespace
}  // namespace raymath

glm::vec3 pathSample(const CpuScene& t, const PixelSample& px, glm::vec3 eye, glm::vec3 d,
                     const PunctualLights& lights, int maxDepth, PathClamp clamp, PixelAovs aovs,
                     RenderStats& stats, SampleFeatures* features) {
    raymath::PathHooks hooks(t, px, lights, aovs, stats, maxDepth, clamp, features);
    raymath::PathHooks::PathState st = hooks.pathStart(eye, d, features != nullptr);
    bool alive;
    hooks.pathTrace(st, 0, maxDepth, alive);
    return st.color;
}

}  // namespace gpurt
