// Test kernel for buffer tables (GPUStorage::Buffer): each element gathers a float and a uint
// texel of two tables at the 1D index its index stream gives.
#include "../common/stream.glsl"

uniform samplerBuffer floats;
uniform usamplerBuffer words;
uniform isampler2D indices;  // .x: the table texel to gather
layout(location = 0) out vec4 gathered;
layout(location = 1) out uvec4 gatheredWords;

void main() {
    int at = readStream(indices).x;
    gathered = texelFetch(floats, at);
    gatheredWords = texelFetch(words, at);
}
