// Whitted's integrator on the cpu backend: one sample's ray tree through a pixel, depth first
// with a stack of pending rays exactly as the gl rounds take it (common/raytree.h), so that the
// colour sums in the same order; every hit is shaded with a shadow ray per light in front of it
// and one to the emitters (glsl/common/integrators/whitted.h over the cpu's hooks; the megakernel
// runs the same file, the wavefront chain WhittedGl the same steps as passes).
#pragma once

#include "raytrace/integrators/CpuIntegrator.h"

#include <vector>

namespace gpurt {

// The colour of the ray tree of the camera ray from eye along d, with up to maxBounces mirror and
// glass levels (< 0: the primary hit only, for the AOVs) and `stackSlots` pending rays.
glm::vec3 whittedSample(const CpuScene& tracer, const PixelSample& px, glm::vec3 eye, glm::vec3 d,
                        const PunctualLights& lights, int maxBounces, int stackSlots, PixelAovs aovs,
                        RenderStats& stats);

}  // namespace gpurt
