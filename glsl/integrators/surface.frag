// Shading, step 1 of a bounce (Whitted 1980; Christen 2005, 5.5): turns the traced ray's hit into
// a surface record (point, facing normal, material, view direction) and starts the local colour
// with the ambient term; an emitter that the ray hits adds weight * its radiance to the pixel. A
// path whose ray missed adds weight * background to the pixel and ends; with an environment light
// (SCENE_ENVIRONMENT) weight * the environment's radiance along the ray instead, and the ambient
// term is the diffuse reflection of the environment's irradiance at the shading normal
// (common/environment.h).
// PATH: for the path integrator: the emission is weighed against next-event estimation of the
// same point (common/path.h emissionWeight, from the pdf of the direction the last hit chose), as is
// the environment a ray finds against next-event estimation of the environment
// (environmentHitWeight), and the local colour starts at 0 (no ambient term).
// FEATURES (with PATH; the denoiser's): a path whose features are still open (pathState w 0;
// common/path.h featuresOpenAfter, the bounce pass closes them) leaves the hit's albedo and shading
// normal, or the background's, in its pixel's elements of pixelAlbedo and pixelNormal.
#include "scene/shading.glsl"
#ifdef PATH
#include "common/path.h"
uniform sampler2D pathState;  // (pdf of the ray's direction at the last hit, 0: delta or camera)
uniform int depth;            // the hits' depth (0: the camera rays')
uniform float clampDirect;    // --clamp-direct (common/path.h clampContribution)
uniform float clampIndirect;  // --clamp-indirect
uniform uint sampleIndex;     // the sample's numbers (unused here: integrators/hooks.glsl needs them)
uniform uint sampleCount;
uniform uint seed;
uniform uint samplerKind;
#ifdef FEATURES
layout(rgba32f) uniform image2D pixelAlbedo;
layout(rgba32f) uniform image2D pixelNormal;
#endif
#endif

uniform sampler2D rayOrigin;
uniform sampler2D rayDir;
uniform sampler2D hitState;
uniform sampler2D weight;      // (product of reflectivities, alive)
uniform sampler2D colorState;  // in place (path: w 1 once the path follows one colour channel, pathDisperse)
uniform vec3 background;

layout(location = 0) out vec4 color;          // (accumulated colour, 0)
layout(location = 1) out vec4 surfacePoint;   // (p, triangle | -1 when this path has no hit)
layout(location = 2) out vec4 surfaceNormal;  // (n facing the ray, material)
layout(location = 3) out vec4 surfaceView;    // (ray direction, barycentric u of the hit)
layout(location = 4) out vec4 localColor;     // (ambient, the hit's distance t); lights add to it
layout(location = 5) out vec4 surfaceShading; // (shading normal, barycentric v): the normal
                                              // smooth, facing as the geometric one

#ifdef PATH
// The sample's features, albedo a and shading normal n (common/integrators/path.h records them
// while they are open).
void recordFeatures(vec3 a, vec3 n) {
#ifdef FEATURES
    ivec2 pixel = pathPixel(readStream(pathState), depth) - ivec2(0, tileRow);
    imageStore(pixelAlbedo, pixel, vec4(a, 0.0f));
    imageStore(pixelNormal, pixel, vec4(n, 0.0f));
#endif
}

#include "integrators/hooks.glsl"
#include "common/integrators/path.h"

// The path of this element as it arrives (its ray, colour c and throughput w so far).
PathState arrivingPath(vec4 c, vec4 w) {
    vec4 state = readStream(pathState);
    PathState st;
    st.o = readStream(rayOrigin).xyz;
    st.d = readStream(rayDir).xyz;
    st.color = c.xyz;
    st.weight = w.xyz;
    st.prevPdf = state.x;
    st.open = state.w == 0.0f;
    st.dispersed = c.w > 0.0f;
    return st;
}
#endif

void main() {
    vec4 w = readStream(weight);
    vec4 c = readStream(colorState);
    vec4 h = readStream(hitState);
    color = c;
    surfacePoint = vec4(0.0f, 0.0f, 0.0f, -1.0f);
    surfaceNormal = vec4(0.0f);
    surfaceView = vec4(0.0f);
    localColor = vec4(0.0f);
    surfaceShading = vec4(0.0f);
    if (w.w == 0.0f) return;  // path ended at an earlier bounce
#ifdef PATH
    PathState st = arrivingPath(c, w);
#endif
    if (h.w < 0.0f) {
#ifdef PATH
        pathMiss(st, depth);
        color = vec4(st.color, c.w);  // w: the path's dispersed flag (path/bounce.frag)
#elif defined(SCENE_ENVIRONMENT)
        color = vec4(c.xyz + w.xyz * environmentRadiance(readStream(rayDir).xyz), 0.0f);
#else
        color = vec4(c.xyz + w.xyz * background, 0.0f);
#endif
        return;
    }
    vec3 o = readStream(rayOrigin).xyz;
    vec3 d = readStream(rayDir).xyz;
    vec3 v0, e1, e2;
    int material;
    fetchTriangle(int(h.w), v0, e1, e2, material);
    vec2 t = fetchTexcoord(int(h.w), h.y, h.z);
    MaterialRecord m = fetchMaterialRecord(material, int(h.w), h.yz, d);
    surfacePoint = vec4(o + h.x * d, h.w);
    vec3 ng = facingNormal(e1, e2, d);
    vec3 ns = fetchMappedNormal(material, int(h.w), e1, e2, d, ng, fetchShadingNormal(int(h.w), h.y, h.z, ng), t, h.yz);
    surfaceNormal = vec4(ng, float(material));
    surfaceShading = vec4(ns, h.z);
    surfaceView = vec4(d, h.y);
    localColor.w = h.x;  // for the bounce passes' crossedWeight
#ifdef PATH
    SurfaceHit s;
    s.p = surfacePoint.xyz;
    s.n = ng;
    s.ns = ns;
    s.front = frontFace(e1, e2, d);
    s.m = materialFacing(m, s.front);
    pathArrive(st, s, h.x, depth);
    color = vec4(st.color, c.w);
#else
    vec3 crossed = materialTransmittance(materialFacing(m, frontFace(e1, e2, d)), h.x);  // the medium the ray crossed
    color = vec4(c.xyz + w.xyz * crossed * materialEmitted(m, ns, d), 0.0f);
#ifdef SCENE_ENVIRONMENT
    localColor.xyz = materialEnvironmentAmbient(m, environmentAmbient(ns));
#else
    localColor.xyz = materialAmbient(m);
#endif
#endif
}
