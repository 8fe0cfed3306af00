// Shadow ray generation for one punctual light: from each surface point that the light reaches
// and is in front of, towards the light, limited to the distance to the light. Other elements carry no ray.
// EMITTER: for the emitters (area lights) instead: each surface point takes its sample's point q
// of the emitters, uniform by area (common/sampling.h, dimension GPURT_DIM_EMITTER + bounce; the
// emitter by a binary search of the area table), stores it for the light pass, and aims the ray
// at it. PATH: only from surfaces that the path integrator's diffuse or glossy lobe can light
// (not from mirrors and glass: common/material.h materialLit).
// ENVIRONMENT (with PATH): for the environment light instead: each surface point draws its
// sample's direction of the environment (environment.glsl sampleEnvironment, dimension
// GPURT_DIM_ENVIRONMENT + bounce), stores it with its pdf for the light pass, and sends an
// unbounded shadow ray along it when it is in front of the surface.
#include "scene/shading.glsl"
#include "common/sampling.h"
#ifdef PATH
#include "common/path.h"
uniform sampler2D pathState;  // the path's pixel (packed paths: shading.glsl pathPixel)
#endif

uniform sampler2D surfacePoint;
uniform sampler2D surfaceNormal;
#ifdef PATH
uniform sampler2D surfaceView;     // w: the hit's barycentric u
uniform sampler2D surfaceShading;  // w: v
#endif
#if defined(EMITTER) || defined(ENVIRONMENT)
uniform uint sampleIndex;
uniform uint sampleCount;
uniform uint seed;
uniform uint samplerKind;
uniform uint bounce;
#else
#include "integrators/light_uniforms.glsl"
#endif

layout(location = 0) out vec4 rayOrigin;  // (o, tLimit)
layout(location = 1) out vec4 rayDir;     // (d, GPURT_A_RAY | GPURT_NO_RAY)
#ifdef EMITTER
layout(location = 2) out vec4 lightSample;  // (q, emitting triangle | -1)
#elif defined(ENVIRONMENT)
layout(location = 2) out vec4 lightSample;  // (direction, pdf | 0: none)
#endif

void main() {
    vec4 s = readStream(surfacePoint);
    vec4 nm = readStream(surfaceNormal);
    vec3 n = nm.xyz;
    rayOrigin = vec4(0.0f);
    rayDir = vec4(0.0f, 0.0f, 0.0f, GPURT_NO_RAY);
#ifdef PATH
    if (s.w >= 0.0f &&
        !materialLit(fetchMaterialRecord(int(nm.w), int(s.w), vec2(readStream(surfaceView).w, readStream(surfaceShading).w),
                                         readStream(surfaceView).xyz)))
        s.w = -1.0f;  // nothing to light
#endif
#ifdef ENVIRONMENT
    lightSample = vec4(0.0f);
    if (s.w < 0.0f) return;
    uvec2 pixel = uvec2(pathPixel(readStream(pathState), int(bounce)));
    vec2 u = sample2D(samplerKind, pixel.x, pixel.y, sampleIndex, sampleCount, seed, GPURT_DIM_ENVIRONMENT + bounce);
    vec3 l;
    float pdf;
    if (!sampleEnvironment(u, l, pdf) || !(dot(n, l) > 0.0f)) return;
    lightSample = vec4(l, pdf);
    vec3 o = offsetOrigin(s.xyz, n, rayOffset);
    vec3 d = l;
    float tLimit = GPURT_FAR;
#elif defined(EMITTER)
    lightSample = vec4(0.0f, 0.0f, 0.0f, -1.0f);
    if (s.w < 0.0f) return;
#ifdef PATH
    uvec2 pixel = uvec2(pathPixel(readStream(pathState), int(bounce)));
#else
    uvec2 pixel = imagePixel();
#endif
    int id;
    vec3 lightPosition = emitterSamplePoint(pixel, sampleIndex, sampleCount, seed, samplerKind, bounce, id);
    if (!lightInFront(s.xyz, n, lightPosition)) return;
    lightSample = vec4(lightPosition, float(id));
    vec3 o, d;
    float tLimit;
    emitterShadowRay(s.xyz, n, rayOffset, lightPosition, o, d, tLimit);
#else
    PunctualLight light = uniformLight();
    vec3 position;
    float intensity;
    if (s.w < 0.0f || !punctualAsPoint(light, s.xyz, position, intensity) || !lightInFront(s.xyz, n, position)) return;
    vec3 o, d;
    float tLimit;
    punctualShadowRay(light, s.xyz, n, rayOffset, position, o, d, tLimit);
#endif
    rayOrigin = vec4(o, tLimit);
    rayDir = vec4(d, GPURT_A_RAY);
}
