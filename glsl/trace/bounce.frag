// Shading, last step of a bounce (Christen 2005, eq. 5.1): colour += weight * local colour; then,
// unless this was the last bounce, weight *= reflectivity and a mirror ray leaves the surface.
// Paths with zero weight, no hit or no bounce left end here.
#include "shading.glsl"

uniform sampler2D surfacePoint;
uniform sampler2D surfaceNormal;
uniform sampler2D surfaceView;
uniform sampler2D surfaceShading;
uniform sampler2D localColor;
uniform sampler2D colorState;   // in place
uniform sampler2D weightState;  // in place
uniform int lastBounce;

layout(location = 0) out vec4 color;
layout(location = 1) out vec4 weight;     // (product of reflectivities, alive)
layout(location = 2) out vec4 rayOrigin;  // the mirror ray
layout(location = 3) out vec4 rayDir;

void main() {
    vec4 s = readStream(surfacePoint);
    vec4 w = readStream(weightState);
    color = readStream(colorState);
    weight = vec4(w.xyz, 0.0f);
    rayOrigin = vec4(0.0f);
    rayDir = vec4(0.0f, 0.0f, 0.0f, GPURT_NO_RAY);
    if (s.w < 0.0f) return;  // no hit: the path ended (a miss was shaded by the surface pass)
    color = vec4(color.xyz + w.xyz * readStream(localColor).xyz, 0.0f);
    if (lastBounce != 0) return;
    vec4 nm = readStream(surfaceNormal);
    vec3 kd, ks, reflectivity;
    float ns;
    fetchMaterial(int(nm.w), kd, ks, ns, reflectivity);
    vec3 next = w.xyz * reflectivity;
    if (next == vec3(0.0f)) return;
    vec3 o = offsetOrigin(s.xyz, nm.xyz, rayOffset);
    vec3 d = shadingReflection(readStream(surfaceView).xyz, readStream(surfaceShading).xyz, nm.xyz);
    weight = vec4(next, 1.0f);
    rayOrigin = vec4(o, GPURT_FAR);
    rayDir = vec4(d, gridEntry(o, d, GPURT_FAR));
}
