// Test kernel on integer streams: exact 32-bit arithmetic and a gather through an index stream.
#include "../common/stream.glsl"

uniform usampler2D words;
uniform usampler2D indices;  // (x, y) of the element to gather
uniform uint salt;
layout(location = 0) out uvec4 result;

void main() {
    uvec4 w = readStream(words);
    uvec4 at = readStream(indices);
    uvec4 g = texelFetch(words, ivec2(at.xy), 0);
    result = uvec4(w.x ^ salt, w.y + g.x, w.z * 3u, g.w);
}
