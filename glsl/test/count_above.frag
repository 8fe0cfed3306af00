// Test kernel: writes 1 for each value above `limit` and discards the others: its occlusion count
// is the number of elements still above the limit.
#include "../common/stream.glsl"

uniform sampler2D values;
uniform float limit;
layout(location = 0) out float flag;

void main() {
    if (readStream(values).x <= limit) discard;
    flag = 1.0f;
}
