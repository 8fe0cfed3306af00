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
#ifndef GPURT_MATERIALS_GLTF_H
#define GPURT_MATERIALS_GLTF_H

#define GPURT_GLTF_SMOOTH 0.01f     // roughness below this: a perfect mirror (alpha < 1e-4)
#define GPURT_GLTF_DIELECTRIC 0.04f  // F0 of the dielectric (ior 1.5)
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

// Smith's masking G1 of the view at n.v for alpha^2 = a2.
GPURT_FN float smithMasking(float a2, float nv) { return 2.0f * nv / (nv + sqrt(a2 + (1.0f - a2) * nv * nv)); }

// The specular lobe's Fresnel weight (1 - m) Fd + m Fm at v.h = vh.
GPURT_FN vec3 gltfSpecularFresnel(vec3 base, float metallic, float vh) {
    float w = schlickWeight(vh);
    float dielectric = GPURT_GLTF_DIELECTRIC + (1.0f - GPURT_GLTF_DIELECTRIC) * w;
    vec3 conductor = base + (vec3(1.0f) - base) * w;
    return vec3(dielectric * (1.0f - metallic)) + conductor * metallic;
}

// The diffuse term's weight (1 - m)(1 - Fd) c at v.h = vh (the BRDF's diffuse part times pi).
GPURT_FN vec3 gltfDiffuseWeight(vec3 base, float metallic, float vh) {
    float dielectric = GPURT_GLTF_DIELECTRIC + (1.0f - GPURT_GLTF_DIELECTRIC) * schlickWeight(vh);
    return base * ((1.0f - metallic) * (1.0f - dielectric));
}

// The BRDF f(l, v) at shading normal n (0 below the surface); a smooth coat's mirror is not in it.
GPURT_FN vec3 gltfBrdf(vec3 base, float metallic, float roughness, vec3 n, vec3 v, vec3 l) {
    float nl = dot(n, l);
    if (!(nl > 0.0f)) return vec3(0.0f);
    float nv = max(dot(n, v), GPURT_GLTF_MIN_COS);
    vec3 h = l + v;
    float hh = dot(h, h);
    if (!(hh > 0.0f)) return vec3(0.0f);
    h = h / sqrt(hh);
    float vh = abs(dot(v, h));
    vec3 f = gltfDiffuseWeight(base, metallic, vh) * GPURT_INV_PI;
    if (gltfSmooth(roughness)) return f;
    float alpha = roughness * roughness;
    float a2 = alpha * alpha;
    float nh = max(dot(n, h), 0.0f);
    return f + gltfSpecularFresnel(base, metallic, vh) * (ggxDistribution(a2, nh) * smithVisibility(a2, nl, nv));
}

// The probability of sampling the specular lobe at n.v = nv: its Fresnel weight's share of the
// two lobes' weights at h = n (largest channels).
GPURT_FN float gltfSpecularProbability(vec3 base, float metallic, float nv) {
    float s = maxChannel(gltfSpecularFresnel(base, metallic, nv));
    float d = maxChannel(gltfDiffuseWeight(base, metallic, nv));
    return s + d > 0.0f ? s / (s + d) : 0.0f;
}

// The solid-angle pdf of sampling l (specular lobe with probability pSpecular): the visible
// normals' D G1(v) / (4 n.v) (0 for a smooth coat's mirror: a delta) plus the cosine lobe's.
GPURT_FN float gltfPdf(float roughness, float pSpecular, vec3 n, vec3 v, vec3 l) {
    float nl = dot(n, l);
    if (!(nl > 0.0f)) return 0.0f;
    float pdf = (1.0f - pSpecular) * nl * GPURT_INV_PI;
    if (gltfSmooth(roughness) || !(pSpecular > 0.0f)) return pdf;
    vec3 h = l + v;
    float hh = dot(h, h);
    if (!(hh > 0.0f)) return pdf;
    h = h / sqrt(hh);
    float alpha = roughness * roughness;
    float a2 = alpha * alpha;
    float nv = max(dot(n, v), GPURT_GLTF_MIN_COS);
    float nh = max(dot(n, h), 0.0f);
    return pdf + pSpecular * ggxDistribution(a2, nh) * smithMasking(a2, nv) / (4.0f * nv);
}

// A microfacet normal of GGX (alpha) visible from v, for u in [0, 1)^2 (Heitz 2018, listing 1,
// isotropic), about the shading normal n.
GPURT_FN vec3 ggxVisibleNormal(vec3 n, vec3 v, float alpha, vec2 u) {
    vec3 t, b;
    orthonormalBasis(n, t, b);
    vec3 ve = vec3(dot(v, t), dot(v, b), max(dot(v, n), GPURT_GLTF_MIN_COS));
    vec3 vh = contractNormalize(vec3(alpha * ve.x, alpha * ve.y, ve.z));
    float lensq = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = lensq > 0.0f ? vec3(-vh.y, vh.x, 0.0f) / sqrt(lensq) : vec3(1.0f, 0.0f, 0.0f);
    vec3 t2 = cross(vh, t1);
    float r = sqrt(u.x);
    float phi = 2.0f * GPURT_PI * u.y;
    float p1 = r * cos(phi);
    float s = 0.5f * (1.0f + vh.z);
    float p2 = (1.0f - s) * sqrt(max(0.0f, 1.0f - p1 * p1)) + s * (r * sin(phi));
    vec3 nh = t1 * p1 + t2 * p2 + vh * sqrt(max(0.0f, 1.0f - p1 * p1 - p2 * p2));
    vec3 ne = contractNormalize(vec3(alpha * nh.x, alpha * nh.y, max(0.0f, nh.z)));
    return t * ne.x + b * ne.y + n * ne.z;
}

// The ambient albedo: the directional albedo at normal incidence, (1 - m) 0.96 c + F0 with
// F0 = mix(0.04, c, m), without F0 for a smooth coat (its mirror ray brings it), times the
// occlusion.
GPURT_FN vec3 gltfAmbientAlbedo(MaterialRecord m) {
    vec3 albedo = gltfDiffuseWeight(m.kd, m.metallic, 1.0f);
    if (!gltfSmooth(m.roughness)) albedo = albedo + gltfSpecularFresnel(m.kd, m.metallic, 1.0f);
    return albedo * m.occlusion;
}

// The material interface (common/material.h) for the glTF model.
GPURT_FN vec3 gltfAmbient(MaterialRecord m) { return GPURT_AMBIENT * gltfAmbientAlbedo(m); }
GPURT_FN vec3 gltfEnvironmentAmbient(MaterialRecord m, vec3 irradiance) {
    return gltfAmbientAlbedo(m) * irradiance * GPURT_INV_PI;
}

GPURT_FN vec3 gltfLight(MaterialRecord m, vec3 p, vec3 n, vec3 d, vec3 lightPos, vec3 lightColor, float intensity) {
    vec3 toLight = lightPos - p;
    float dist2 = dot(toLight, toLight);
    vec3 l = contractNormalize(toLight);
    vec3 f = gltfBrdf(m.kd, m.metallic, m.roughness, n, -d, l);
    return min(f * (GPURT_PI * max(0.0f, dot(n, l))) * lightColor * intensity / dist2, vec3(1e30f));
}

GPURT_FN bool gltfSpawns(MaterialRecord m) { return gltfSmooth(m.roughness); }

GPURT_FN int gltfChildren(MaterialRecord m, vec3 d, vec3 ng, vec3 ns, vec3 w, GPURT_OUT(vec3) dirA,
                          GPURT_OUT(vec3) weightA, GPURT_OUT(float) sideA, GPURT_OUT(vec3) dirB,
                          GPURT_OUT(vec3) weightB) {
    dirA = shadingReflection(d, ns, ng);
    weightA = w * gltfSpecularFresnel(m.kd, m.metallic, max(-dot(d, ns), 0.0f));
    sideA = 1.0f;
    dirB = dirA;
    weightB = vec3(0.0f);
    return gltfSmooth(m.roughness) && maxChannel(weightA) >= GPURT_MIN_WEIGHT ? 1 : 0;
}

GPURT_FN bool gltfLit(MaterialRecord m) {
    return !gltfSmooth(m.roughness) || maxChannel(gltfDiffuseWeight(m.kd, m.metallic, 1.0f)) > 0.0f;
}

GPURT_FN vec3 gltfEval(MaterialRecord m, vec3 n, vec3 d, vec3 wi) {
    return GPURT_PI * gltfBrdf(m.kd, m.metallic, m.roughness, n, -d, wi);
}

GPURT_FN float gltfMaterialPdf(MaterialRecord m, vec3 n, vec3 d, vec3 wi) {
    float p = gltfSpecularProbability(m.kd, m.metallic, max(-dot(d, n), GPURT_GLTF_MIN_COS));
    return gltfPdf(m.roughness, p, n, -d, wi);
}

GPURT_FN bool gltfSample(MaterialRecord m, vec3 d, vec3 ng, vec3 ns, vec2 u, float lobe, GPURT_OUT(vec3) dir,
                         GPURT_OUT(vec3) factor, GPURT_OUT(float) pdf, GPURT_OUT(float) side) {
    vec3 v = -d;
    float nv = max(dot(ns, v), GPURT_GLTF_MIN_COS);
    float p = gltfSpecularProbability(m.kd, m.metallic, nv);
    dir = shadingReflection(d, ns, ng);
    factor = vec3(0.0f);
    pdf = 0.0f;
    side = 1.0f;
    bool mirror = gltfSmooth(m.roughness);
    if (lobe < p) {
        if (mirror) {  // a delta lobe
            factor = gltfSpecularFresnel(m.kd, m.metallic, nv) / p;
            return true;
        }
        vec3 h = ggxVisibleNormal(ns, v, m.roughness * m.roughness, u);
        dir = mirrorDirection(d, h);
    } else {
        dir = directionAbout(ns, sqrt(1.0f - u.x), u.y);  // cosine-weighted
    }
    float cosI = dot(ns, dir);
    if (!(dot(dir, ng) > 0.0f) || !(cosI > 0.0f)) return false;
    pdf = gltfPdf(m.roughness, p, ns, v, dir);
    if (!(pdf > 0.0f)) return false;
    factor = gltfBrdf(m.kd, m.metallic, m.roughness, ns, v, dir) * (cosI / pdf);
    return true;
}

#endif
