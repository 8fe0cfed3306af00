// Shadow ray generation for one point light: from each surface point that the light is in front
// of, towards the light, limited to the distance to the light. Other elements carry no ray.
#include "shading.glsl"

uniform sampler2D surfacePoint;
uniform sampler2D surfaceNormal;
uniform vec3 lightPosition;

layout(location = 0) out vec4 rayOrigin;  // (o, tLimit)
layout(location = 1) out vec4 rayDir;     // (d, tEnter | GPURT_MISSED_BOX | GPURT_NO_RAY)

void main() {
    vec4 s = readStream(surfacePoint);
    vec3 n = readStream(surfaceNormal).xyz;
    if (s.w < 0.0f || !lightInFront(s.xyz, n, lightPosition)) {
        rayOrigin = vec4(0.0f);
        rayDir = vec4(0.0f, 0.0f, 0.0f, GPURT_NO_RAY);
        return;
    }
    vec3 o, d;
    float tLimit;
    shadowRay(s.xyz, n, rayOffset, lightPosition, o, d, tLimit);
    rayOrigin = vec4(o, tLimit);
    rayDir = vec4(d, gridEntry(o, d, tLimit));
}
