// The glTF 2.0 metallic-roughness model (GPURT_MODEL_GLTF: glTF materials, MTL's PBR extension,
// JSON "metallic" / "roughness"), shared word for word by the kernels and the CPU backend
// (included by common/material.h; same rules as raymath.h). The BRDF is the glTF 2.0
// specification's Appendix B, mixed as it says (B.3.5), with c the base colour, m metallic,
// alpha = roughness^2, v towards the viewer, l towards the light, h = normalize(l + v):
//   f = (1 - m) [(1 - Fd) c / pi + Fd D V] + m Fm D V
//   Fd = 0.04 + 0.96 (1 - |v.h|)^5 (dielectric), Fm = c + (1 - c)(1 - |v.h|)^5 (conductor),
//   D the GGX / Trowbridge-Reitz distribution, V the Smith height-correlated visibility
//   G2 / (4 |n.l| |n.v|).
// A roughness below GPURT_GLTF_SMOOTH is a smooth coat: the specular lobe is a perfect mirror of
// weight (1 - m) Fd + m Fm at h = n, over the same diffuse term.
// Path: a direction takes the specular lobe with probability gltfSpecularProbability (its share
// of the albedo at n.v), sampled by GGX's distribution of visible normals (Heitz 2018, "Sampling
// the GGX Distribution of Visible Normals"), else the cosine-weighted diffuse lobe; both are
// weighed against their mixture pdf and against light sampling by MIS (common/path.h).
// Whitted: every light gets the same BRDF; a smooth coat spawns the mirror ray; the ambient term
// is the directional albedo at normal incidence (smooth: its diffuse part, the mirror ray brings
// the rest) times the occlusion map.
// KHR_materials_ior sets the dielectric's F0 = ((ior - 1) / (ior + 1))^2 (record ior 0: 1.5, F0
// 0.04). KHR_materials_transmission (factor t = record tf.x where ior > 0) turns the dielectric's
// diffuse part into a rough dielectric's transmission, as the extension mixes it:
//   (1 - m) [(1 - Fd) ((1 - t) c / pi + t c f_t) + Fd D V] + m Fm D V
// with f_t Walter et al.'s (2007) microfacet BTDF (GGX, the same alpha, height-correlated Smith)
// for a solid of index ior (the record's ior is relative across the boundary in the ray's
// direction: materialFacing); leaving the solid, Fd is Schlick's at the transmitted angle and 1
// past the critical angle. A thin wall (record thin: glTF's transmission without
// KHR_materials_volume, the extension's default) bends nothing: f_t is the reflection's D V at the
// light's mirror image through the surface, and a smooth wall passes the ray straight on. Path:
// the specular lobe's visible normal reflects or refracts, chosen by their weights at it; a
// refracted direction's pdf is reported as 0 (a delta for MIS: light sampling never goes through
// the surface). Whitted: the refracted ray is spawned as through a smooth surface (Whitted cannot
// blur), with the mirror ray where the surface is smooth.
// The extensions' layers follow below, each where it enters: KHR_materials_specular, _clearcoat,
// _sheen, _iridescence (thin_film.h) and _anisotropy (the base's lobe, reflection and
// transmission, stretched along a direction: anisotropic_ggx.h, gltfSpecularLobe).
#ifndef GPURT_MATERIALS_GLTF_H
#define GPURT_MATERIALS_GLTF_H

#define GPURT_GLTF_SMOOTH 0.01f     // roughness below this: a perfect mirror (alpha < 1e-4)
#define GPURT_GLTF_DIELECTRIC 0.04f  // F0 of the dielectric (ior 1.5)
#define GPURT_GLTF_IOR 1.5f          // the index without KHR_materials_ior
#define GPURT_GLTF_MIN_COS 1e-4f     // n.v where the view is at or below the shading normal

GPURT_FN bool gltfSmooth(float roughness) { return roughness < GPURT_GLTF_SMOOTH; }

// (1 - c)^5, Schlick's weight at cosine c.
GPURT_FN float schlickWeight(float c) {
    float k = clamp(1.0f - c, 0.0f, 1.0f);
    float k2 = k * k;
    return k2 * k2 * k;
}

// GGX's normal distribution D at n.h for alpha^2 = a2.
GPURT_FN float ggxDistribution(float a2, float nh) {
    float k = nh * nh * (a2 - 1.0f) + 1.0f;
    return a2 / (GPURT_PI * k * k);
}

// The Smith height-correlated visibility V = G2 / (4 n.l n.v) for alpha^2 = a2 (Appendix B.3.2).
GPURT_FN float smithVisibility(float a2, float nl, float nv) {
    float s = nl * sqrt(nv * nv * (1.0f - a2) + a2) + nv * sqrt(nl * nl * (1.0f - a2) + a2);
    return s > 0.0f ? 0.5f / s : 0.0f;
}

// GGX's microfacet lobe D V of alpha at cosines nh, nl, nv.
GPURT_FN float ggxLobe(float alpha, float nh, float nl, float nv) {
    float a2 = alpha * alpha;
    return ggxDistribution(a2, nh) * smithVisibility(a2, nl, nv);
}

// Smith's masking G1 of the view at n.v for alpha^2 = a2.
GPURT_FN float smithMasking(float a2, float nv) { return 2.0f * nv / (nv + sqrt(a2 + (1.0f - a2) * nv * nv)); }

// KHR_materials_anisotropy: the base's specular lobe (reflection and transmission) stretched along
// the record's direction, alpha_t = mix(alpha, 1, strength^2) along it and alpha_b = alpha across
// (alpha = roughness^2, both at least GPURT_GLTF_SMOOTH^2: a rough surface, never a mirror).
#if defined(__cplusplus) || defined(SCENE_ANISOTROPY)  // SceneTextures::bind
#include "anisotropic_ggx.h"
#endif

// Whether the record's base lobe is anisotropic (compiled only for scenes with anisotropy).
GPURT_FN bool gltfAnisotropic(MaterialRecord m) {
#if defined(__cplusplus) || defined(SCENE_ANISOTROPY)
    return m.anisotropy > 0.0f;
#else
    return false;
#endif
}

// Whether the base's specular lobe is a perfect mirror: a roughness below GPURT_GLTF_SMOOTH,
// without anisotropy.
GPURT_FN bool gltfBaseSmooth(MaterialRecord m) { return gltfSmooth(m.roughness) && !gltfAnisotropic(m); }

// KHR_materials_anisotropy's strength and direction in tangent space at a hit, from its map's
// linear RGB `texel` ((1, 0.5, 1) without a map): RG mapped from [0, 1] to [-1, 1], normalized
// and turned by the rotation (cos, sin) counter-clockwise; B times the strength. Returns (x, y,
// strength); a texel without a direction has no anisotropy.
GPURT_FN vec3 gltfAnisotropyAt(float strength, vec2 rotation, vec3 texel) {
    float x = texel.x * 2.0f - 1.0f;
    float y = texel.y * 2.0f - 1.0f;
    float len2 = x * x + y * y;
    if (!(len2 > 0.0f)) return vec3(1.0f, 0.0f, 0.0f);
    float k = 1.0f / sqrt(len2);
    x = x * k;
    y = y * k;
    return vec3(rotation.x * x - rotation.y * y, rotation.y * x + rotation.x * y, strength * texel.z);
}

#if defined(__cplusplus) || defined(SCENE_ANISOTROPY)
// The anisotropy's frame about the shading normal n: t the record's direction made orthogonal to n
// (any tangent where they are parallel), b = n x t; returns (alpha_t, alpha_b).
GPURT_FN vec2 gltfAnisotropicFrame(MaterialRecord m, vec3 n, GPURT_OUT(vec3) t, GPURT_OUT(vec3) b) {
    vec3 d = m.anisotropyDirection;
    t = d - n * dot(n, d);
    float tt = dot(t, t);
    if (tt > 1e-12f) {
        t = t / sqrt(tt);
        b = cross(n, t);
    } else {
        orthonormalBasis(n, t, b);
    }
    float alpha = max(m.roughness * m.roughness, GPURT_GLTF_SMOOTH * GPURT_GLTF_SMOOTH);
    return vec2(mix(alpha, 1.0f, m.anisotropy * m.anisotropy), alpha);
}
#endif

// The base's specular microfacet lobe D V at half vector h, for the view v and the light l at
// cosines nv, nl > 0 (for the BTDF |n.l|) about the shading normal n: GGX of alpha = roughness^2,
// stretched along the anisotropy's direction (KHR_materials_anisotropy).
GPURT_FN float gltfSpecularLobe(MaterialRecord m, vec3 n, vec3 v, vec3 l, vec3 h, float nl, float nv) {
#if defined(__cplusplus) || defined(SCENE_ANISOTROPY)
    if (gltfAnisotropic(m)) {
        vec3 t, b;
        vec2 a = gltfAnisotropicFrame(m, n, t, b);
        return ggxAnisotropicDistribution(a.x, a.y, dot(t, h), dot(b, h), max(dot(n, h), 0.0f)) *
               ggxAnisotropicVisibility(a.x, a.y, dot(t, v), dot(b, v), nv, dot(t, l), dot(b, l), nl);
    }
#endif
    return ggxLobe(m.roughness * m.roughness, max(dot(n, h), 0.0f), nl, nv);
}

// The dielectric's F0 for the record's (relative) ior: Appendix B's 0.04 for the default index,
// else ((ior - 1) / (ior + 1))^2 (symmetric in ior and 1 / ior).
GPURT_FN float gltfDielectricF0(float ior) {
    float f0 = GPURT_GLTF_DIELECTRIC;
    if (ior > 0.0f && ior != GPURT_GLTF_IOR) {
        float r = (ior - 1.0f) / (ior + 1.0f);
        f0 = r * r;
    }
    return f0;
}

// The cosine Schlick's weight is taken at for microfacet cosine c = |v.h|: c itself, or leaving a
// transmissive solid (transmission factor t > 0, relative index below 1) the transmitted angle's;
// -1 past the critical angle (all is reflected).
GPURT_FN float gltfFresnelCosine(float ior, float t, float c) {
    if (t > 0.0f && ior > 0.0f && ior < 1.0f) {
        float sin2T = (1.0f - c * c) / (ior * ior);
        if (sin2T >= 1.0f) return -1.0f;
        c = sqrt(1.0f - sin2T);
    }
    return c;
}

// The dielectric's Schlick reflectance Fd at microfacet cosine c = |v.h| for the record's
// (relative) ior and transmission factor t: Appendix B's 0.04 + 0.96 (1 - c)^5 for the default
// index, F0 from the index otherwise, 1 past the critical angle.
GPURT_FN float gltfDielectricFresnel(float ior, float t, float c) {
    float f0 = gltfDielectricF0(ior);
    c = gltfFresnelCosine(ior, t, c);
    if (c < 0.0f) return 1.0f;
    return f0 + (1.0f - f0) * schlickWeight(c);
}

// The transmission factor t of a record (0 without KHR_materials_transmission).
GPURT_FN float gltfTransmission(MaterialRecord m) { return m.ior > 0.0f ? m.tf.x : 0.0f; }

#if defined(__cplusplus) || defined(SCENE_IRIDESCENCE)  // SceneTextures::bind
#include "thin_film.h"

// The dielectric's specular layer under an iridescent film at cosine c (gltfDielectricLayer):
// Schlick's from F0 = min(F0(ior) x specular colour, 1) mixed with the film's reflectance over that
// F0 by the iridescence factor, times the specular weight.
GPURT_FN vec3 gltfIridescentLayer(MaterialRecord m, float t, float c) {
    vec3 f0 = min(vec3(gltfDielectricF0(m.ior)) * m.specularColor, vec3(1.0f));
    float k = gltfFresnelCosine(m.ior, t, c);
    if (k < 0.0f) return vec3(m.specularWeight);  // past the critical angle
    vec3 fr = f0 + (vec3(1.0f) - f0) * schlickWeight(k);
    return mix(fr, thinFilmFresnel(m.iridescenceIor, m.iridescenceThickness, k, f0), m.iridescence) * m.specularWeight;
}
#endif

// The dielectric's specular layer at microfacet cosine c = |v.h|: Fd in every channel; with
// KHR_materials_specular its fresnel_mix, weight x Schlick's from F0 = min(F0(ior) x specular
// colour, 1) to 1 (F90 = the weight, the base below it scaled by 1 - max(layer):
// gltfDielectricBase); with KHR_materials_iridescence mixed with a thin film's
// (gltfIridescentLayer).
GPURT_FN vec3 gltfDielectricLayer(MaterialRecord m, float c) {
    float t = gltfTransmission(m);
#if defined(__cplusplus) || defined(SCENE_IRIDESCENCE)
    if (m.iridescence > 0.0f) return gltfIridescentLayer(m, t, c);
#endif
#if defined(__cplusplus) || defined(SCENE_SPECULAR_LAYER)  // SceneTextures::bind
    if (m.specularWeight != 1.0f || m.specularColor != vec3(1.0f)) {
        vec3 f0 = min(vec3(gltfDielectricF0(m.ior)) * m.specularColor, vec3(1.0f));
        float k = gltfFresnelCosine(m.ior, t, c);
        vec3 fr = k < 0.0f ? vec3(1.0f) : f0 + (vec3(1.0f) - f0) * schlickWeight(k);
        return fr * m.specularWeight;
    }
#endif
    return vec3(gltfDielectricFresnel(m.ior, t, c));
}

// What of the dielectric's base (diffuse, transmission) the specular layer leaves at c: 1 - Fd,
// 1 - max(layer) with KHR_materials_specular.
GPURT_FN float gltfDielectricBase(MaterialRecord m, float c) { return 1.0f - maxChannel(gltfDielectricLayer(m, c)); }

// The specular lobe's Fresnel weight (1 - m) Fd + m Fm at v.h = vh; with KHR_materials_iridescence
// the conductor's Fm mixed with a thin film's over it (F0 the base colour) by the factor.
GPURT_FN vec3 gltfSpecularFresnel(MaterialRecord m, float vh) {
    float w = schlickWeight(vh);
    vec3 conductor = m.kd + (vec3(1.0f) - m.kd) * w;
#if defined(__cplusplus) || defined(SCENE_IRIDESCENCE)
    if (m.iridescence > 0.0f && m.metallic > 0.0f)
        conductor = mix(conductor, thinFilmFresnel(m.iridescenceIor, m.iridescenceThickness, vh, m.kd), m.iridescence);
#endif
    return gltfDielectricLayer(m, vh) * (1.0f - m.metallic) + conductor * m.metallic;
}

// The diffuse term's weight (1 - m)(1 - t)(1 - Fd) c at v.h = vh (the BRDF's diffuse part times pi).
GPURT_FN vec3 gltfDiffuseWeight(MaterialRecord m, float vh) {
    float t = gltfTransmission(m);
    return m.kd * ((1.0f - m.metallic) * (1.0f - t) * gltfDielectricBase(m, vh));
}

// The transmission's weight (1 - m) t (1 - Fd) c at v.h = vh (the BTDF's factor before its
// microfacet terms).
GPURT_FN vec3 gltfTransmissionWeight(MaterialRecord m, float vh) {
    float t = gltfTransmission(m);
    if (!(t > 0.0f)) return vec3(0.0f);
    return m.kd * ((1.0f - m.metallic) * t * gltfDielectricBase(m, vh));
}

// KHR_materials_clearcoat's fresnel_coat: the coat's weight seen from v, the clearcoat factor
// times Schlick's reflectance of a dielectric of index 1.5 (F0 0.04) at the coat normal's n.v;
// what lies under the coat (the rest of the BRDF, the BTDF, the emission) is scaled by 1 - it.
GPURT_FN float gltfCoatWeight(MaterialRecord m, vec3 v) {
#if defined(__cplusplus) || defined(SCENE_CLEARCOAT)  // SceneTextures::bind
    if (m.coat > 0.0f) return m.coat * (GPURT_GLTF_DIELECTRIC + (1.0f - GPURT_GLTF_DIELECTRIC) * schlickWeight(abs(dot(m.coatNormal, v))));
#endif
    return 0.0f;
}

// Whether the coat is a perfect mirror (its roughness below GPURT_GLTF_SMOOTH; the default).
GPURT_FN bool gltfCoatSmooth(MaterialRecord m) { return gltfSmooth(m.coatRoughness); }

#include "sheen.h"

// Whether the record has a sheen (compiled only for scenes with one).
GPURT_FN bool gltfHasSheen(MaterialRecord m) {
#if defined(__cplusplus) || defined(SCENE_SHEEN)
    return maxChannel(m.sheenColor) > 0.0f;
#else
    return false;
#endif
}

// What the sheen leaves of the rest seen at cosine mu: 1 - max(sheen colour) E(mu) (the albedo
// scaling's one side; 1 without a sheen).
GPURT_FN float gltfSheenBase(MaterialRecord m, float mu) {
#if defined(__cplusplus) || defined(SCENE_SHEEN)
    if (gltfHasSheen(m)) return 1.0f - maxChannel(m.sheenColor) * sheenAlbedo(mu, m.sheenRoughness);
#endif
    return 1.0f;
}

// The probability that the specular lobe's microfacet at v.h = vh reflects (else it refracts):
// the reflection's share of the two weights (largest channels).
GPURT_FN float gltfReflectProbability(MaterialRecord m, float vh) {
    float r = maxChannel(gltfSpecularFresnel(m, vh));
    float t = maxChannel(gltfTransmissionWeight(m, vh));
    return r + t > 0.0f ? r / (r + t) : 1.0f;
}

// The BRDF under the coat, f(l, v) at shading normal n facing v (0 below the surface); a smooth
// surface's mirror is not in it.
GPURT_FN vec3 gltfBaseBrdf(MaterialRecord m, vec3 n, vec3 v, vec3 l) {
    float nl = dot(n, l);
    if (!(nl > 0.0f)) return vec3(0.0f);
    float nv = max(dot(n, v), GPURT_GLTF_MIN_COS);
    vec3 h = l + v;
    float hh = dot(h, h);
    if (!(hh > 0.0f)) return vec3(0.0f);
    h = h / sqrt(hh);
    float vh = abs(dot(v, h));
    vec3 f = gltfDiffuseWeight(m, vh) * GPURT_INV_PI;
    if (gltfBaseSmooth(m)) return f;
    return f + gltfSpecularFresnel(m, vh) * gltfSpecularLobe(m, n, v, l, h, nl, nv);
}

// The rough coat's microfacet lobe D V about the coat normal (its Fresnel is the weight
// gltfCoatWeight); 0 for a smooth coat (a delta) or below the coat.
GPURT_FN float gltfCoatLobe(MaterialRecord m, vec3 v, vec3 l) {
    vec3 n = m.coatNormal;
    float nl = dot(n, l);
    if (gltfCoatSmooth(m) || !(nl > 0.0f)) return 0.0f;
    float nv = max(dot(n, v), GPURT_GLTF_MIN_COS);
    vec3 h = l + v;
    float hh = dot(h, h);
    if (!(hh > 0.0f)) return 0.0f;
    h = h / sqrt(hh);
    return ggxLobe(m.coatRoughness * m.coatRoughness, max(dot(n, h), 0.0f), nl, nv);
}

// The BRDF f(l, v): the base's, under a sheen where there is one (KHR_materials_sheen: sheen colour
// D V + base x min(1 - max(colour) E(n.v), 1 - max(colour) E(n.l))), under the coat where there is
// one (KHR_materials_clearcoat: mix(that, coat lobe, coat weight)). Every caller weighs f by the
// cosine about the shading normal n; the coat's lobe lies about the coat's own normal (its normal
// texture's, or the surface's where the base has a normal texture and the coat none), whose
// cosine it takes as the glTF Sample Viewer does: times (coat normal . l) / (n . l), exactly 1
// where the two normals are the same.
GPURT_FN vec3 gltfBrdf(MaterialRecord m, vec3 n, vec3 v, vec3 l) {
    vec3 f = gltfBaseBrdf(m, n, v, l);
#if defined(__cplusplus) || defined(SCENE_SHEEN)
    float nl = dot(n, l);
    if (gltfHasSheen(m) && nl > 0.0f) {  // sheen colour D V + the rest x min(scaling at v, at l)
        float nv = max(dot(n, v), GPURT_GLTF_MIN_COS);
        vec3 h = contractNormalize(l + v);
        f = f * min(gltfSheenBase(m, nv), gltfSheenBase(m, nl)) +
            m.sheenColor * sheenLobe(sheenAlpha(m.sheenRoughness), max(dot(n, h), 0.0f), nl, nv);
    }
#endif
#if defined(__cplusplus) || defined(SCENE_CLEARCOAT)
    if (m.coat > 0.0f) {
        float w = gltfCoatWeight(m, v);
        float nl = dot(n, l);
        float cosines = nl > 0.0f ? max(dot(m.coatNormal, l), 0.0f) / nl : 0.0f;
        f = f * (1.0f - w) + vec3(w * (gltfCoatLobe(m, v, l) * cosines));
    }
#endif
    return f;
}

// The refraction's generalized half vector of v and l below the surface (relative index ior) on
// n's side, with its cosines vh = v.h > 0 and lh = l.h < 0; false where none.
GPURT_FN bool gltfRefractionHalf(float ior, vec3 n, vec3 v, vec3 l, GPURT_OUT(vec3) h, GPURT_OUT(float) vh,
                                 GPURT_OUT(float) lh) {
    h = v + ior * l;
    vh = 0.0f;
    lh = 0.0f;
    float hh = dot(h, h);
    if (!(hh > 0.0f)) return false;
    h = h / sqrt(hh);
    if (dot(h, n) < 0.0f) h = -h;
    vh = dot(v, h);
    lh = dot(l, h);
    return vh > 0.0f && lh < 0.0f;
}

// Whether the record is a thin wall: compiled in only for scenes that have one (SceneTextures::bind
// defines SCENE_THIN_WALLS; llvmpipe would run the branches of every transmissive hit otherwise).
GPURT_FN bool gltfThin(MaterialRecord m) {
#if defined(__cplusplus) || defined(SCENE_THIN_WALLS)
    return m.thin;
#else
    return false;
#endif
}

// A thin wall's transmission (KHR_materials_transmission without a volume: record thin): the light
// passes an infinitely thin sheet unbent, so l below the surface is the reflection's lobe at l's
// mirror image through the surface, l - 2 (n.l) n, above it.
GPURT_FN vec3 gltfThinMirror(vec3 n, vec3 l) { return l - 2.0f * dot(n, l) * n; }

// The half vector of v and the mirror image of l below the surface through a thin wall, with v.h;
// false where none.
GPURT_FN bool gltfThinHalf(vec3 n, vec3 v, vec3 l, GPURT_OUT(vec3) h, GPURT_OUT(float) vh) {
    h = v + gltfThinMirror(n, l);
    vh = 0.0f;
    float hh = dot(h, h);
    if (!(hh > 0.0f)) return false;
    h = h / sqrt(hh);
    vh = dot(v, h);
    return vh > 0.0f;
}

// What a delta refraction divides radiance by: ior^2 into a solid, 1 through a thin wall.
GPURT_FN float gltfRadianceDivisor(MaterialRecord m) { return gltfThin(m) ? 1.0f : m.ior * m.ior; }

// The rough dielectric's BTDF f(l, v) for l below the surface (Walter et al. 2007; pbrt-v4's
// DielectricBxDF): weight D G2 |l.h| v.h / ((l.h + v.h / ior)^2 |n.l| n.v), radiance scaled by
// 1 / ior^2; through a thin wall the reflection's D V at l's mirror image (the extension's
// specular_btdf); 0 for a smooth surface (its refraction is a delta) or without transmission.
GPURT_FN vec3 gltfBtdf(MaterialRecord m, vec3 n, vec3 v, vec3 l) {
    float anl = -dot(n, l);
    if (!(anl > 0.0f) || gltfBaseSmooth(m) || !(gltfTransmission(m) > 0.0f)) return vec3(0.0f);
    vec3 h;
    float vh, lh;
    float nv = max(dot(n, v), GPURT_GLTF_MIN_COS);
    float k;
    if (gltfThin(m)) {
        if (!gltfThinHalf(n, v, l, h, vh)) return vec3(0.0f);
        k = gltfSpecularLobe(m, n, v, gltfThinMirror(n, l), h, anl, nv);
    } else {
        if (!gltfRefractionHalf(m.ior, n, v, l, h, vh, lh)) return vec3(0.0f);
        float denom = lh + vh / m.ior;
        // G2 / (|n.l| n.v) = 4 V
        k = gltfSpecularLobe(m, n, v, l, h, anl, nv) * 4.0f * (-lh) * vh / (denom * denom * m.ior * m.ior);
    }
    return gltfTransmissionWeight(m, vh) * (k * (1.0f - gltfCoatWeight(m, v)) * gltfSheenBase(m, nv));
}

// The probability of sampling the specular lobe (reflection or refraction at a visible normal) at
// n.v = nv: its weights' share of all at h = n (largest channels).
GPURT_FN float gltfSpecularProbability(MaterialRecord m, float nv) {
    float s = maxChannel(gltfSpecularFresnel(m, nv)) + maxChannel(gltfTransmissionWeight(m, nv));
    float d = maxChannel(gltfDiffuseWeight(m, nv));
    return s + d > 0.0f ? s / (s + d) : 0.0f;
}

// The probability of sampling a layer of weight w over the base at shading n.v = nv: w's share
// beside the base's lobes under it, scaled by 1 - w (their weights at h = n, largest channels).
GPURT_FN float gltfLayerProbability(MaterialRecord m, float w, float nv) {
    float base = maxChannel(gltfSpecularFresnel(m, nv)) + maxChannel(gltfTransmissionWeight(m, nv)) +
                 maxChannel(gltfDiffuseWeight(m, nv));
    float all = w + (1.0f - w) * base;
    return all > 0.0f ? w / all : 0.0f;
}

// The probability of sampling the coat (coat weight w seen from v, shading n.v = nv); 0 without.
GPURT_FN float gltfCoatProbability(MaterialRecord m, float w, float nv) {
#if defined(__cplusplus) || defined(SCENE_CLEARCOAT)
    if (w > 0.0f) return gltfLayerProbability(m, w, nv);
#endif
    return 0.0f;
}

// GGX's pdf of the visible normal h seen from v: D(h) G1(v) v.h / n.v.
GPURT_FN float ggxVisiblePdf(float a2, vec3 n, vec3 v, vec3 h) {
    float nv = max(dot(n, v), GPURT_GLTF_MIN_COS);
    return ggxDistribution(a2, max(dot(n, h), 0.0f)) * smithMasking(a2, nv) * max(dot(v, h), 0.0f) / nv;
}

// The pdf of the base's visible normal h seen from v about the shading normal n (gltfVisibleNormal).
GPURT_FN float gltfVisiblePdf(MaterialRecord m, vec3 n, vec3 v, vec3 h) {
#if defined(__cplusplus) || defined(SCENE_ANISOTROPY)
    if (gltfAnisotropic(m)) {
        vec3 t, b;
        vec2 a = gltfAnisotropicFrame(m, n, t, b);
        float nv = max(dot(n, v), GPURT_GLTF_MIN_COS);
        return ggxAnisotropicDistribution(a.x, a.y, dot(t, h), dot(b, h), max(dot(n, h), 0.0f)) *
               ggxAnisotropicMasking(a.x, a.y, dot(t, v), dot(b, v), nv) * max(dot(v, h), 0.0f) / nv;
    }
#endif
    float alpha = m.roughness * m.roughness;
    return ggxVisiblePdf(alpha * alpha, n, v, h);
}

// The solid-angle pdf of sampling l (specular lobe with probability pSpecular) above the surface:
// the visible normal's pdf / (4 v.h) times the share that reflects (0 for a smooth surface's
// mirror: a delta) plus the cosine lobe's; below it, the visible normal's pdf times the
// refraction's Jacobian |l.h| / (l.h + v.h / ior)^2 and the share that refracts (through a thin
// wall the reflection's pdf at l's mirror image).
GPURT_FN float gltfBasePdf(MaterialRecord m, float pSpecular, vec3 n, vec3 v, vec3 l) {
    float nl = dot(n, l);
    bool rough = !gltfBaseSmooth(m) && pSpecular > 0.0f;
    if (nl < 0.0f) {
        vec3 h;
        float vh, lh;
        if (!rough || !(gltfTransmission(m) > 0.0f)) return 0.0f;
        if (gltfThin(m)) {
            if (!gltfThinHalf(n, v, l, h, vh)) return 0.0f;
            return pSpecular * (1.0f - gltfReflectProbability(m, vh)) * gltfVisiblePdf(m, n, v, h) / (4.0f * vh);
        }
        if (!gltfRefractionHalf(m.ior, n, v, l, h, vh, lh)) return 0.0f;
        float denom = lh + vh / m.ior;
        return pSpecular * (1.0f - gltfReflectProbability(m, vh)) * gltfVisiblePdf(m, n, v, h) * (-lh) / (denom * denom);
    }
    if (!(nl > 0.0f)) return 0.0f;
    float pdf = (1.0f - pSpecular) * nl * GPURT_INV_PI;
    if (!rough) return pdf;
    vec3 h = l + v;
    float hh = dot(h, h);
    if (!(hh > 0.0f)) return pdf;
    h = h / sqrt(hh);
    float vh = max(dot(v, h), 0.0f);
    if (!(vh > 0.0f)) return pdf;
    return pdf + pSpecular * gltfReflectProbability(m, vh) * gltfVisiblePdf(m, n, v, h) / (4.0f * vh);
}

// The probability of sampling the sheen (by the cosine, as the diffuse lobe) under the coat at
// shading n.v = nv: its albedo max(colour) E(nv)'s share beside the lobes under it; 0 without.
GPURT_FN float gltfSheenProbability(MaterialRecord m, float nv) {
#if defined(__cplusplus) || defined(SCENE_SHEEN)
    if (gltfHasSheen(m)) return gltfLayerProbability(m, 1.0f - gltfSheenBase(m, nv), nv);
#endif
    return 0.0f;
}

// The solid-angle pdf of sampling l: the coat's visible normal with probability pCoat (0 for a
// smooth coat: a delta), else the sheen's cosine lobe with its probability, else the base's lobes
// (gltfBasePdf).
GPURT_FN float gltfPdf(MaterialRecord m, float pCoat, float pSpecular, vec3 n, vec3 v, vec3 l) {
    float pdf = gltfBasePdf(m, pSpecular, n, v, l);
#if defined(__cplusplus) || defined(SCENE_SHEEN)
    if (gltfHasSheen(m)) {
        float ps = gltfSheenProbability(m, max(dot(n, v), GPURT_GLTF_MIN_COS));
        pdf = pdf * (1.0f - ps) + ps * max(dot(n, l), 0.0f) * GPURT_INV_PI;
    }
#endif
#if defined(__cplusplus) || defined(SCENE_CLEARCOAT)
    if (pCoat > 0.0f) {
        pdf = pdf * (1.0f - pCoat);
        vec3 nc = m.coatNormal;
        vec3 h = l + v;
        float hh = dot(h, h);
        if (!gltfCoatSmooth(m) && dot(nc, l) > 0.0f && hh > 0.0f) {
            h = h / sqrt(hh);
            float vh = dot(v, h);
            float alpha = m.coatRoughness * m.coatRoughness;
            if (vh > 0.0f) pdf = pdf + pCoat * ggxVisiblePdf(alpha * alpha, nc, v, h) / (4.0f * vh);
        }
    }
#endif
    return pdf;
}

// A microfacet normal of GGX visible from v, alpha ax along the unit tangent t and ay along b
// (t, b, n orthonormal), for u in [0, 1)^2 (Heitz 2018, listing 1).
GPURT_FN vec3 ggxStretchedVisibleNormal(vec3 t, vec3 b, vec3 n, vec3 v, float ax, float ay, vec2 u) {
    vec3 ve = vec3(dot(v, t), dot(v, b), max(dot(v, n), GPURT_GLTF_MIN_COS));
    vec3 vh = contractNormalize(vec3(ax * ve.x, ay * ve.y, ve.z));
    float lensq = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = lensq > 0.0f ? vec3(-vh.y, vh.x, 0.0f) / sqrt(lensq) : vec3(1.0f, 0.0f, 0.0f);
    vec3 t2 = cross(vh, t1);
    float r = sqrt(u.x);
    float phi = 2.0f * GPURT_PI * u.y;
    float p1 = r * cos(phi);
    float s = 0.5f * (1.0f + vh.z);
    float p2 = (1.0f - s) * sqrt(max(0.0f, 1.0f - p1 * p1)) + s * (r * sin(phi));
    vec3 nh = t1 * p1 + t2 * p2 + vh * sqrt(max(0.0f, 1.0f - p1 * p1 - p2 * p2));
    vec3 ne = contractNormalize(vec3(ax * nh.x, ay * nh.y, max(0.0f, nh.z)));
    return t * ne.x + b * ne.y + n * ne.z;
}

// The same for the isotropic GGX (alpha) about the shading normal n (any tangent).
GPURT_FN vec3 ggxVisibleNormal(vec3 n, vec3 v, float alpha, vec2 u) {
    vec3 t, b;
    orthonormalBasis(n, t, b);
    return ggxStretchedVisibleNormal(t, b, n, v, alpha, alpha, u);
}

// The base's visible normal from v about the shading normal n: the isotropic GGX's of alpha =
// roughness^2, stretched along the anisotropy's direction (KHR_materials_anisotropy).
GPURT_FN vec3 gltfVisibleNormal(MaterialRecord m, vec3 n, vec3 v, vec2 u) {
#if defined(__cplusplus) || defined(SCENE_ANISOTROPY)
    if (gltfAnisotropic(m)) {
        vec3 t, b;
        vec2 a = gltfAnisotropicFrame(m, n, t, b);
        return ggxStretchedVisibleNormal(t, b, n, v, a.x, a.y, u);
    }
#endif
    return ggxVisibleNormal(n, v, m.roughness * m.roughness, u);
}

// The ambient albedo: the directional albedo at normal incidence, (1 - m)(1 - t) 0.96 c + F0 with
// F0 = mix(0.04, c, m), without F0 for a smooth coat (its mirror ray brings it), under a sheen's
// scaling with the sheen's own albedo added, under a coat's (1 - its weight) with a rough coat's
// own weight added (a smooth one's comes by the mirror ray), times the occlusion.
GPURT_FN vec3 gltfAmbientAlbedo(MaterialRecord m) {
    vec3 albedo = gltfDiffuseWeight(m, 1.0f);
    if (!gltfBaseSmooth(m)) albedo = albedo + gltfSpecularFresnel(m, 1.0f);
#if defined(__cplusplus) || defined(SCENE_SHEEN)
    if (gltfHasSheen(m)) albedo = albedo * gltfSheenBase(m, 1.0f) + m.sheenColor * sheenAlbedo(1.0f, m.sheenRoughness);
#endif
#if defined(__cplusplus) || defined(SCENE_CLEARCOAT)
    if (m.coat > 0.0f) {
        float w = m.coat * GPURT_GLTF_DIELECTRIC;
        albedo = albedo * (1.0f - w) + vec3(gltfCoatSmooth(m) ? 0.0f : w);
    }
#endif
    return albedo * m.occlusion;
}

// The record as a ray meets the surface: a transmissive material's index becomes relative across
// the boundary in the ray's direction (1 / ior leaving the solid: `entering` false; a thin wall has
// the same outside on both sides), and a volume's absorption is the medium the ray came through
// only when it leaves the solid.
GPURT_FN MaterialRecord gltfFacing(MaterialRecord m, bool entering) {
    if (m.ior > 0.0f && !entering && !gltfThin(m)) m.ior = 1.0f / m.ior;
    if (entering) m.absorption = vec3(0.0f);  // the volume's medium is behind the front face
    return m;
}

// The material interface (common/material.h) for the glTF model.
GPURT_FN vec3 gltfAmbient(MaterialRecord m) { return GPURT_AMBIENT * gltfAmbientAlbedo(m); }
GPURT_FN vec3 gltfEnvironmentAmbient(MaterialRecord m, vec3 irradiance) {
    return gltfAmbientAlbedo(m) * irradiance * GPURT_INV_PI;
}

// The emission seen along d: under a coat, times 1 - its weight (KHR_materials_clearcoat).
GPURT_FN vec3 gltfEmitted(MaterialRecord m, vec3 d) { return m.emission * (1.0f - gltfCoatWeight(m, -d)); }

GPURT_FN vec3 gltfLight(MaterialRecord m, vec3 p, vec3 n, vec3 d, vec3 lightPos, vec3 lightColor, float intensity) {
    vec3 toLight = lightPos - p;
    float dist2 = dot(toLight, toLight);
    vec3 l = contractNormalize(toLight);
    vec3 f = gltfBrdf(m, n, -d, l);
    return min(f * (GPURT_PI * max(0.0f, dot(n, l))) * lightColor * intensity / dist2, vec3(1e30f));
}

// Whether a smooth coat mirrors (KHR_materials_clearcoat with a roughness below GPURT_GLTF_SMOOTH).
GPURT_FN bool gltfCoatMirrors(MaterialRecord m) {
#if defined(__cplusplus) || defined(SCENE_CLEARCOAT)
    return m.coat > 0.0f && gltfCoatSmooth(m);
#else
    return false;
#endif
}

GPURT_FN bool gltfSpawns(MaterialRecord m) {
    return gltfBaseSmooth(m) || gltfTransmission(m) > 0.0f || gltfCoatMirrors(m);
}

GPURT_FN bool gltfSplits(MaterialRecord m) { return gltfTransmission(m) > 0.0f; }

// Whitted's rays: the refracted ray (as through a smooth surface) where the material transmits,
// continuing the pixel's ray, and the mirror ray of a smooth surface and of a smooth coat (one ray:
// about the coat's normal where the coat mirrors, a smooth base's mirror taken along it; the two
// normals differ only under a normal map), the base's weights under the coat's 1 - weight and the
// sheen's scaling.
GPURT_FN int gltfChildren(MaterialRecord m, vec3 d, vec3 ng, vec3 ns, vec3 w, GPURT_OUT(vec3) dirA,
                          GPURT_OUT(vec3) weightA, GPURT_OUT(float) sideA, GPURT_OUT(vec3) dirB,
                          GPURT_OUT(vec3) weightB) {
    float nv = clamp(-dot(d, ns), 0.0f, 1.0f);
    float coat = gltfCoatWeight(m, -d);
    vec3 under = w * ((1.0f - coat) * gltfSheenBase(m, nv));
    dirA = shadingReflection(d, gltfCoatMirrors(m) ? m.coatNormal : ns, ng);
    weightA = gltfBaseSmooth(m) ? under * gltfSpecularFresnel(m, nv) : vec3(0.0f);
    if (gltfCoatMirrors(m)) weightA = weightA + w * coat;
    sideA = 1.0f;
    dirB = dirA;
    weightB = vec3(0.0f);
    vec3 tw = gltfTransmissionWeight(m, nv);
    if (maxChannel(tw) > 0.0f && (gltfThin(m) || (1.0f - nv * nv) < m.ior * m.ior)) {
        vec3 t = gltfThin(m) ? d : refractedDirection(d, ns, m.ior, nv);  // a thin wall does not bend it
        if (dot(t, ng) < 0.0f) {
            weightB = weightA;
            dirA = t;
            weightA = under * tw / gltfRadianceDivisor(m);
            sideA = -1.0f;
        }
    }
    return rayTreeChildren(dirA, weightA, sideA, dirB, weightB);
}

GPURT_FN bool gltfLit(MaterialRecord m) {
    bool roughCoat = false;
#if defined(__cplusplus) || defined(SCENE_CLEARCOAT)
    roughCoat = m.coat > 0.0f && !gltfCoatSmooth(m);
#endif
    return !gltfBaseSmooth(m) || maxChannel(gltfDiffuseWeight(m, 1.0f)) > 0.0f || roughCoat || gltfHasSheen(m);
}

// pi times the BRDF (light sampling reaches only directions above the surface).
GPURT_FN vec3 gltfEval(MaterialRecord m, vec3 n, vec3 d, vec3 wi) { return GPURT_PI * gltfBrdf(m, n, -d, wi); }

GPURT_FN float gltfMaterialPdf(MaterialRecord m, vec3 n, vec3 d, vec3 wi) {
    if (!(dot(n, wi) > 0.0f)) return 0.0f;
    float nv = max(-dot(d, n), GPURT_GLTF_MIN_COS);
    float p = gltfSpecularProbability(m, nv);
    return gltfPdf(m, gltfCoatProbability(m, gltfCoatWeight(m, -d), nv), p, n, -d, wi);
}

// gltfSample's layers: with probability pc (the coat's weight `coat` seen at n.v = nv) the coat's
// lobe, its mirror a delta (GPURT_LAYER_DELTA: dir and factor set), its GGX lobe a direction
// (GPURT_LAYER_PICKED: dir set, to be weighed as the mixture); else with the sheen's share its
// cosine lobe (GPURT_LAYER_PICKED); else (GPURT_LAYER_BASE) the lobe number rescaled for the base's
// lobes and `under` their delta lobes' factor for the layers over them.
#define GPURT_LAYER_BASE 0
#define GPURT_LAYER_DELTA 1
#define GPURT_LAYER_PICKED 2
GPURT_FN int gltfSampleLayers(MaterialRecord m, vec3 d, vec3 ng, vec3 ns, vec2 u, float nv, float coat, float pc,
                              GPURT_INOUT(float) lobe, GPURT_INOUT(vec3) dir, GPURT_INOUT(vec3) factor,
                              GPURT_OUT(vec3) under) {
    under = vec3(1.0f);
    int layer = GPURT_LAYER_BASE;
#if defined(__cplusplus) || defined(SCENE_CLEARCOAT)
    if (lobe < pc) {
        if (gltfCoatSmooth(m)) {  // a delta lobe
            dir = shadingReflection(d, m.coatNormal, ng);
            factor = vec3(coat / pc);
            return GPURT_LAYER_DELTA;
        }
        dir = mirrorDirection(d, ggxVisibleNormal(m.coatNormal, -d, m.coatRoughness * m.coatRoughness, u));
        layer = GPURT_LAYER_PICKED;
    } else if (pc > 0.0f) {
        lobe = (lobe - pc) / (1.0f - pc);
        under = vec3((1.0f - coat) / (1.0f - pc));
    }
#endif
#if defined(__cplusplus) || defined(SCENE_SHEEN)
    float ps = layer == GPURT_LAYER_PICKED ? 0.0f : gltfSheenProbability(m, nv);
    if (lobe < ps) {
        dir = directionAbout(ns, sqrt(1.0f - u.x), u.y);  // cosine-weighted
        layer = GPURT_LAYER_PICKED;
    } else if (ps > 0.0f) {
        lobe = (lobe - ps) / (1.0f - ps);
        under = under * (gltfSheenBase(m, nv) / (1.0f - ps));
    }
#endif
    return layer;
}

// A direction by the lobes' probabilities: the coat's (its weight's share), else the base's lobes
// (the lobe number rescaled). A refracted direction reports pdf 0: light sampling never draws
// below the surface, so the emission it finds counts in full (common/path.h).
GPURT_FN bool gltfSample(MaterialRecord m, vec3 d, vec3 ng, vec3 ns, vec2 u, float lobe, GPURT_OUT(vec3) dir,
                         GPURT_OUT(vec3) factor, GPURT_OUT(float) pdf, GPURT_OUT(float) side) {
    vec3 v = -d;
    float nv = max(dot(ns, v), GPURT_GLTF_MIN_COS);
    float p = gltfSpecularProbability(m, nv);
    float coat = gltfCoatWeight(m, v);
    float pc = gltfCoatProbability(m, coat, nv);
    dir = shadingReflection(d, ns, ng);
    factor = vec3(0.0f);
    pdf = 0.0f;
    side = 1.0f;
    bool mirror = gltfBaseSmooth(m);
    vec3 under;  // the base's delta lobes' share under the coat and sheen over their probability's
    int layer = gltfSampleLayers(m, d, ng, ns, u, nv, coat, pc, lobe, dir, factor, under);
    if (layer == GPURT_LAYER_DELTA) return true;
    if (layer == GPURT_LAYER_PICKED) {  // the coat's or the sheen's direction: evaluated below as the mixture
    } else if (lobe < p) {
        vec3 h = mirror ? ns : gltfVisibleNormal(m, ns, v, u);
        float vh = mirror ? nv : max(dot(v, h), 0.0f);
        float pr = gltfReflectProbability(m, vh);
        if (lobe < p * pr) {
            if (mirror) {  // a delta lobe
                factor = gltfSpecularFresnel(m, nv) / (p * pr) * under;
                return true;
            }
            dir = mirrorDirection(d, h);
        } else {  // refraction through the microfacet h; through a thin wall its reflection mirrored
            if (gltfThin(m)) {
                dir = mirror ? d : gltfThinMirror(ns, mirrorDirection(d, h));
            } else {
                if (!((1.0f - vh * vh) < m.ior * m.ior)) return false;
                dir = refractedDirection(d, h, m.ior, vh);
            }
            float cosT = -dot(ns, dir);
            if (!(dot(dir, ng) < 0.0f) || !(cosT > 0.0f)) return false;
            side = -1.0f;
            if (mirror) {  // a delta lobe
                factor = gltfTransmissionWeight(m, nv) / (gltfRadianceDivisor(m) * p * (1.0f - pr)) * under;
                return true;
            }
            float tpdf = gltfPdf(m, pc, p, ns, v, dir);
            if (!(tpdf > 0.0f)) return false;
            factor = gltfBtdf(m, ns, v, dir) * (cosT / tpdf);
            return true;
        }
    } else {
        dir = directionAbout(ns, sqrt(1.0f - u.x), u.y);  // cosine-weighted
    }
    float cosI = dot(ns, dir);
    if (!(dot(dir, ng) > 0.0f) || !(cosI > 0.0f)) return false;
    pdf = gltfPdf(m, pc, p, ns, v, dir);
    if (!(pdf > 0.0f)) return false;
    factor = gltfBrdf(m, ns, v, dir) * (cosI / pdf);
    return true;
}

#endif
