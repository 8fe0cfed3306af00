// The passes both integrators run on gl (glsl/integrators/*.frag; the path integrator's with
// PATH), each declared with the streams it reads and writes, so that an integrator's constructor
// says which passes it has and its stages say when they run.
#pragma once

#include "raytrace/GpuPipeline.h"

namespace gpurt {

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

// light.frag: a light's term at each surface point its shadow ray found unblocked.
//   reads surfacePoint, surfaceNormal, surfaceView, surfaceShading, hit (emitter: lightSample);
//   in place localColor.
void declareLightPass(GPUKernel& k, GpuPipeline& p, bool emitter);

// accumulate.frag: the sample's colour into the pixels' sums.
//   reads `colour`; in place sampleSum.
void declareAccumulatePass(GPUKernel& k, GpuPipeline& p, const GPUFloatArray& colour);

}  // namespace gpurt
