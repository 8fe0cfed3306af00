// Test kernel: three outputs of different widths from two inputs (multiple render targets).
#include "../common/stream.glsl"

uniform sampler2D a;
uniform sampler2D b;
layout(location = 0) out vec4 sum;
layout(location = 1) out float product;
layout(location = 2) out vec2 pair;

void main() {
    vec4 x = readStream(a);
    vec4 y = readStream(b);
    sum = x + y;
    product = x.x * y.x;
    pair = vec2(x.y, y.y);
}
