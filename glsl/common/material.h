// The material seam, shared word for word by the kernels and the CPU backend (after
// common/shading.h; same rules as raymath.h). A hit's material is fetched once, with its textures
// at the hit, into a MaterialRecord (the kernels: shading.glsl fetchMaterialRecord; C++:
// raytrace/materials/MaterialRecord.h materialRecord); the integrators then ask it only through the
// functions below, which dispatch on the record's model to the model's file in materials/:
//   Whitted:  materialAmbient (the ambient term; materialEnvironmentAmbient under an environment), materialLight (one unshadowed point light),
//             materialSpawns / materialSplits / materialChildren (the reflected and refracted
//             rays of the ray tree);
//   both:     materialEmitted (radiance the surface sends itself, area lights);
//   path:     materialLit (whether next-event estimation can light it: a non-delta lobe),
//             materialEval (pi times the BSDF), materialPdf (the solid-angle pdf materialSample
//             samples a direction with; 0 for delta lobes), materialSample (a direction, its
//             throughput factor f cos / pdf, pdf and side).
// Conventions: d is the incoming ray's direction, ng the geometric normal facing it, ns the shading
// normal (facing as ng), wi the direction towards the light. docs/ARCHITECTURE.md says how to add
// a model.
#ifndef GPURT_MATERIAL_H
#define GPURT_MATERIAL_H

#ifndef GPURT_SHADING_H
#error "include common/shading.h before common/material.h"
#endif

// Material models (the record's `model`; Material::model in the scene): GPURT_MODEL_*.
#include "material_models.h"

// What the integrators know of a material at one hit.
struct MaterialRecord {
    int model;          // GPURT_MODEL_*
    vec3 kd;            // diffuse colour (glTF: base colour), textured at the hit
    vec3 ks;            // specular colour
    float ns;           // Phong exponent
    vec3 reflectivity;  // mirror weight
    vec3 tf;            // transmission filter of a dielectric
    float ior;          // index of refraction; 0: not a dielectric
    bool thin;          // glTF: a thin wall (KHR_materials_transmission without a volume): no bending
    vec3 emission;      // radiance emitted from both sides, textured at the hit
    bool emitterLight;  // its triangles are sampled as area lights (no emissive texture)
    float metallic;     // glTF: metallic and roughness, textured at the hit
    float roughness;
    float occlusion;    // glTF: the ambient terms' factor (occlusion map; 1 without)
    vec3 specularColor;   // glTF, KHR_materials_specular: the F0 colour (1 without), textured
    float specularWeight; // and the specular layer's weight (1 without), textured
    float coat;           // glTF, KHR_materials_clearcoat: the coat's weight (0: none), textured
    float coatRoughness;  // its roughness, textured
    vec3 coatNormal;      // its normal facing the ray (the surface's: CpuScene::surfaceAt, fetchMaterialRecord)
    vec3 sheenColor;      // glTF, KHR_materials_sheen: the sheen's colour (0: none), textured
    float sheenRoughness; // and roughness, textured
    float iridescence;    // glTF, KHR_materials_iridescence: the film's weight (0: none), textured
    float iridescenceIor; // its index
    float iridescenceThickness;  // and thickness (nm), textured
    float anisotropy;     // glTF, KHR_materials_anisotropy: the strength (0: isotropic), textured
    vec3 anisotropyDirection;  // and its direction in scene space (the tangent frame's; not yet
                               // orthogonal to the shading normal: gltfAnisotropicFrame)
    vec3 absorption;      // glTF, KHR_materials_volume: the absorption coefficient (per unit length)
                          // of the medium the ray arrives through: the solid's, seen from inside
                          // it (materialFacing), else 0
    float dispersion;     // glTF, KHR_materials_dispersion: 20 / the Abbe number of a solid (0: none)
};

#include "raytree.h"
#include "materials/classic.h"
// A model other than the classic one is compiled into the kernels only for a scene that uses it
// (SceneTextures::bind defines SCENE_MODEL_<id>): llvmpipe runs both sides of a branch.
#if defined(__cplusplus) || defined(SCENE_MODEL_1)
#define GPURT_WITH_DEBUG_NORMAL
#include "materials/debug_normal.h"
#endif
#if defined(__cplusplus) || defined(SCENE_MODEL_2)
#define GPURT_WITH_GLTF
#include "materials/gltf.h"
#endif
// The models that show only themselves (debug normal, unlit): they send their own colour along
// every ray that sees them (materialEmitted), reflect nothing and no light reaches them.
#if defined(__cplusplus) || defined(SCENE_MODEL_1) || defined(SCENE_MODEL_3)
#define GPURT_WITH_SELF_SHOWN
GPURT_FN bool materialShowsItself(MaterialRecord m) {
    return m.model == GPURT_MODEL_DEBUG_NORMAL || m.model == GPURT_MODEL_UNLIT;
}
#endif

// Whether a path ray that left its last hit in a direction of pdf prevPdf passes the surface as if
// it were not there: KHR_materials_unlit's, as Blender's importer builds it (its colour for camera
// rays and what mirrors and glass show, prevPdf 0; transparent to every other ray, so it lights
// nothing; shadow rays pass it in the traversals, common/alpha.h GPURT_COVER_SHADOWLESS).
GPURT_FN bool materialHiddenFrom(MaterialRecord m, float prevPdf) {
#if defined(__cplusplus) || defined(SCENE_MODEL_3)
    return m.model == GPURT_MODEL_UNLIT && prevPdf > 0.0f;
#else
    return false;  // no unlit material in the scene (SceneTextures::bind)
#endif
}

// The record as the ray meets the surface, on the front side (`entering`: frontFace) or the back:
// the glTF model's index of refraction becomes relative across the boundary in the ray's
// direction. Every integrator applies it to a hit's record before asking the record anything.
GPURT_FN MaterialRecord materialFacing(MaterialRecord m, bool entering) {
#ifdef GPURT_WITH_GLTF
    if (m.model == GPURT_MODEL_GLTF) return gltfFacing(m, entering);
#endif
    return m;
}

// The fraction of the light along the ray's segment of length t to the hit that arrives there:
// the Beer-Lambert transmittance exp(-absorption t) of a KHR_materials_volume solid the ray
// travelled inside (the record as materialFacing made it), 1 elsewhere. The integrators weigh
// everything the hit gives the ray (emission, lights, the rays it spawns) with it.
GPURT_FN vec3 materialTransmittance(MaterialRecord m, float t) {
#if defined(__cplusplus) || defined(SCENE_VOLUME)  // SceneTextures::bind
    if (m.absorption != vec3(0.0f)) return exp(-m.absorption * t);
#endif
    return vec3(1.0f);
}

// KHR_materials_dispersion: the index of a solid of index nd (at the Fraunhofer d line, 587.6 nm)
// and dispersion 20 / V_d (V_d its Abbe number) at wavelength lambda (nm), as the extension
// defines it: max(nd + (nd - 1) / V_d (523655 / lambda^2 - 1.5168), 1), a Cauchy form whose
// indices at the F (486.1 nm) and C (656.3 nm) lines differ by (nd - 1) / V_d.
GPURT_FN float dispersedIor(float nd, float dispersion, float lambda) {
    return max(nd + (nd - 1.0f) * (dispersion / 20.0f) * (523655.0f / (lambda * lambda) - 1.5168f), 1.0f);
}

// The wavelength (nm) that stands for colour channel c under dispersion: the C, d and F lines of
// the Abbe number's definition for red, green and blue, so that green sees the file's index.
GPURT_FN float channelWavelength(int c) { return c == 0 ? 656.3f : (c == 1 ? 587.6f : 486.1f); }

// The colour channel c alone (1 there, 0 in the others).
GPURT_FN vec3 channelMask(int c) { return vec3(c == 0 ? 1.0f : 0.0f, c == 1 ? 1.0f : 0.0f, c == 2 ? 1.0f : 0.0f); }

// Whether record m's index depends on the wavelength (a solid with a dispersion; the scene
// defines SCENE_DISPERSION when a material has one).
GPURT_FN bool materialDisperses(MaterialRecord m) {
#if defined(__cplusplus) || defined(SCENE_DISPERSION)
    return m.dispersion > 0.0f && m.ior > 0.0f;
#else
    return false;
#endif
}

// Record m as light of colour channel c sees it: a dispersing solid's index at the channel's
// wavelength, relative across the boundary as materialFacing made it (an index below 1 is the
// solid's seen from inside: glTF's indices are 0 or >= 1); m itself where it does not disperse.
GPURT_FN MaterialRecord materialAtChannel(MaterialRecord m, int c) {
    if (!materialDisperses(m)) return m;
    bool inside = m.ior < 1.0f;
    float n = dispersedIor(inside ? 1.0f / m.ior : m.ior, m.dispersion, channelWavelength(c));
    m.ior = inside ? 1.0f / n : n;
    m.dispersion = 0.0f;
    return m;
}

// The albedo that the denoiser's feature buffer records at a hit (Open Image Denoise's: the
// surface's colour apart from light and view, each channel in [0, 1]): the classic model's
// diffuse, specular, mirror and glass colours together, the glTF model's base colour (a metal's
// reflectance at normal incidence, a dielectric's diffuse or transmitted colour), 1 for the
// debug-normal model (its colour is its emission).
GPURT_FN vec3 materialAlbedo(MaterialRecord m) {
#ifdef GPURT_WITH_DEBUG_NORMAL
    if (m.model == GPURT_MODEL_DEBUG_NORMAL) return vec3(1.0f);
#endif
#ifdef GPURT_WITH_GLTF
    if (m.model == GPURT_MODEL_GLTF) return clamp(m.kd, vec3(0.0f), vec3(1.0f));
#endif
    vec3 glass = m.ior > 0.0f ? m.tf : vec3(0.0f);
    return clamp(m.kd + m.ks + m.reflectivity + glass, vec3(0.0f), vec3(1.0f));
}

// The radiance the surface sends along the ray d by itself at shading normal ns (emission).
GPURT_FN vec3 materialEmitted(MaterialRecord m, vec3 ns, vec3 d) {
#ifdef GPURT_WITH_DEBUG_NORMAL
    if (m.model == GPURT_MODEL_DEBUG_NORMAL) return debugNormalEmitted(ns);
#endif
    if (m.model == GPURT_MODEL_UNLIT) return m.kd;
#if defined(__cplusplus) || defined(SCENE_CLEARCOAT)
    if (m.model == GPURT_MODEL_GLTF) return gltfEmitted(m, d);
#endif
    return m.emission;
}

GPURT_FN vec3 materialAmbient(MaterialRecord m) {
#ifdef GPURT_WITH_SELF_SHOWN
    if (materialShowsItself(m)) return vec3(0.0f);
#endif
#ifdef GPURT_WITH_GLTF
    if (m.model == GPURT_MODEL_GLTF) return gltfAmbient(m);
#endif
    return classicAmbient(m);
}

// The ambient term under an environment light whose irradiance at the shading normal is E
// (Whitted; common/environment.h environmentIrradiance): the diffuse reflection of E.
GPURT_FN vec3 materialEnvironmentAmbient(MaterialRecord m, vec3 irradiance) {
#ifdef GPURT_WITH_SELF_SHOWN
    if (materialShowsItself(m)) return vec3(0.0f);
#endif
#ifdef GPURT_WITH_GLTF
    if (m.model == GPURT_MODEL_GLTF) return gltfEnvironmentAmbient(m, irradiance);
#endif
    return classicEnvironmentAmbient(m, irradiance);
}

GPURT_FN vec3 materialLight(MaterialRecord m, vec3 p, vec3 n, vec3 d, vec3 lightPos, vec3 lightColor,
                            float intensity) {
#ifdef GPURT_WITH_SELF_SHOWN
    if (materialShowsItself(m)) return vec3(0.0f);
#endif
#ifdef GPURT_WITH_GLTF
    if (m.model == GPURT_MODEL_GLTF) return gltfLight(m, p, n, d, lightPos, lightColor, intensity);
#endif
    return classicLight(m, p, n, d, lightPos, lightColor, intensity);
}

GPURT_FN bool materialSpawns(MaterialRecord m) {
#ifdef GPURT_WITH_SELF_SHOWN
    if (materialShowsItself(m)) return false;
#endif
#ifdef GPURT_WITH_GLTF
    if (m.model == GPURT_MODEL_GLTF) return gltfSpawns(m);
#endif
    return classicSpawns(m);
}

// Whether a hit may spawn two rays (glass: the ray tree's stacks are needed).
GPURT_FN bool materialSplits(MaterialRecord m) {
#ifdef GPURT_WITH_SELF_SHOWN
    if (materialShowsItself(m)) return false;
#endif
#ifdef GPURT_WITH_GLTF
    if (m.model == GPURT_MODEL_GLTF) return gltfSplits(m);
#endif
    return classicSplits(m);
}

GPURT_FN int materialChildren(MaterialRecord m, vec3 d, vec3 ng, vec3 ns, bool entering, vec3 w,
                              GPURT_OUT(vec3) dirA, GPURT_OUT(vec3) weightA, GPURT_OUT(float) sideA,
                              GPURT_OUT(vec3) dirB, GPURT_OUT(vec3) weightB) {
#ifdef GPURT_WITH_SELF_SHOWN
    if (materialShowsItself(m)) return 0;
#endif
#ifdef GPURT_WITH_GLTF
    if (m.model == GPURT_MODEL_GLTF) return gltfChildren(m, d, ng, ns, w, dirA, weightA, sideA, dirB, weightB);
#endif
    return classicChildren(m, d, ng, ns, entering, w, dirA, weightA, sideA, dirB, weightB);
}

GPURT_FN bool materialLit(MaterialRecord m) {
#ifdef GPURT_WITH_SELF_SHOWN
    if (materialShowsItself(m)) return false;
#endif
#ifdef GPURT_WITH_GLTF
    if (m.model == GPURT_MODEL_GLTF) return gltfLit(m);
#endif
    return classicLit(m);
}

GPURT_FN vec3 materialEval(MaterialRecord m, vec3 n, vec3 d, vec3 wi) {
#ifdef GPURT_WITH_SELF_SHOWN
    if (materialShowsItself(m)) return vec3(0.0f);
#endif
#ifdef GPURT_WITH_GLTF
    if (m.model == GPURT_MODEL_GLTF) return gltfEval(m, n, d, wi);
#endif
    return classicEval(m, n, d, wi);
}

GPURT_FN float materialPdf(MaterialRecord m, vec3 n, vec3 d, vec3 wi) {
#ifdef GPURT_WITH_SELF_SHOWN
    if (materialShowsItself(m)) return 0.0f;
#endif
#ifdef GPURT_WITH_GLTF
    if (m.model == GPURT_MODEL_GLTF) return gltfMaterialPdf(m, n, d, wi);
#endif
    return classicPdf(m, n, d, wi);
}

GPURT_FN bool materialSample(MaterialRecord m, vec3 d, vec3 ng, vec3 ns, bool entering, vec2 u, float lobe,
                             GPURT_OUT(vec3) dir, GPURT_OUT(vec3) factor, GPURT_OUT(float) pdf,
                             GPURT_OUT(float) side) {
#ifdef GPURT_WITH_SELF_SHOWN
    if (materialShowsItself(m)) return false;
#endif
#ifdef GPURT_WITH_GLTF
    if (m.model == GPURT_MODEL_GLTF) return gltfSample(m, d, ng, ns, u, lobe, dir, factor, pdf, side);
#endif
    return classicSample(m, d, ng, ns, entering, u, lobe, dir, factor, pdf, side);
}

// A surface as an integrator meets it (the megakernels' surfaceAt, CpuTracer::surfaceAt): the
// point, the geometric normal facing the ray, the shading normal, whether the ray meets the front
// face, and the material record as the ray meets it (materialFacing).
struct SurfaceHit {
    vec3 p;
    vec3 n;
    vec3 ns;
    bool front;
    MaterialRecord m;
};

#endif
