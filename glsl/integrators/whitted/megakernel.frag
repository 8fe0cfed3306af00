// Whitted's integrator as a megakernel (--kernel megakernel): each pixel's whole ray tree in this
// one pass, running the control flow WhittedCpu runs per pixel (common/integrators/whitted.h: the
// same rays in the same order, its pending rays on a stack in registers): trace (the accelerator
// inside, accel/trace.glsl), emission, the ambient term, each point light and the round's emitter
// point with its shadow ray, then the tree's next ray (common/raytree.h). The wavefront chain
// (surface, shadowgen, light, bounce passes, one round a ray of each tree) writes each step to
// streams and the stacks to images. AOVS: the primary hit, facing normal and step count as well.
#include "integrators/megakernel.glsl"
#include "common/raytree.h"

uniform int maxBounces;  // mirror and glass levels (--bounces)
uniform int stackSlots;  // the pending rays a tree keeps (GpuTracer::stackSlots)

layout(location = 0) out vec4 colorOut;  // (the sample's colour, 0)

#include "common/integrators/whitted.h"

void main() {
    int rounds;
    vec3 o;
    vec3 d;
    beginCameraSample(o, d);
    vec3 color = whittedTrace(o, d, rounds);
    countRays(rounds);
    colorOut = vec4(color, 0.0f);
}
