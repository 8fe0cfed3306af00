// The hooks of the shared integrators (glsl/common/integrators/README.md) on the cpu backend: an
// integrator's cpu form is a struct derived from CpuHooks for one pixel sample, into which its
// glsl/common/integrators/<name>.h is included, so that its functions run as members over these
// (the kernels define the same names as uniforms and functions: integrators/hooks.glsl and
// megakernel.glsl).
#pragma once

#include "raytrace/integrators/CpuIntegrator.h"
#include "raytrace/lights/PunctualLights.h"

#include <vector>

namespace gpurt::raymath {

struct CpuHooks {
    CpuHooks(const CpuScene& tracer, const PixelSample& px, const PunctualLights& lights, PixelAovs aovs,
             RenderStats& stats)
        : tracer(tracer), px(px), lights(lights), aovs(aovs), stats(stats), rayOffset(tracer.rayOffset()),
          emitterArea(tracer.emitters().totalArea), background(tracer.scene().background),
          sceneHasEnvironment(!tracer.environment().empty()), environmentSampled(tracer.environment().sampled),
          sceneHasEmitters(!tracer.emitters().empty()), punctualLightCount(int(lights.size())) {}

    const CpuScene& tracer;
    const PixelSample& px;
    const PunctualLights& lights;  // the render's, converted once (punctualLights)
    PixelAovs aovs;       // where the camera ray's AOVs go
    RenderStats& stats;   // the rays traced
    TraceHit hit{};       // the last closest hit traced (surfaceAt reads it)

    // The scene, as the kernels' uniforms and defines hold it.
    float rayOffset;
    float emitterArea;
    vec3 background;
    bool sceneHasEnvironment;
    bool environmentSampled;
    bool sceneHasEmitters;
    int punctualLightCount;

    vec2 pixelSample2D(uint dim) const { return px.sample2D(dim); }
    vec2 pixelSampleChoice(uint dim) const { return px.sampleChoice(dim); }

    PunctualLight punctualLight(int k) const { return lights[size_t(k)]; }
    vec3 environmentRadiance(vec3 d) const { return tracer.environment().radiance(d); }
    float environmentLightPdf(vec3 d) const { return tracer.environment().pdf(d); }
    vec3 environmentAmbient(vec3 n) const { return tracer.environment().irradiance(n); }
    bool sampleEnvironment(vec2 u, vec3& l, float& pdf) const { return tracer.environment().sample(u, l, pdf); }

    // The emitter point for the sample numbers u (scene/shading.glsl emitterPointOf).
    void emitterPointAt(vec2 u, vec3& q, vec3& e1, vec3& e2, vec3& emission) const {
        const EmitterTable& table = tracer.emitters();
        const size_t k = table.pick(u.x);
        const uint32_t id = table.triangles[k];
        const CpuScene::PreparedTriangle& e = tracer.triangle(id);
        q = emitterPoint(e.v0, e.e1, e.e2, vec2(remapToUnit(u.x, table.lower(k), table.cdf[k]), u.y));
        e1 = e.e1;
        e2 = e.e2;
        emission = tracer.scene().materials[tracer.scene().materialIds[id]].emission;
    }

    // The closest hit of o + t d as the kernels hold it, (t, u, v, triangle | -1); the camera
    // ray's (depth or round 0) steps go to the AOVs.
    vec4 traceClosest(vec3 o, vec3 d, int b) {
        hit = tracer.trace(o, d, GPURT_FAR, px.coverageKey());
        ++(b == 0 ? stats.primaryRays : stats.secondaryRays);
        if (hit.state == RAY_OVERFLOW) ++stats.overflowRays;
        if (b == 0 && aovs.out) aovs.out->steps[aovs.pixel] = static_cast<float>(hit.steps);
        return hit.prim < 0 ? vec4(GPURT_FAR, hit.u, hit.v, -1.0f) : vec4(hit.t, hit.u, hit.v, float(hit.prim));
    }
    SurfaceHit surfaceAt(vec4, vec3 o, vec3 d) const { return tracer.surfaceAt(hit, o, d); }
    void recordPrimary(vec4 h, vec3 n) const {
        if (aovs.out) aovs.write(h.x, h.w, n);
    }
    bool unblockedRay(vec3 o, vec3 d, float limit) { return tracer.unblocked(o, d, limit, px.coverageKey(), stats); }

#define GPURT_TRACE_HOOKS
#include "../../../glsl/common/integrators/lights.h"
};

}  // namespace gpurt::raymath
