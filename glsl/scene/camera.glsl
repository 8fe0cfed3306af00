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
