// The primary AOVs of the pixel centres in one pass, for the renders whose integrators are
// megakernels (several samples a pixel, and the viewer): the camera ray through each pixel centre
// traced (the accelerator inside, accel/trace.glsl) into its hit, step count and facing geometric
// normal, as Whitted's wavefront round does with its trace and surface passes.
#define PIXEL_CENTRE_AOVS  // its outputs are these, not the megakernels' AOVS
#include "integrators/megakernel.glsl"

layout(location = 0) out vec4 hitOut;     // (t, u, v, triangle | -1)
layout(location = 1) out vec4 normalOut;  // (facing geometric normal, 0)
layout(location = 2) out ivec4 stepsOut;  // w: the cells or nodes the trace visited

void main() {
    beginPixel(imagePixel());
    vec3 d = primaryDirection();
    int steps;
    vec4 h = traceClosest(eye, d, GPURT_FAR, true, steps);
    hitOut = h;
    stepsOut = ivec4(0, 0, 0, steps);
    normalOut = vec4(0.0f);
    if (h.w >= 0.0f) normalOut = vec4(surfaceAt(h, eye, d).n, 0.0f);
    countRays(0);
}
