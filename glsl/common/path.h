// The path integrator's light transport (--integrator path), shared word for word by the kernels
// (after common/material.h and common/sampling.h) and the CPU backend, so that both backends take
// the same decisions from the same random numbers. Same rules as raymath.h.
//
// A path gathers light at each hit by next-event estimation (each point light, one emitter point)
// and continues in a direction the material's BSDF samples (common/material.h materialSample).
// Light samples and BSDF directions that can both reach an emitter are weighed against each other
// by their pdfs (multiple importance sampling, Veach 1997, power heuristic); the emission a delta
// direction (mirror, glass) finds counts in full. Russian roulette ends long paths.
//
// Units as common/shading.h: a point light of intensity I is pi I watts per steradian, so a white
// diffuse surface facing it at distance r has radiance I / r^2 under both integrators.
#ifndef GPURT_PATH_H
#define GPURT_PATH_H

#ifndef GPURT_MATERIAL_H
#error "include common/material.h before common/path.h"
#endif

// Russian roulette from this hit depth on (0 = the camera ray's hit): the path survives with
// probability min(0.95, largest channel of its throughput), and its throughput is divided by it.
#define GPURT_RR_DEPTH 3
// The sample dimensions of hit depth b (sampling.h): the emitter point is GPURT_DIM_EMITTER + b
// as for Whitted; the new direction GPURT_DIM_SCATTER + 2 b, and (lobe, roulette) the next one.
#define GPURT_DIM_SCATTER 1024u
// The colour channel a path follows after a dispersing solid (integrators/path.h pathDisperse).
#define GPURT_DIM_WAVELENGTH 8189u

// The solid-angle pdf of reaching an emitter point at distance dist whose surface makes the
// cosine cosQ with the ray, when the emitters are sampled uniformly by area (total area A).
GPURT_FN float emitterPdf(float dist, float cosQ, float area) {
    float pdf = dist * dist / (cosQ * area);
    return cosQ > 0.0f ? min(pdf, 1e30f) : 1e30f;
}

// Veach's power heuristic (beta = 2) for a sample of pdf a against the other strategy's b.
GPURT_FN float powerHeuristic(float a, float b) {
    if (!(a > 0.0f)) return 0.0f;
    float r = b / a;
    return 1.0f / (1.0f + r * r);
}

// Radiance arriving through material m's BSDF from an unshadowed point light at lightPos (colour
// times intensity, see the units above) at p, seen along d, shading normal n; for one index of
// refraction (pathLightContribution takes a dispersing record's channels apart).
GPURT_FN vec3 lightThroughBsdf(MaterialRecord m, vec3 p, vec3 n, vec3 d, vec3 lightPos, vec3 lightColor,
                               float intensity) {
    vec3 toLight = lightPos - p;
    float dist2 = dot(toLight, toLight);
    vec3 l = contractNormalize(toLight);
    float cosP = max(0.0f, dot(n, l));
    // Bounded as lightContribution (common/materials/classic.h).
    return min(materialEval(m, n, d, l) * cosP * lightColor * intensity / dist2, vec3(1e30f));
}

// The multiple-importance weight of a light sample: the emitter point q (edges e1, e2 of its
// triangle, all emitters of total area `area`) seen from p against the pdf with which material
// m's BSDF (shading normal n, view ray d) samples the same direction.
GPURT_FN float emitterSampleWeight(MaterialRecord m, vec3 p, vec3 q, vec3 e1, vec3 e2, float area, vec3 n, vec3 d) {
    vec3 toQ = q - p;
    float dist = sqrt(dot(toQ, toQ));
    vec3 l = contractNormalize(toQ);
    float cosQ = abs(dot(facingNormal(e1, e2, l), l));
    return powerHeuristic(emitterPdf(dist, cosQ, area), materialPdf(m, n, d, l));
}

// Next-event estimation under dispersion (KHR_materials_dispersion): the BSDF of a dispersing
// solid is, channel by channel, the BSDF at that channel's index (common/material.h
// materialAtChannel), and so is the pdf with which a path of that channel samples a direction
// (pathDisperse), so each channel's light and multiple-importance weight are taken at its own
// index: exact whatever channel the path has or will have taken. A record that does not disperse
// is taken once.

// Radiance arriving through material m's BSDF from an unshadowed point light at lightPos (colour
// times intensity, see the units above) at p, seen along d, shading normal n.
GPURT_FN vec3 pathLightContribution(MaterialRecord m, vec3 p, vec3 n, vec3 d, vec3 lightPos, vec3 lightColor,
                                    float intensity) {
    if (!materialDisperses(m)) return lightThroughBsdf(m, p, n, d, lightPos, lightColor, intensity);
    vec3 sum = vec3(0.0f);
    for (int c = 0; c < 3; ++c)
        sum = sum + channelMask(c) * lightThroughBsdf(materialAtChannel(m, c), p, n, d, lightPos, lightColor, intensity);
    return sum;
}

// The light of the emitter point q (edges e1, e2 of its triangle, radiance `emission`, all
// emitters of total area `area`), unshadowed, through material m's BSDF at p (shading normal n,
// view ray d), weighed against the BSDF's sampling of its direction.
GPURT_FN vec3 pathEmitterContribution(MaterialRecord m, vec3 p, vec3 n, vec3 d, vec3 q, vec3 e1, vec3 e2,
                                      vec3 emission, float area) {
    float intensity = emitterIntensity(p, q, e1, e2, area);
    if (!materialDisperses(m))
        return lightThroughBsdf(m, p, n, d, q, emission, intensity) * emitterSampleWeight(m, p, q, e1, e2, area, n, d);
    vec3 sum = vec3(0.0f);
    for (int c = 0; c < 3; ++c) {
        MaterialRecord mc = materialAtChannel(m, c);
        sum = sum + channelMask(c) * lightThroughBsdf(mc, p, n, d, q, emission, intensity) *
                        emitterSampleWeight(mc, p, q, e1, e2, area, n, d);
    }
    return sum;
}

// The weight of the emission that a ray finds at distance t, on a triangle with facing normal ng,
// after leaving the last hit in a direction of pdf prevPdf: 1 after a delta lobe or from the
// camera (prevPdf 0), else the BSDF's share against next-event estimation of the same point.
GPURT_FN float emissionWeight(float prevPdf, float t, vec3 ng, vec3 d, float area) {
    if (!(prevPdf > 0.0f)) return 1.0f;
    return powerHeuristic(prevPdf, emitterPdf(t, abs(dot(ng, d)), area));
}

// The weight of the environment that a ray finds on leaving the scene after the last hit chose its
// direction with pdf prevPdf: 1 after a delta lobe or from the camera (prevPdf 0), else the BSDF's
// share against next-event estimation of the environment, which draws that direction with
// lightPdf (0: the environment is not sampled).
GPURT_FN float environmentHitWeight(float prevPdf, float lightPdf) {
    if (!(prevPdf > 0.0f)) return 1.0f;
    return powerHeuristic(prevPdf, lightPdf);
}

// Radiance arriving through material m's BSDF (shading normal n, view ray d) from the
// environment's radiance L in the unshadowed direction l that next-event estimation drew with
// solid-angle pdf lightPdf, weighed against the BSDF's sampling of l; for one index of refraction.
GPURT_FN vec3 environmentThroughBsdf(MaterialRecord m, vec3 n, vec3 d, vec3 l, vec3 radiance, float lightPdf) {
    float cosP = max(0.0f, dot(n, l));
    float w = powerHeuristic(lightPdf, materialPdf(m, n, d, l));
    return min(materialEval(m, n, d, l) * GPURT_INV_PI * cosP * radiance * (w / lightPdf), vec3(1e30f));
}

// environmentThroughBsdf, a dispersing record's channels each at its own index.
GPURT_FN vec3 pathEnvironmentContribution(MaterialRecord m, vec3 n, vec3 d, vec3 l, vec3 radiance, float lightPdf) {
    if (!(lightPdf > 0.0f)) return vec3(0.0f);
    if (!materialDisperses(m)) return environmentThroughBsdf(m, n, d, l, radiance, lightPdf);
    vec3 sum = vec3(0.0f);
    for (int c = 0; c < 3; ++c)
        sum = sum + channelMask(c) * environmentThroughBsdf(materialAtChannel(m, c), n, d, l, radiance, lightPdf);
    return sum;
}

// --clamp-direct and --clamp-indirect (Cycles' meaning; 0: off): the contribution c a path adds
// to its pixel at hit depth b (0: what the camera ray finds: the emission or sky it sees and the
// light gathered at its hit) is direct, later ones indirect; scaled down so that its largest
// channel is at most the limit (fireflies of rare, heavy paths, for a little bias).
GPURT_FN vec3 clampContribution(vec3 c, int b, float clampDirect, float clampIndirect) {
    float limit = b == 0 ? clampDirect : clampIndirect;
    float m = maxChannel(c);
    return limit > 0.0f && m > limit ? c * (limit / m) : c;
}

// The denoiser's features of a sample (--aov albedo and shading_normal; Open Image Denoise's
// definitions): the albedo (materialAlbedo) and shading normal of the first hit whose sampled lobe
// is not a delta, that is, through mirrors and smooth glass. Each hit of a path whose features are
// still open records its own; a delta lobe (pdf 0) leaves them open for the next hit to
// overwrite. A ray that leaves the scene records the background's: albedo
// GPURT_BACKGROUND_ALBEDO (its light passes the denoiser's demodulation unchanged), normal 0.
#define GPURT_BACKGROUND_ALBEDO 1.0f
GPURT_FN bool featuresOpenAfter(bool open, float pdf) { return open && !(pdf > 0.0f); }

// Russian roulette at hit depth b for throughput w and the random number u: the probability the
// path survives (1: no roulette yet), or 0 when it ends here.
GPURT_FN float survival(int b, vec3 w, float u) {
    if (b < GPURT_RR_DEPTH) return 1.0f;
    float q = min(0.95f, maxChannel(w));
    return u < q ? q : 0.0f;
}

// The Russian roulette step of a path at hit depth b whose throughput w already carries the
// scattering factor, for the random number u: false when the path ends here, else w divided by
// its survival probability.
GPURT_FN bool russianRoulette(int b, GPURT_INOUT(vec3) w, float u) {
    float q = survival(b, w, u);
    if (q == 0.0f) return false;
    w = w / q;
    return true;
}

#endif
