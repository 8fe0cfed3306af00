// Test kernel: result = value * scale + offset on every element (sequence and for-loop tests).
#include "../common/stream.glsl"

uniform sampler2D values;
uniform float scale;
uniform float offset;
layout(location = 0) out float result;

void main() { result = readStream(values).x * scale + offset; }
