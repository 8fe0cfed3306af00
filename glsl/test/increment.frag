// Test kernel for masking: adds 1 to every element it runs on (the mask decides which).
#include "../common/stream.glsl"

uniform sampler2D values;
layout(location = 0) out float result;

void main() { result = readStream(values).x + 1.0f; }
