// An iteration of the denoiser (common/denoise.h, step 2): the a-trous filter with holes of
// `stride` pixels over the signal, guided by the albedo, normal and depth streams.
// REMODULATE (the last iteration, step 3): writes the colour (irradiance times albedo) instead.
#include "common/stream.glsl"
#include "common/raymath.h"

uniform sampler2D signal;       // (irradiance, variance of its luminance)
uniform sampler2D albedoGuide;  // (albedo, 0)
uniform sampler2D normalGuide;  // (shading normal, depth)
uniform int stride;  // the holes: 2^i pixels in iteration i

#define GPURT_DENOISE_PARAMS
#define GPURT_DENOISE_SIGNAL(q) texelFetch(signal, q, 0)
#define GPURT_DENOISE_ALBEDO(q) texelFetch(albedoGuide, q, 0).xyz
#define GPURT_DENOISE_NORMAL(q) texelFetch(normalGuide, q, 0)
#include "common/denoise.h"

layout(location = 0) out vec4 result;

void main() {
    ivec2 p = streamIndex();
    vec4 filtered = denoiseIteration(p, textureSize(signal, 0), stride);
#ifdef REMODULATE
    result = vec4(denoiseRemodulate(filtered, texelFetch(albedoGuide, p, 0).xyz), 1.0f);
#else
    result = filtered;
#endif
}
