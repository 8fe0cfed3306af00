// The passes both integrators run on gl (glsl/integrators/*.frag; the path integrator's with
// PATH), each declared with the streams it reads and writes, so that an integrator's constructor
// says which passes it has and its stages say when they run.
#pragma once

#include "raytrace/integrators/GpuPipeline.h"

#include <string>
#include <vector>

namespace gpurt {

// The variants of the integrators' kernels, as flags (Magnum's shaders choose theirs alike); each
// is a #define of the kernel's source (passDefines).
enum PassFlag : unsigned {
    kPathPass = 1,      // PATH: the path integrator's variant
    kEmitterPass = 2,   // EMITTER: for the emitters' sample point instead of a point light
    kPackPass = 4,      // PACK: the path bounce that packs the live paths
    kLastRound = 8,     // LAST_ROUND: Whitted's bounce when no ray can follow
    kPixelCentre = 16,  // PIXEL_CENTRE: raygen through the pixel centres
    kEnvironmentPass = 32,  // ENVIRONMENT: for the environment light's sample direction (path)
    kCameraPass = 64,   // CAMERA: a megakernel's first pass, from the camera rays it makes itself
    kAovPass = 128,     // AOVS: a megakernel's first pass writes the primary hits' AOVs as well
};
std::vector<std::string> passDefines(unsigned flags);

// surface.frag: the round's hits into surface records (point, facing normal and material, view
// direction and texture coordinates, shading normal), emission and misses into the colour.
//   reads rayOrigin, rayDir, hit, weight (PATH: pathState); in place color;
//   writes surfacePoint, surfaceNormal, surfaceView, localColor, surfaceShading.
void declareSurfacePass(GPUKernel& k, GpuPipeline& p, bool path);

// shadowgen.frag: a shadow ray from each surface point towards a point light, or (emitter) the
// sample's point of the emitters.
//   reads surfacePoint, surfaceNormal (PATH: surfaceView, surfaceShading; emitter: pathState);
//   writes rayOrigin, rayDir (emitter: lightSample).
void declareShadowgenPass(GPUKernel& k, GpuPipeline& p, bool path, bool emitter);
// shadowgen.frag ENVIRONMENT: a shadow ray along each surface point's sample direction of the
// environment. reads surfacePoint, surfaceNormal, surfaceView, surfaceShading, pathState;
// writes rayOrigin, rayDir, lightSample.
void declareEnvironmentShadowgenPass(GPUKernel& k, GpuPipeline& p);

// light.frag: a light's term at each surface point its shadow ray found unblocked.
//   reads surfacePoint, surfaceNormal, surfaceView, surfaceShading, hit (emitter: lightSample);
//   in place localColor.
void declareLightPass(GPUKernel& k, GpuPipeline& p, bool emitter);  // emitter: or the environment

// Light `light` as the uniforms of shadowgen.frag and light.frag (integrators/light_uniforms.glsl).
void setLightUniforms(GPUKernel& k, const Light& light);

// accumulate.frag: the sample's colour into the pixels' sums.
//   reads `colour`; in place sampleSum.
void declareAccumulatePass(GPUKernel& k, GpuPipeline& p, const GPUFloatArray& colour);

}  // namespace gpurt
