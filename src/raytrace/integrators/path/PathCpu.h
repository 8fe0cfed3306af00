// The path integrator on the cpu backend: one path through a pixel, the control flow of
// glsl/common/integrators/path.h (which the megakernel and the wavefront stages run too) over the
// cpu's hooks (CpuHooks): the hit's emission (weighed against next-event estimation), then below
// the last depth the point lights, the environment direction and one emitter point, each with a
// shadow ray, then the next direction and Russian roulette.
#pragma once

#include "raytrace/integrators/CpuIntegrator.h"

#include <vector>

namespace gpurt {

// --clamp-direct and --clamp-indirect (0: off; common/path.h clampContribution).
struct PathClamp {
    float direct = 0.0f, indirect = 0.0f;
};

// The colour of the path of the camera ray from eye along d, with hits up to maxDepth; with
// `features`, the sample's features there.
glm::vec3 pathSample(const CpuScene& tracer, const PixelSample& px, glm::vec3 eye, glm::vec3 d,
                     const PunctualLights& lights, int maxDepth, PathClamp clamp, PixelAovs aovs,
                     RenderStats& stats, SampleFeatures* features = nullptr);

}  // namespace gpurt
