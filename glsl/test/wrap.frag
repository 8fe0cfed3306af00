// Test kernel, outer loop of a nested while: for elements whose round count (channel 1) is below
// their target, subtracts 1 from the value (channel 0) and counts the round; discards the others.
#include "../common/stream.glsl"

uniform sampler2D values;
uniform sampler2D targets;
layout(location = 0) out vec4 result;

void main() {
    vec4 v = readStream(values);
    if (v.y >= readStream(targets).x) discard;
    result = vec4(v.x - 1.0f, v.y + 1.0f, v.zw);
}
