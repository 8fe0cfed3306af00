// The denoiser's first pass (common/denoise.h, step 1): each pixel's irradiance and the variance of
// its luminance into the signal, and the guides the iterations read (albedo; shading normal and
// depth) into streams of their own.
// SUMS (the viewer): from the running sums of the samples, their squares and features (the means
// as GpuTracer::render and CpuTracer::render divide them), the depth from the pixel-centre ray's
// hit; a pixel's variance of 0 (one sample) is estimated as DenoiseCpu's denoiseVariance does.
// Otherwise from the images (render --denoise, gpurt denoise), uploaded (the variance estimated
// where it is 0 already).
#include "common/stream.glsl"
#include "common/raymath.h"
#include "common/adaptive.h"

#ifdef SUMS
uniform sampler2D sampleSum;  // (sum of the pixel's samples, their count)
#define GPURT_DENOISE_PARAMS
#define GPURT_DENOISE_COLOR(q) (texelFetch(sampleSum, q, 0).xyz / max(texelFetch(sampleSum, q, 0).w, 1.0f))
uniform sampler2D squareSum;  // (sum of their squares, 0)
uniform sampler2D albedoSum;  // (sum of their albedos, 0)
uniform sampler2D normalSum;  // (sum of their shading normals, 0)
uniform sampler2D aovHit;     // the pixel-centre ray's (t, u, v, triangle | -1)
#else
uniform sampler2D colorIn;     // (mean colour, 0)
uniform sampler2D varianceIn;  // (variance of the mean, 0)
uniform sampler2D albedoIn;    // (albedo, 0)
uniform sampler2D normalIn;    // (shading normal, depth)
#endif

#include "common/denoise.h"

layout(location = 0) out vec4 signal;  // (irradiance, variance of its luminance; < 0: refused)
layout(location = 1) out vec4 albedo;  // (albedo, 0)
layout(location = 2) out vec4 normal;  // (shading normal, depth)

void main() {
#ifdef SUMS
    vec4 s = readStream(sampleSum);
    float n = max(s.w, 1.0f);
    vec3 c = vec3(s.xyz) / n;
    vec3 v = sampleMeanVariance(s.xyz, readStream(squareSum).xyz, s.w);
    if (v == vec3(0.0f)) v = denoiseVarianceEstimate(streamIndex(), textureSize(sampleSum, 0));  // (DenoiseCpu denoiseVariance)
    vec3 a = readStream(albedoSum).xyz / n;
    vec4 h = readStream(aovHit);
    normal = vec4(readStream(normalSum).xyz / n, h.w < 0.0f ? GPURT_FAR : h.x);
#else
    vec3 c = readStream(colorIn).xyz;
    vec3 v = readStream(varianceIn).xyz;
    vec3 a = readStream(albedoIn).xyz;
    normal = readStream(normalIn);
#endif
    albedo = vec4(a, 0.0f);
    signal = denoiseDemodulate(c, v, a);
}
