// Test kernel, the seed's loop example (Christen 2005, 4.3): add 0.01 until the value reaches
// 1.0, then discard, so a loop ends when every element has reached 1.0. Channel 0 is the value;
// further channels are passed through.
#include "../common/stream.glsl"

uniform sampler2D values;
layout(location = 0) out vec4 result;

void main() {
    vec4 v = readStream(values);
    if (v.x >= 1.0f) discard;
    result = vec4(v.x + 0.01f, v.yzw);
}
