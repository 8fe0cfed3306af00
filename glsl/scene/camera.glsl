// The contract camera as uniforms (GpuPipeline::setCamera), for the kernels that generate primary
// rays: through the pixel centre (common/raymath.h cameraRayDirection), or through sample
// `sampleIndex` of `sampleCount` of the pixel (common/sampling.h).
#include "pixel.glsl"
#include "../common/sampling.h"
uniform vec3 eye;
uniform vec3 forward;
uniform vec3 right;
uniform vec3 upOrtho;
uniform float tanHalf;
uniform float aspect;
uniform vec2 imageSize;
uniform uint sampleIndex;  // the sample of this pass
uniform uint sampleCount;  // --spp (1: the pixel centre)
uniform uint seed;         // --seed
uniform uint samplerKind;  // --sampler (sampling.h GPURT_SAMPLER_*)
uniform float lensRadius;     // 0: the pinhole camera (Camera.h CameraBasis)
uniform float focusDistance;
uniform int blades;
uniform float bladeRotation;  // radians

// The direction of this fragment's primary ray (stream row y = image row tileRow + y from the
// top; pixel.glsl imagePixel).
vec3 primaryDirection() {
    vec2 pixel = vec2(imagePixel());
    return cameraRayDirection(forward, right, upOrtho, tanHalf, aspect, pixel.x, pixel.y,
                              imageSize.x, imageSize.y);
}

// The direction of this fragment's ray for sample sampleIndex of sampleCount (Camera.cpp
// sampleDirection on the CPU).
vec3 sampleDirectionAt(uvec2 pixel) {
    vec2 offset = pixelSampleOffset(samplerKind, pixel.x, pixel.y, sampleIndex, sampleCount, seed);
    return cameraRayThrough(forward, right, upOrtho, tanHalf, aspect, float(pixel.x) + offset.x,
                            float(pixel.y) + offset.y, imageSize.x, imageSize.y);
}

vec3 sampleDirection() { return sampleDirectionAt(imagePixel()); }

// The camera ray of this fragment's sample for the pinhole direction d at pixel: from the eye, or
// with a lens through the sample's lens point (Camera.cpp sampleRay on the CPU).
void cameraRay(uvec2 pixel, vec3 d, out vec3 origin, out vec3 direction) {
    origin = eye;
    direction = d;
    if (!(lensRadius > 0.0f)) return;
    vec2 u = sample2D(samplerKind, pixel.x, pixel.y, sampleIndex, sampleCount, seed, GPURT_DIM_LENS);
    thinLensRay(eye, forward, right, upOrtho, d, lensRadius, focusDistance, aperturePoint(u, blades, bladeRotation),
                origin, direction);
}
