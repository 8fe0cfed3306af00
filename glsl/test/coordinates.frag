// Test kernel: writes each element's own 2D index (checks the stream generator's coverage).
layout(location = 0) out vec2 index;

void main() { index = floor(gl_FragCoord.xy); }
