// Ambient occlusion (--integrator ao) as a megakernel: each pixel's sample in this one pass
// (common/integrators/ao.h, which the cpu backend runs too): the camera ray traced (the
// accelerator inside, accel/trace.glsl) and one occlusion ray from its hit. AOVS: the primary hit,
// facing normal and step count as well.
#include "integrators/megakernel.glsl"
#include "common/path.h"

uniform float aoDistance;  // --ao-distance (GPURT_FAR: unlimited)

layout(location = 0) out vec4 colorOut;  // (the sample's value, 0)

#include "common/integrators/ao.h"

void main() {
    vec3 o;
    vec3 d;
    beginCameraSample(o, d);
    colorOut = vec4(aoTrace(o, d), 0.0f);
    countRays(0);
}
