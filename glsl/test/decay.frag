// Test kernel for a while over two kernels: multiplies values above `limit` by `factor`,
// discarding the others (they keep their value).
#include "../common/stream.glsl"

uniform sampler2D values;
uniform float limit;
uniform float factor;
layout(location = 0) out float result;

void main() {
    float v = readStream(values).x;
    if (v <= limit) discard;
    result = v * factor;
}
