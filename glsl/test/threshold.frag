// Test kernel: writes 2 * value where value >= threshold and discards the other elements, so the
// occlusion count is the number of elements at or above the threshold.
#include "../common/stream.glsl"

uniform sampler2D values;
uniform float threshold;
layout(location = 0) out float result;

void main() {
    float v = readStream(values).x;
    if (v < threshold) discard;
    result = 2.0f * v;
}
