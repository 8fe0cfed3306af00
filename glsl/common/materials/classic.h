// The classic material model (GPURT_MODEL_CLASSIC, every material of OBJ/MTL, JSON and glTF
// today), shared word for word by the kernels and the CPU backend (included by common/material.h;
// same rules as raymath.h). A material (kd, ks, ns, reflectivity, ior, Tf):
//   Whitted (common/shading.h's units): local = 0.1 kd + per unshadowed light kd max(0, n.l) +
//     ks max(0, reflect(-l, n).(-d))^ns, times colour x intensity / dist^2; a mirror spawns the
//     reflected ray, glass the reflected and refracted rays (hitChildren).
//   path: glass (ior > 0) is a smooth dielectric only: Fresnel reflection or refraction (filtered
//     by Tf), chosen with probability F (pbrt-v3 FresnelSpecular); kd and ks are unused.
//     Otherwise the sum of three lobes:
//       diffuse  kd / pi (Lambert);
//       glossy   ks (ns + 2) / (2 pi) cos^ns(alpha), the normalised modified Phong lobe (Lafortune
//                & Willems 1994), alpha the angle between the light direction and the mirror
//                direction of the view; only where the material is not a mirror, because MTL's
//                illum 3 makes the same Ks the mirror's colour;
//       mirror   a perfect reflection weighted by the reflectivity.
//     A scattering direction takes one lobe, chosen with probabilities proportional to the lobes'
//     largest channels (pathLobes); diffuse and glossy directions are weighted against their
//     mixture pdf (bsdfPdf). The mirror and glass are delta lobes (pdf 0).
// The functions on loose fields are the model's math (tests call them); the classic* functions
// at the end are its side of the material interface (common/material.h).
#ifndef GPURT_MATERIALS_CLASSIC_H
#define GPURT_MATERIALS_CLASSIC_H

#define GPURT_AMBIENT 0.1f  // ambient term: this fraction of the diffuse colour

// Diffuse + specular light from one unshadowed point light.
GPURT_FN vec3 lightContribution(vec3 p, vec3 n, vec3 d, vec3 kd, vec3 ks, float ns, vec3 lightPos,
                                vec3 lightColor, float intensity) {
    vec3 toLight = lightPos - p;
    float dist2 = dot(toLight, toLight);
    vec3 l = contractNormalize(toLight);
    float diffuse = max(0.0f, dot(n, l));
    float s = max(0.0f, dot(mirrorDirection(-l, n), -d));
    // GLSL leaves pow(0, y) undefined; a zero base contributes nothing.
    float specular = s > 0.0f ? pow(s, ns) : 0.0f;
    // Bounded: a light of colour 1e30 and intensity 1e30 (or one at 1e-20 from the surface)
    // would give infinity, and a later bounce's weight of 0 times infinity a NaN pixel. 1e30 is
    // far beyond white and leaves room to sum any number of lights.
    return min((kd * diffuse + ks * specular) * lightColor * intensity / dist2, vec3(1e30f));
}

// The ambient part of the local colour.
GPURT_FN vec3 ambientColor(vec3 kd) { return GPURT_AMBIENT * kd; }

// The rays a hit spawns, from the pixel's ray of direction d and weight w at a surface with
// facing geometric normal ng and shading normal ns. A dielectric (ior > 0; entering when
// `entering`): the refracted ray of weight w (1 - F) tf and the reflected ray of weight w F,
// or only the reflected ray, of weight w, where there is no refraction (total internal
// reflection, or a refracted ray that the shading normal would send out on the facing side). A
// mirror: the reflected ray of weight w reflectivity. A is the ray the pixel continues with (the
// refracted one where there is one; sideA -1: it leaves on the far side of the surface), B the
// second, pushed on the pixel's stack. Returns how many (0, 1 or 2).
GPURT_FN int hitChildren(vec3 d, vec3 ng, vec3 ns, bool entering, vec3 reflectivity, float ior,
                         vec3 tf, vec3 w, GPURT_OUT(vec3) dirA, GPURT_OUT(vec3) weightA,
                         GPURT_OUT(float) sideA, GPURT_OUT(vec3) dirB, GPURT_OUT(vec3) weightB) {
    vec3 r = shadingReflection(d, ns, ng);
    dirA = r;
    weightA = w * reflectivity;
    sideA = 1.0f;
    dirB = r;
    weightB = vec3(0.0f);
    if (ior > 0.0f) {
        float eta = entering ? ior : 1.0f / ior;
        float cosI = clamp(-dot(d, ns), 0.0f, 1.0f);
        float f = fresnelDielectric(cosI, eta);
        weightA = w;  // no refraction: all of it is reflected
        if (f < 1.0f) {
            vec3 t = refractedDirection(d, ns, eta, cosI);
            if (dot(t, ng) < 0.0f) {
                dirA = t;
                weightA = w * ((1.0f - f) * tf);
                sideA = -1.0f;
                weightB = w * f;
            }
        }
    }
    return rayTreeChildren(dirA, weightA, sideA, dirB, weightB);
}

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


// The material interface (common/material.h) for the classic model.
GPURT_FN vec3 classicAmbient(MaterialRecord m) { return ambientColor(m.kd); }
// Under an environment of irradiance E at the normal: Lambert's kd E / pi instead.
GPURT_FN vec3 classicEnvironmentAmbient(MaterialRecord m, vec3 irradiance) { return m.kd * irradiance * GPURT_INV_PI; }

GPURT_FN vec3 classicLight(MaterialRecord m, vec3 p, vec3 n, vec3 d, vec3 lightPos, vec3 lightColor,
                           float intensity) {
    return lightContribution(p, n, d, m.kd, m.ks, m.ns, lightPos, lightColor, intensity);
}

GPURT_FN bool classicSpawns(MaterialRecord m) { return m.ior > 0.0f || m.reflectivity != vec3(0.0f); }

GPURT_FN bool classicSplits(MaterialRecord m) { return m.ior > 0.0f; }

GPURT_FN int classicChildren(MaterialRecord m, vec3 d, vec3 ng, vec3 ns, bool entering, vec3 w,
                             GPURT_OUT(vec3) dirA, GPURT_OUT(vec3) weightA, GPURT_OUT(float) sideA,
                             GPURT_OUT(vec3) dirB, GPURT_OUT(vec3) weightB) {
    return hitChildren(d, ng, ns, entering, m.reflectivity, m.ior, m.tf, w, dirA, weightA, sideA, dirB, weightB);
}

GPURT_FN bool classicLit(MaterialRecord m) {
    vec3 diffuse, glossy;
    return pathLobes(m.kd, m.ks, m.reflectivity, m.ior, diffuse, glossy);
}

GPURT_FN vec3 classicEval(MaterialRecord m, vec3 n, vec3 d, vec3 wi) {
    vec3 diffuse, glossy;
    pathLobes(m.kd, m.ks, m.reflectivity, m.ior, diffuse, glossy);
    return bsdfTimesPi(diffuse, glossy, m.ns, n, d, wi);
}

GPURT_FN float classicPdf(MaterialRecord m, vec3 n, vec3 d, vec3 wi) {
    vec3 diffuse, glossy;
    pathLobes(m.kd, m.ks, m.reflectivity, m.ior, diffuse, glossy);
    return bsdfPdf(lobeProbabilities(diffuse, glossy, m.reflectivity, m.ior), m.ns, n, d, wi);
}

GPURT_FN bool classicSample(MaterialRecord m, vec3 d, vec3 ng, vec3 ns, bool entering, vec2 u, float lobe,
                            GPURT_OUT(vec3) dir, GPURT_OUT(vec3) factor, GPURT_OUT(float) pdf,
                            GPURT_OUT(float) side) {
    vec3 diffuse, glossy;
    pathLobes(m.kd, m.ks, m.reflectivity, m.ior, diffuse, glossy);
    return scatterPath(d, ng, ns, entering, diffuse, glossy, m.ns, m.reflectivity, m.ior, m.tf, u, lobe, dir, factor,
                       pdf, side);
}

#endif
