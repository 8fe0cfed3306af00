// The path integrator's surface model and sampling (--integrator path), shared word for word by
// the kernels (after common/shading.h and common/sampling.h) and the CPU backend, so that both
// backends take the same decisions from the same random numbers. Same rules as raymath.h.
//
// The BSDF of a material (kd, ks, ns, reflectivity, ior, Tf):
//   glass (ior > 0): a smooth dielectric only: Fresnel reflection or refraction (filtered by Tf),
//     chosen with probability F (pbrt-v3 FresnelSpecular); kd and ks are unused.
//   otherwise the sum of three lobes:
//     diffuse  kd / pi (Lambert);
//     glossy   ks (ns + 2) / (2 pi) cos^ns(alpha), the normalised modified Phong lobe (Lafortune
//              & Willems 1994), alpha the angle between the light direction and the mirror
//              direction of the view; only where the material is not a mirror, because MTL's
//              illum 3 makes the same Ks the mirror's colour;
//     mirror   a perfect reflection weighted by the reflectivity.
//   A scattering direction takes one lobe, chosen with probabilities proportional to the lobes'
//   largest channels (pathLobes); diffuse and glossy directions are weighted against their mixture
//   pdf (bsdfPdf), so that next-event estimation can weigh light samples against them (multiple
//   importance sampling, Veach 1997, power heuristic). The mirror and glass are delta lobes: the
//   emission a delta direction finds counts in full.
//
// Units as common/shading.h: a point light of intensity I is pi I watts per steradian, so a white
// diffuse surface facing it at distance r has radiance I / r^2 under both integrators.
#ifndef GPURT_PATH_H
#define GPURT_PATH_H

#ifndef GPURT_SHADING_H
#error "include common/shading.h before common/path.h"
#endif

#define GPURT_PI 3.14159265f
#define GPURT_INV_PI 0.31830988f
// Russian roulette from this hit depth on (0 = the camera ray's hit): the path survives with
// probability min(0.95, largest channel of its throughput), and its throughput is divided by it.
#define GPURT_RR_DEPTH 3
// The sample dimensions of hit depth b (sampling.h): the emitter point is GPURT_DIM_EMITTER + b
// as for Whitted; the new direction GPURT_DIM_SCATTER + 2 b, and (lobe, roulette) the next one.
#define GPURT_DIM_SCATTER 1024u

GPURT_FN float maxChannel(vec3 c) { return max(c.x, max(c.y, c.z)); }

// The weights of the diffuse and glossy lobes of a material for the path integrator (0 for glass,
// and glossy 0 for a mirror); false when neither is there: next-event estimation has nothing to
// light (a pure mirror, glass).
GPURT_FN bool pathLobes(vec3 kd, vec3 ks, vec3 reflectivity, float ior, GPURT_OUT(vec3) diffuse,
                        GPURT_OUT(vec3) glossy) {
    diffuse = ior > 0.0f ? vec3(0.0f) : kd;
    glossy = (ior > 0.0f || reflectivity != vec3(0.0f)) ? vec3(0.0f) : ks;
    return maxChannel(diffuse) > 0.0f || maxChannel(glossy) > 0.0f;
}

// The probabilities of choosing the diffuse, glossy and delta lobe (mirror, or glass); all 0 for a
// black material (the path ends there).
GPURT_FN vec3 lobeProbabilities(vec3 diffuse, vec3 glossy, vec3 reflectivity, float ior) {
    if (ior > 0.0f) return vec3(0.0f, 0.0f, 1.0f);
    float a = max(maxChannel(diffuse), 0.0f);
    float b = max(maxChannel(glossy), 0.0f);
    float c = max(maxChannel(reflectivity), 0.0f);
    float s = a + b + c;
    if (!(s > 0.0f)) return vec3(0.0f);
    return vec3(a / s, b / s, c / s);
}

// cos^ns of the angle between wi and the mirror direction of the ray d about n (0 behind it).
GPURT_FN float phongCosine(vec3 n, vec3 d, vec3 wi, float ns) {
    float c = dot(mirrorDirection(d, n), wi);
    return c > 0.0f ? pow(c, ns) : 0.0f;  // GLSL leaves pow(0, y) undefined
}

// pi times the diffuse and glossy BSDF for light arriving from wi at a surface seen along the ray
// d with shading normal n.
GPURT_FN vec3 bsdfTimesPi(vec3 diffuse, vec3 glossy, float ns, vec3 n, vec3 d, vec3 wi) {
    if (maxChannel(glossy) > 0.0f) return diffuse + glossy * ((ns + 2.0f) * 0.5f * phongCosine(n, d, wi, ns));
    return diffuse;
}

// The solid-angle pdf with which the diffuse and glossy lobes (chosen with probabilities
// probs.x, probs.y) sample wi.
GPURT_FN float bsdfPdf(vec3 probs, float ns, vec3 n, vec3 d, vec3 wi) {
    float pdf = probs.x * max(0.0f, dot(n, wi)) * GPURT_INV_PI;
    if (probs.y > 0.0f) pdf += probs.y * (ns + 1.0f) * 0.5f * GPURT_INV_PI * phongCosine(n, d, wi, ns);
    return pdf;
}

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

// The unit vector at angle acos(cosTheta) from the unit axis a, at azimuth 2 pi u about it, in
// the branchless orthonormal basis of Duff et al. 2017 ("Building an Orthonormal Basis,
// Revisited").
GPURT_FN vec3 directionAbout(vec3 a, float cosTheta, float u) {
    float s = a.z >= 0.0f ? 1.0f : -1.0f;
    float k = -1.0f / (s + a.z);
    float m = a.x * a.y * k;
    vec3 t = vec3(1.0f + s * a.x * a.x * k, s * m, -s * a.x);
    vec3 b = vec3(m, s + a.y * a.y * k, -a.y);
    float sinTheta = sqrt(max(0.0f, 1.0f - cosTheta * cosTheta));
    float phi = 2.0f * GPURT_PI * u;
    return contractNormalize(t * (sinTheta * cos(phi)) + b * (sinTheta * sin(phi)) + a * cosTheta);
}

// Radiance arriving over the diffuse and glossy lobes from an unshadowed point light at lightPos
// (colour times intensity, see the units above) at p, seen along d, shading normal n.
GPURT_FN vec3 pathLightContribution(vec3 p, vec3 n, vec3 d, vec3 diffuse, vec3 glossy, float ns, vec3 lightPos,
                                    vec3 lightColor, float intensity) {
    vec3 toLight = lightPos - p;
    float dist2 = dot(toLight, toLight);
    vec3 l = contractNormalize(toLight);
    float cosP = max(0.0f, dot(n, l));
    // Bounded as lightContribution (common/shading.h).
    return min(bsdfTimesPi(diffuse, glossy, ns, n, d, l) * cosP * lightColor * intensity / dist2, vec3(1e30f));
}

// The multiple-importance weight of a light sample: the emitter point q (edges e1, e2 of its
// triangle, all emitters of total area `area`) seen from p against the BSDF's pdf (lobe
// probabilities probs, shading normal n, view ray d) of the same direction.
GPURT_FN float emitterSampleWeight(vec3 p, vec3 q, vec3 e1, vec3 e2, float area, vec3 probs, float shininess,
                                   vec3 n, vec3 d) {
    vec3 toQ = q - p;
    float dist = sqrt(dot(toQ, toQ));
    vec3 l = contractNormalize(toQ);
    float cosQ = abs(dot(facingNormal(e1, e2, l), l));
    return powerHeuristic(emitterPdf(dist, cosQ, area), bsdfPdf(probs, shininess, n, d, l));
}

// The weight of the emission that a ray finds at distance t, on a triangle with facing normal ng,
// after leaving the last hit in a direction of pdf prevPdf: 1 after a delta lobe or from the
// camera (prevPdf 0), else the BSDF's share against next-event estimation of the same point.
GPURT_FN float emissionWeight(float prevPdf, float t, vec3 ng, vec3 d, float area) {
    if (!(prevPdf > 0.0f)) return 1.0f;
    return powerHeuristic(prevPdf, emitterPdf(t, abs(dot(ng, d)), area));
}

// The path's next direction from a hit seen along d (facing geometric normal ng, shading normal
// ns, `entering` the front side) for the random numbers u (direction) and lobe (lobe choice), as
// the BSDF above samples it: `dir`, the factor f cos / pdf that the throughput takes, the pdf
// (0 for a delta lobe: mirror or glass) and the side it leaves on (-1: through the surface).
// False when the path ends: a black material, or a direction below the surface.
GPURT_FN bool scatterPath(vec3 d, vec3 ng, vec3 ns, bool entering, vec3 diffuse, vec3 glossy, float shininess,
                          vec3 reflectivity, float ior, vec3 tf, vec2 u, float lobe, GPURT_OUT(vec3) dir,
                          GPURT_OUT(vec3) factor, GPURT_OUT(float) pdf, GPURT_OUT(float) side) {
    dir = shadingReflection(d, ns, ng);
    factor = vec3(1.0f);
    pdf = 0.0f;
    side = 1.0f;
    if (ior > 0.0f) {  // Fresnel reflection with probability F, else refraction
        float eta = entering ? ior : 1.0f / ior;
        float cosI = clamp(-dot(d, ns), 0.0f, 1.0f);
        if (lobe < fresnelDielectric(cosI, eta)) return true;
        vec3 t = refractedDirection(d, ns, eta, cosI);
        if (dot(t, ng) >= 0.0f) return true;  // refraction the shading normal sends back: reflect (hitChildren)
        dir = t;
        factor = tf;
        side = -1.0f;
        return true;
    }
    vec3 probs = lobeProbabilities(diffuse, glossy, reflectivity, ior);
    if (lobe < probs.z) {
        factor = reflectivity / probs.z;
        return true;
    }
    if (!(probs.x + probs.y > 0.0f)) return false;
    if (lobe < probs.z + probs.x) dir = directionAbout(ns, sqrt(1.0f - u.x), u.y);  // cosine-weighted
    else dir = directionAbout(contractNormalize(mirrorDirection(d, ns)), pow(1.0f - u.x, 1.0f / (shininess + 1.0f)), u.y);
    float cosI = dot(ns, dir);
    if (!(dot(dir, ng) > 0.0f) || !(cosI > 0.0f)) return false;
    pdf = bsdfPdf(probs, shininess, ns, d, dir);
    if (!(pdf > 0.0f)) return false;
    factor = bsdfTimesPi(diffuse, glossy, shininess, ns, d, dir) * (cosI * GPURT_INV_PI / pdf);
    return true;
}

// Russian roulette at hit depth b for throughput w and the random number u: the probability the
// path survives (1: no roulette yet), or 0 when it ends here.
GPURT_FN float survival(int b, vec3 w, float u) {
    if (b < GPURT_RR_DEPTH) return 1.0f;
    float q = min(0.95f, maxChannel(w));
    return u < q ? q : 0.0f;
}

#endif
