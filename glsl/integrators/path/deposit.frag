// The end of the path integrator's last round: every path still alive leaves its colour in its
// pixel's element of pixelColor, as the bounce pass does for the paths that end before
// (path/bounce.frag), so that each pixel has its sample's colour there once.
#include "scene/shading.glsl"

uniform sampler2D colorState;
uniform sampler2D weightState;
uniform sampler2D pathStateIn;
uniform int depth;
layout(rgba32f) uniform image2D pixelColor;

layout(location = 0) out vec4 lives;

void main() {
    lives = vec4(0.0f);
    if (readStream(weightState).w == 0.0f) return;
    imageStore(pixelColor, pathPixel(readStream(pathStateIn), depth) - ivec2(0, tileRow), vec4(readStream(colorState).xyz, 0.0f));
}
