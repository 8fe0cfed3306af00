// The path integrator's control flow (--integrator path), written once: the cpu backend
// (integrators/path/PathCpu.cpp), the megakernel (glsl/integrators/path/megakernel.frag) and the
// wavefront chain's stages (glsl/integrators/surface.frag: pathMiss and pathArrive;
// glsl/integrators/path/bounce.frag: pathScatter) run these functions, so that each change to light
// transport is made in one place. The light transport itself (the MIS weights, the light
// contributions, Russian roulette) is common/path.h's.
//
// The includer defines the hooks first (common/integrators/README.md): the scene's
// (the "uniforms" rayOffset, emitterArea, background, sceneHasEnvironment, punctualLightCount,
// clampDirect, clampIndirect, maxDepth; environmentRadiance, environmentLightPdf), the
// pixel's sample numbers (pixelSample2D, pixelSampleChoice), recordFeatures, and where the
// includer traces rays itself (GPURT_TRACE_HOOKS defined: pathDirectLight, pathBounce and
// pathTrace), tracing (integratorTrace, surfaceAt, recordPrimary, punctualLight, lightVisible,
// environmentVisible, emitterVisible). GLSL: globals and functions before the #include; C++: the
// members of the struct the file is included into.
#ifndef GPURT_INTEGRATOR_PATH_H
#define GPURT_INTEGRATOR_PATH_H

#ifndef GPURT_PATH_H
#error "include common/path.h before common/integrators/path.h"
#endif

// A path between two of its depths: the ray it follows, the colour it has gathered, its
// throughput, the pdf with which its last hit chose the ray's direction (0: the camera ray or a
// delta lobe: what the ray finds counts in full) and whether its sample's features (the
// denoiser's) are still to be recorded.
struct PathState {
    vec3 o;
    vec3 d;
    vec3 color;
    vec3 weight;
    float prevPdf;
    bool open;
    bool dispersed;  // it follows one colour channel since a dispersing solid (pathDisperse)
};

// The path of a camera ray o + t d (features: the sample's features are wanted).
GPURT_FN PathState pathStart(vec3 o, vec3 d, bool features) {
    PathState st;
    st.o = o;
    st.d = d;
    st.color = vec3(0.0f);
    st.weight = vec3(1.0f);
    st.prevPdf = 0.0f;
    st.open = features;
    st.dispersed = false;
    return st;
}

// Adds contribution c (before its throughput) found at depth b to the path, clamped as
// --clamp-direct and --clamp-indirect say.
GPURT_FN void pathAdd(GPURT_INOUT(PathState) st, vec3 c, int b) {
    st.color = st.color + clampContribution(st.weight * c, b, clampDirect, clampIndirect);
}

// The path's ray left the scene at depth b: the background's features, and the sky it sees
// (the environment weighed against its next-event estimation, or the background colour).
GPURT_FN void pathMiss(GPURT_INOUT(PathState) st, int b) {
    if (st.open) recordFeatures(vec3(GPURT_BACKGROUND_ALBEDO), vec3(0.0f));
    if (sceneHasEnvironment)
        pathAdd(st, environmentRadiance(st.d) * environmentHitWeight(st.prevPdf, environmentLightPdf(st.d)), b);
    else
        pathAdd(st, background, b);
}

// The path's ray reached surface s at distance t: its throughput times what of the light the
// medium it crossed lets through (a KHR_materials_volume solid's Beer-Lambert absorption, seen from
// inside). pathArrive applies it; the wavefront chain's bounce pass again, as the surface pass
// does not write the throughput back.
GPURT_FN void pathCross(GPURT_INOUT(PathState) st, SurfaceHit s, float t) {
    st.weight = st.weight * materialTransmittance(s.m, t);
}

// The path's ray hit surface s at distance t, depth b: the medium it crossed (pathCross), the hit's
// features while they are open, and its emission, weighed against next-event estimation of the
// same point.
GPURT_FN void pathArrive(GPURT_INOUT(PathState) st, SurfaceHit s, float t, int b) {
    pathCross(st, s, t);
    if (materialHiddenFrom(s.m, st.prevPdf)) return;  // not there for this ray (pathScatter passes it)
    if (st.open) recordFeatures(materialAlbedo(s.m), s.ns);
    float mis = s.m.emitterLight ? emissionWeight(st.prevPdf, t, s.n, st.d, emitterArea) : 1.0f;
    pathAdd(st, materialEmitted(s.m, s.ns, st.d) * mis, b);
}

// Dispersion (KHR_materials_dispersion): light of each colour bends by its own index, so a path
// that scatters at a dispersing solid follows one colour channel from there on: the channel the
// sample's number of GPURT_DIM_WAVELENGTH picks, uniformly and once for the whole path (every
// later dispersing surface sees the same), its throughput that channel alone, times 3 (the
// channel's probability divided out). Returns record m at that channel's index (m itself where it
// does not disperse).
GPURT_FN MaterialRecord pathDisperse(GPURT_INOUT(PathState) st, MaterialRecord m) {
    if (!materialDisperses(m)) return m;
    int c = min(int(pixelSampleChoice(GPURT_DIM_WAVELENGTH).x * 3.0f), 2);
    if (!st.dispersed) {
        st.weight = st.weight * channelMask(c) * 3.0f;
        st.dispersed = true;
    }
    return materialAtChannel(m, c);
}

// The path's next ray from its hit s at depth b: a direction the material samples from the
// sample's numbers of this depth, the throughput times f cos / pdf, Russian roulette (or the same
// ray on past a surface hidden from it, common/material.h materialHiddenFrom). False when the path
// ends here (absorbed, below the surface, roulette).
GPURT_FN bool pathScatter(GPURT_INOUT(PathState) st, SurfaceHit s, int b) {
    if (materialHiddenFrom(s.m, st.prevPdf)) {  // on through it, as it came (a depth spent)
        st.o = offsetOrigin(s.p, -s.n, rayOffset);
        return true;
    }
    uint dim = GPURT_DIM_SCATTER + 2u * uint(b);
    vec2 u = pixelSample2D(dim);
    vec2 choice = pixelSampleChoice(dim + 1u);
    vec3 dir;
    vec3 factor;
    float pdf;
    float side;
    MaterialRecord m = pathDisperse(st, s.m);
    if (!materialSample(m, st.d, s.n, s.ns, s.front, u, choice.x, dir, factor, pdf, side)) return false;
    st.weight = st.weight * factor;
    st.open = featuresOpenAfter(st.open, pdf);
    if (!russianRoulette(b, st.weight, choice.y)) return false;
    st.prevPdf = pdf;
    st.o = offsetOrigin(s.p, side * s.n, rayOffset);
    st.d = dir;
    return true;
}

#ifdef GPURT_TRACE_HOOKS  // the includer traces rays itself (the cpu backend, the megakernels)

// Next-event estimation at surface s hit along d at depth b: each visible punctual light through the
// BSDF, the depth's environment direction and emitter point, each weighed against the BSDF's
// sampling of it (the wavefront chain spreads this over its shadowgen, light and bounce passes).
GPURT_FN vec3 pathDirectLight(SurfaceHit s, vec3 d, int b) {
    vec3 local = vec3(0.0f);
    for (int k = 0; k < punctualLightCount; ++k) {
        PunctualLight light = punctualLight(k);
        vec3 position;
        float intensity;
        if (lightVisible(light, s.p, s.n, position, intensity))
            local = local + pathLightContribution(s.m, s.p, s.ns, d, position, light.color, intensity);
    }
    vec3 l;
    float pdf;
    if (environmentVisible(b, s.p, s.n, l, pdf))
        local = local + pathEnvironmentContribution(s.m, s.ns, d, l, environmentRadiance(l), pdf);
    vec3 q;
    vec3 e1;
    vec3 e2;
    vec3 emission;
    if (emitterVisible(b, s.p, s.n, q, e1, e2, emission))
        local = local + pathEmitterContribution(s.m, s.p, s.ns, d, q, e1, e2, emission, emitterArea);
    return local;
}

// Depth b of the path: what its ray (traced by the caller: hit h, (t, u, v, triangle | -1))
// finds, the light gathered there, and its next ray. False when the path ends here (it missed,
// reached maxDepth, was absorbed or lost the roulette).
GPURT_FN bool pathBounce(GPURT_INOUT(PathState) st, vec4 h, int b) {
    if (h.w < 0.0f) {
        pathMiss(st, b);
        return false;
    }
    SurfaceHit s = surfaceAt(h, st.o, st.d);
    if (b == 0) recordPrimary(h, s.n);
    pathArrive(st, s, h.x, b);
    if (b == maxDepth) return false;
    if (materialLit(s.m)) pathAdd(st, pathDirectLight(s, st.d, b), b);
    return pathScatter(st, s, b);
}

// Follows path st from depth `first` (st holds that depth's ray) through depth `last` at most.
// Returns the depth of its last ray; alive: the path goes on after depth `last`, st holding its
// next ray (the megakernel's passes each take `last - first + 1` depths).
GPURT_FN int pathTrace(GPURT_INOUT(PathState) st, int first, int last, GPURT_OUT(bool) alive) {
    alive = false;
    int b = first;
    for (;; ++b) {
        if (!pathBounce(st, integratorTrace(st.o, st.d, b), b)) break;
        if (b == last) {
            alive = true;
            break;
        }
    }
    return b;
}

#endif  // GPURT_TRACE_HOOKS

#endif
