// The hooks of the shared integrators (common/integrators/README.md) that every integrator kernel
// defines the same way: what the scene has (compiled in: SceneTextures::bind and Megakernel's
// defines), and the numbers of the sample that the element takes for its pixel. Include after the
// uniforms sampleIndex, sampleCount, seed and samplerKind (scene/camera.glsl, or the kernel's own).
#include "scene/shading.glsl"

#ifdef SCENE_ENVIRONMENT
const bool sceneHasEnvironment = true;
#else
const bool sceneHasEnvironment = false;
#endif
#ifdef ENVIRONMENT_LIGHT  // the environment is sampled by next-event estimation
const bool environmentSampled = true;
#else
const bool environmentSampled = false;
#endif
#ifdef SCENE_EMITTERS
const bool sceneHasEmitters = true;
#else
const bool sceneHasEmitters = false;
#endif

// The pixel whose sample the element takes (its main sets it).
uvec2 samplePixel = uvec2(0u);

vec2 pixelSample2D(uint dim) {
    return sample2D(samplerKind, samplePixel.x, samplePixel.y, sampleIndex, sampleCount, seed, dim);
}

vec2 pixelSampleChoice(uint dim) {
    return sampleChoice(samplerKind, samplePixel.x, samplePixel.y, sampleIndex, sampleCount, seed, dim);
}
