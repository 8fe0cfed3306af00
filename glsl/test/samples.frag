// Test kernel: element (x, y) holds sample `sampleIndex` of pixel (x, y) in dimension `dimension`
// from each sampler (common/sampling.h): (sobol.x, sobol.y, stratified.x, stratified.y) in the
// first output, (random.x, random.y, choice.x, choice.y) in the second. SamplerGLTest compares them
// with the C++ backend's, bit for bit.
#include "common/raymath.h"
#include "common/sampling.h"

uniform uint sampleIndex;
uniform uint sampleCount;
uniform uint seed;
uniform uint dimension;

layout(location = 0) out vec4 first;
layout(location = 1) out vec4 second;

void main() {
    uvec2 p = uvec2(gl_FragCoord.xy);
    vec2 sobol = sample2D(GPURT_SAMPLER_SOBOL, p.x, p.y, sampleIndex, sampleCount, seed, dimension);
    vec2 stratified = sample2D(GPURT_SAMPLER_STRATIFIED, p.x, p.y, sampleIndex, sampleCount, seed, dimension);
    vec2 random = sample2D(GPURT_SAMPLER_RANDOM, p.x, p.y, sampleIndex, sampleCount, seed, dimension);
    vec2 choice = sampleChoice(GPURT_SAMPLER_SOBOL, p.x, p.y, sampleIndex, sampleCount, seed, dimension + 1u);
    first = vec4(sobol, stratified);
    second = vec4(random, choice);
}
