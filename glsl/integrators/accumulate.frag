// The sample loop's sum (--spp): adds this sample's pixel colour to the running sum of the
// pixel's samples and counts it (w). The mean is the sum divided by the count (GpuTracer::render,
// and the viewer's present pass), so each sample costs one more pass over the chain, not more.
// ODD_SUM (adaptive sampling): the odd-numbered samples are summed apart as well
// (common/adaptive.h). Under adaptive sampling the pass runs only for the active pixels.
// SQUARE_SUM (the variance AOV): the squares of the samples are summed as well.
// FEATURE_SUM (the denoiser's features): the samples' albedos and shading normals as well.
#include "common/stream.glsl"

uniform sampler2D colorState;  // this sample's colour
uniform sampler2D sumState;    // in place
#ifdef ODD_SUM
uniform sampler2D oddState;  // in place
uniform float odd;           // 1 for an odd-numbered sample, else 0
#endif
#ifdef SQUARE_SUM
uniform sampler2D squareState;  // in place
#endif
#ifdef FEATURE_SUM
uniform sampler2D albedoSample;  // this sample's features
uniform sampler2D normalSample;
uniform sampler2D albedoState;   // in place
uniform sampler2D normalState;   // in place
#endif

layout(location = 0) out vec4 sum;
#ifdef ODD_SUM
layout(location = 1) out vec4 oddOut;
#endif
// The outputs in the order of SharedPasses declareAccumulatePass.
#if defined(SQUARE_SUM) && defined(ODD_SUM)
layout(location = 2) out vec4 squareOut;
#elif defined(SQUARE_SUM)
layout(location = 1) out vec4 squareOut;
#endif
#if defined(FEATURE_SUM) && defined(SQUARE_SUM) && defined(ODD_SUM)
layout(location = 3) out vec4 albedoOut;
layout(location = 4) out vec4 normalOut;
#elif defined(FEATURE_SUM) && (defined(SQUARE_SUM) || defined(ODD_SUM))
layout(location = 2) out vec4 albedoOut;
layout(location = 3) out vec4 normalOut;
#elif defined(FEATURE_SUM)
layout(location = 1) out vec4 albedoOut;
layout(location = 2) out vec4 normalOut;
#endif

void main() {
    vec3 c = readStream(colorState).xyz;
    vec4 s = readStream(sumState);
    sum = vec4(s.xyz + c, s.w + 1.0f);
#ifdef ODD_SUM
    oddOut = vec4(readStream(oddState).xyz + (odd > 0.5f ? c : vec3(0.0f)), 0.0f);
#endif
#ifdef SQUARE_SUM
    squareOut = vec4(readStream(squareState).xyz + c * c, 0.0f);
#endif
#ifdef FEATURE_SUM
    albedoOut = vec4(readStream(albedoState).xyz + readStream(albedoSample).xyz, 0.0f);
    normalOut = vec4(readStream(normalState).xyz + readStream(normalSample).xyz, 0.0f);
#endif
}
