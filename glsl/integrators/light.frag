// Adds one punctual light's diffuse and specular term to the local colour of each surface point
// whose shadow ray found no occluder. EMITTER: the same for the emitter point each surface point
// took (shadowgen.frag EMITTER), as a point light of the intensity emitterIntensity gives it.
// ENVIRONMENT (with PATH): the environment direction each surface point drew (shadowgen.frag
// ENVIRONMENT), unshadowed, through the BSDF and weighed against the BSDF's sampling of it
// (common/path.h pathEnvironmentContribution).
// PATH: the path integrator's light through the BSDF (common/path.h) instead of Whitted's terms, for point lights (its emitter point is lit in path/bounce.frag).
#include "scene/shading.glsl"
#ifdef PATH
#include "common/path.h"
#endif

uniform sampler2D surfacePoint;
uniform sampler2D surfaceNormal;
uniform sampler2D surfaceView;
uniform sampler2D surfaceShading;
uniform sampler2D hitState;    // the shadow rays' hits
uniform sampler2D localState;  // in place
#ifdef EMITTER
uniform sampler2D lightSample;  // (q, emitting triangle | -1)
#elif defined(ENVIRONMENT)
uniform sampler2D lightSample;  // (direction, pdf | 0)
#else
#include "integrators/light_uniforms.glsl"
#endif

layout(location = 0) out vec4 localColor;

void main() {
    vec4 s = readStream(surfacePoint);
    vec4 nm = readStream(surfaceNormal);
#ifdef ENVIRONMENT
    vec4 q = readStream(lightSample);
    if (s.w < 0.0f || !(q.w > 0.0f) || readStream(hitState).w >= 0.0f) discard;  // none, or in shadow
#elif defined(EMITTER)
    vec4 q = readStream(lightSample);
    if (s.w < 0.0f || q.w < 0.0f || readStream(hitState).w >= 0.0f)
        discard;  // no surface, emitter point behind it, or in shadow: the local colour stays
    vec3 v0, e1, e2;
    int emitterMaterial;
    fetchTriangle(int(q.w), v0, e1, e2, emitterMaterial);
    vec3 lightPosition = q.xyz;
    vec3 lightColor = fetchEmission(emitterMaterial);
    float lightIntensity = emitterIntensity(s.xyz, lightPosition, e1, e2, emitterArea);
#else
    PunctualLight light = uniformLight();
    vec3 lightPosition;
    float lightIntensity;
    vec3 lightColor = light.color;
    if (s.w < 0.0f || !punctualAsPoint(light, s.xyz, lightPosition, lightIntensity) ||
        !lightInFront(s.xyz, nm.xyz, lightPosition) || readStream(hitState).w >= 0.0f)
        discard;  // no surface, light not reaching it or behind it, or in shadow: the local colour stays
#endif
    vec4 shading = readStream(surfaceShading);
    vec4 view = readStream(surfaceView);
    vec3 n = shading.xyz;
    vec3 d = view.xyz;
    MaterialRecord m = fetchMaterialRecord(int(nm.w), int(s.w), vec2(view.w, shading.w), view.xyz);
#ifdef SCENE_TRANSMISSION  // a transmissive glTF material: its index as seen from the ray's side
    vec3 sv0, se1, se2;
    int surfaceMaterial;
    fetchTriangle(int(s.w), sv0, se1, se2, surfaceMaterial);
    m = materialFacing(m, frontFace(se1, se2, d));
#endif
#ifdef ENVIRONMENT
    vec3 add = pathEnvironmentContribution(m, n, d, q.xyz, environmentRadiance(q.xyz), q.w);
#elif defined(PATH)
    vec3 add = pathLightContribution(m, s.xyz, n, d, lightPosition, lightColor, lightIntensity);
#else
    vec3 add = materialLight(m, s.xyz, n, d, lightPosition, lightColor, lightIntensity);
#endif
    vec4 before = readStream(localState);
    localColor = vec4(before.xyz + add, before.w);  // w: the hit's distance (surface.frag)
}
