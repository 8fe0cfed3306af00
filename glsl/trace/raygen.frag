// Primary ray generation (Purcell et al. 2002, 4.1; Christen 2005, 5.4.1): one ray per pixel
// through the pixel centre, exactly the contract's camera (common/raymath.h). Rays that miss the
// grid's box are marked rejected; the others start where they enter it (rayDir.w = tEnter).
#include "scene.glsl"

uniform vec3 eye;
uniform vec3 forward;
uniform vec3 right;
uniform vec3 upOrtho;
uniform float tanHalf;
uniform float aspect;
uniform vec2 imageSize;

layout(location = 0) out vec4 rayOrigin;  // (o, tLimit)
layout(location = 1) out vec4 rayDir;     // (d, tEnter | GPURT_MISSED_BOX)

void main() {
    vec2 pixel = floor(gl_FragCoord.xy);  // stream row y = image row from the top
    vec3 d = cameraRayDirection(forward, right, upOrtho, tanHalf, aspect, pixel.x, pixel.y,
                                imageSize.x, imageSize.y);
    rayOrigin = vec4(eye, GPURT_FAR);
    rayDir = vec4(d, gridEntry(eye, d, GPURT_FAR));
}
