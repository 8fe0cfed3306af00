// Primary ray generation (Purcell et al. 2002, 4.1; Christen 2005, 5.4.1): one ray per pixel
// through the pixel centre, exactly the contract's camera (common/raymath.h), or, for --spp, through
// the pass's sample of the pixel (common/sampling.h; one pass per sample). Rays that miss the
// (The grid's trace.frag with CAMERA generates the same rays itself when only the hits are wanted.)
#include "scene/scene.glsl"
#include "scene/camera.glsl"

layout(location = 0) out vec4 rayOrigin;  // (o, tLimit)
layout(location = 1) out vec4 rayDir;     // (d, GPURT_A_RAY)

void main() {
#ifdef PIXEL_CENTRE  // one sample a pixel: llvmpipe would run sampleDirection's jitter under masks
    vec3 d = primaryDirection();
#else
    vec3 d = sampleDirection();
#endif
    vec3 o;
    cameraRay(imagePixel(), d, o, d);
    rayOrigin = vec4(o, GPURT_FAR);
    rayDir = vec4(d, GPURT_A_RAY);
}
