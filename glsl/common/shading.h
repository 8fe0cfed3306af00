// The geometry and optics of a hit, shared word for word by the GLSL kernels (#include
// "common/shading.h" after "common/raymath.h") and the C++ CPU backend (raytrace/common/RayMath.h
// includes it inside namespace gpurt::raymath), so both backends treat a hit with the same float
// operations: normals, ray offsets, shadow rays, mirror and refracted directions, Fresnel, emitter
// points. Same rules as raymath.h: the common subset of GLSL 4.50 and C++/GLM, no swizzle writes,
// float literals with 'f'. What a material does with light is common/material.h's.
//
// Whitted's rule per hit (Whitted 1980; Christen 2005, eq. 5.1): colour = sum over the rays of the
// pixel's ray tree of weight * (emission + local), local = the material's ambient term plus its
// response to each light in front of the surface and not in shadow; a miss adds weight *
// background. A ray's weight is the product of the mirror reflectivities, Fresnel reflectances and
// transmissions along its branch (materialChildren); the lighting terms use the shading normal
// (shadingNormal). A light behind the surface (n.l <= 0, n facing the ray) counts as shadowed by
// the surface itself and gets no shadow ray.
//
// Units: a white diffuse surface facing a point light of intensity I at distance r has radiance
// I / r^2 (the light's radiant intensity is pi I: Lambert's BRDF kd / pi times pi I / r^2).
// Emitters (area lights, MTL Ke) have radiance Le on both sides; each sample takes one point q of
// all emitters, uniformly by area A, and lights p as a point light at q of intensity
// Le |cos theta_q| A / pi would (emitterIntensity): the Monte Carlo estimate of the irradiance
// integral of Le cos theta_p cos theta_q / r^2 over the emitters, times kd / pi.
#ifndef GPURT_SHADING_H
#define GPURT_SHADING_H

#ifndef GPURT_RAYMATH_H
#error "include common/raymath.h before common/shading.h"
#endif

// Geometric unit normal of the triangle with edges e1 = v1 - v0, e2 = v2 - v0, turned to face
// the incoming ray direction d. The squared length of cross(e1, e2) is quartic in the edges and
// leaves the float range for edges below about 1e-10 or above 1e9: a cross product below 1e-12
// or above 1e12 is first scaled by 2^100 or 2^-100 (exact: the direction is kept). A triangle
// whose cross product is zero in float (collinear vertices) can still pass the hit test by
// rounding; it has no normal and faces the ray.
GPURT_FN vec3 facingNormal(vec3 e1, vec3 e2, vec3 d) {
    vec3 c = cross(e1, e2);
    float m = max(abs(c.x), max(abs(c.y), abs(c.z)));
    if (m == 0.0f) return -d;
    if (m < 1e-12f) c = c * 1.2676506e30f;  // 2^100
    if (m > 1e12f) c = c * 7.8886091e-31f;  // 2^-100
    vec3 n = contractNormalize(c);
    if (dot(n, d) > 0.0f) n = -n;
    return n;
}

// The vertex colour at barycentrics (u, v) of a triangle whose corners have c0, c1, c2 (linear
// RGB): it multiplies the diffuse colour at the hit (the kernels: shading.glsl fetchMaterialRecord;
// C++: raytrace/materials/MaterialRecord.cpp materialRecord). Written from c0 along the edges, so that equal
// corners give exactly their colour (white changes nothing, bit for bit).
GPURT_FN vec3 interpolateVertexColor(vec3 c0, vec3 c1, vec3 c2, float u, float v) {
    return c0 + (c1 - c0) * u + (c2 - c0) * v;
}

// The shading normal at barycentrics (u, v) (weights of vertices 1 and 2) from the vertex normals
// n0, n1, n2, turned to the side of the facing geometric normal ng; ng itself when the triangle
// has no vertex normals (all zero) or they cancel. Light and mirror directions use it; ray offsets,
// "light in front" tests and the normal AOV keep ng.
GPURT_FN vec3 shadingNormal(vec3 n0, vec3 n1, vec3 n2, float u, float v, vec3 ng) {
    vec3 s = n0 * (1.0f - u - v) + n1 * u + n2 * v;
    if (!(dot(s, s) > 1e-12f)) return ng;
    s = contractNormalize(s);
    return dot(s, ng) < 0.0f ? -s : s;
}

// Mirror direction of i about n; the formula of GLSL's reflect(), spelled out so that both
// languages evaluate the same operations.
GPURT_FN vec3 mirrorDirection(vec3 i, vec3 n) { return i - 2.0f * dot(n, i) * n; }

// Whether the ray d meets the side of the triangle (edges e1, e2) its winding faces: the outside
// of a dielectric's closed surface.
GPURT_FN bool frontFace(vec3 e1, vec3 e2, vec3 d) { return dot(cross(e1, e2), d) < 0.0f; }

// The normal n (unit, facing as ng) turned towards the geometric normal ng just far enough that
// the mirror image of wo (unit, towards the viewer, in front of ng) about it rises t =
// min(0.9 ng.wo, 0.01) above the surface, as Cycles' ensure_valid_reflection does with the normals
// of its normal map node and coats: a normal bent away from the viewer would otherwise mirror
// everything into the surface, where no light comes from. n itself where its mirror already rises
// t. The new normal lies in the plane of n and ng, on n's side, and is the half vector of wo and
// that lifted mirror r, which keeps wo's component across the plane (negated, as any mirror about
// a normal in the plane does) and takes the rest of its length along n's side of the plane.
GPURT_FN vec3 validReflectionNormal(vec3 n, vec3 ng, vec3 wo) {
    float cosO = dot(ng, wo);
    float t = min(0.9f * cosO, 0.01f);
    if (!(cosO > 0.0f) || dot(mirrorDirection(-wo, n), ng) >= t) return n;
    vec3 x = n - ng * dot(n, ng);
    float xx = dot(x, x);
    if (!(xx > 1e-24f)) return ng;
    x = x / sqrt(xx);
    vec3 y = cross(ng, x);
    float oy = dot(wo, y);
    vec3 r = x * sqrt(max(0.0f, 1.0f - oy * oy - t * t)) - y * oy + ng * t;
    return contractNormalize(wo + r);
}

// The tangent-space normal `texel` (a normal map's linear value, its x and y times `scale`) in the
// frame (t, b, n) of the front side's unit normal n, as the shading normal facing as ng for a ray
// along d (flipped for a back hit, `front` false), turned so that the mirror of -d about it stays
// above the surface (validReflectionNormal); ns where it is degenerate or would face away from the
// ray.
GPURT_FN vec3 bentNormal(vec3 ns, vec3 ng, vec3 d, bool front, vec3 n, vec3 t, vec3 b, vec3 texel, float scale) {
    vec3 m = texel * 2.0f - vec3(1.0f);
    vec3 bent = t * (m.x * scale) + b * (m.y * scale) + n * m.z;
    float bb = dot(bent, bent);
    if (!(bb > 1e-24f)) return ns;
    bent = bent / sqrt(bb);
    if (!front) bent = -bent;
    return dot(bent, ng) > 0.0f ? validReflectionNormal(bent, ng, -contractNormalize(d)) : ns;
}

// The tangent frame (t, b) about the front side's unit normal n made per triangle from its edges
// e1, e2 and their texture coordinate differences dt1, dt2 (image coordinates, v down as glTF's):
// T along increasing u, made orthogonal to n, B = cross(N, T) times the handedness (B points along
// decreasing v, image up, unless the mapping is mirrored). False where it is degenerate (no
// texture coordinates).
GPURT_FN bool generatedTangentFrame(vec3 n, vec3 e1, vec3 e2, vec2 dt1, vec2 dt2, GPURT_OUT(vec3) t,
                                    GPURT_OUT(vec3) b) {
    t = vec3(0.0f);
    b = vec3(0.0f);
    float det = dt1.x * dt2.y - dt2.x * dt1.y;
    if (!(abs(det) > 1e-12f)) return false;
    vec3 dpdu = (e1 * dt2.y - e2 * dt1.y) / det;
    vec3 dpdv = (e2 * dt1.x - e1 * dt2.x) / det;
    t = dpdu - n * dot(n, dpdu);
    float tt = dot(t, t);
    if (!(tt > 1e-24f)) return false;
    t = t / sqrt(tt);
    b = cross(n, t);
    if (dot(b, dpdv) > 0.0f) b = -b;
    return true;
}

// The tangent frame (t, b) about the front side's unit normal n from a given vertex tangent (glTF
// TANGENT, interpolated): T the tangent made orthogonal to n (Gram-Schmidt), B = cross(N, T) times
// the handedness (glTF: bitangent = cross(normal, tangent.xyz) * tangent.w; w below 0 is -1,
// anything else +1, so an interpolated w of 0 between corners of both hands is +1). False for a
// tangent of zero length (a triangle without TANGENT, or a file's zero vector), not finite (NaN or
// infinite), or parallel to the normal at this hit (less than 1e-3 of its length left after
// Gram-Schmidt): the hit takes the frame generated per triangle then (generatedTangentFrame).
GPURT_FN bool givenTangentFrame(vec3 n, vec4 tangent, GPURT_OUT(vec3) t, GPURT_OUT(vec3) b) {
    vec3 given = vec3(tangent.x, tangent.y, tangent.z);
    float gg = dot(given, given);
    t = given - n * dot(n, given);
    b = vec3(0.0f);
    float tt = dot(t, t);
    if (!(gg > 1e-24f) || !(tt > 1e-6f * gg)) return false;
    t = t / sqrt(tt);
    b = cross(n, t) * (tangent.w < 0.0f ? -1.0f : 1.0f);
    return true;
}

// The shading normal ns (facing as ng) bent by a tangent-space normal map (glTF normalTexture):
// `texel` the map's linear value at the hit, its x and y times `scale`, in the frame generated per
// triangle (generatedTangentFrame), for the ray along d. The map bends the front side's normal and
// a ray that sees the triangle's back (frontFace false) sees it flipped. Where the frame or the
// result is degenerate (no texture coordinates, a normal facing away), ns stays.
GPURT_FN vec3 normalMapped(vec3 ns, vec3 ng, vec3 d, vec3 e1, vec3 e2, vec2 dt1, vec2 dt2, vec3 texel, float scale) {
    bool front = frontFace(e1, e2, d);
    vec3 n = front ? ns : -ns;
    vec3 t, b;
    if (!generatedTangentFrame(n, e1, e2, dt1, dt2, t, b)) return ns;
    return bentNormal(ns, ng, d, front, n, t, b, texel, scale);
}

// The vertex tangent at barycentrics (u, v) from the corners' t0, t1, t2 (glTF TANGENT: xyz the
// tangent, w the handedness +-1; all zero for a triangle without), interpolated as the vertex
// normals are (shadingNormal).
GPURT_FN vec4 interpolateTangent(vec4 t0, vec4 t1, vec4 t2, float u, float v) {
    return t0 * (1.0f - u - v) + t1 * u + t2 * v;
}

// normalMapped in the frame of a given vertex tangent (givenTangentFrame), or where it has none,
// the generated one (normalMapped).
GPURT_FN vec3 normalMappedTangent(vec3 ns, vec3 ng, vec3 d, vec4 tangent, vec3 e1, vec3 e2, vec2 dt1, vec2 dt2,
                                  vec3 texel, float scale) {
    bool front = frontFace(e1, e2, d);
    vec3 n = front ? ns : -ns;
    vec3 t, b;
    if (!givenTangentFrame(n, tangent, t, b)) return normalMapped(ns, ng, d, e1, e2, dt1, dt2, texel, scale);
    return bentNormal(ns, ng, d, front, n, t, b, texel, scale);
}

// KHR_materials_anisotropy's direction in scene space at a hit (the record's anisotropyDirection):
// `direction` (tangent space) in the frame of the vertex tangent where there is one
// (`hasTangent`, givenTangentFrame), else in the one generated from the texture coordinates, else
// (no texture coordinates either) in the frame whose tangent runs around the scene's up axis +y
// (T = +y x n: Blender's radial tangent), about the front side's shading normal n; zero where n is
// along the axis there.
GPURT_FN vec3 anisotropyFrameDirection(vec3 n, bool hasTangent, vec4 tangent, vec3 e1, vec3 e2, vec2 dt1, vec2 dt2,
                                       vec2 direction) {
    vec3 t, b;
    bool framed = hasTangent && givenTangentFrame(n, tangent, t, b);
    if (!framed) framed = generatedTangentFrame(n, e1, e2, dt1, dt2, t, b);
    if (!framed) {
        t = cross(vec3(0.0f, 1.0f, 0.0f), n);
        float tt = dot(t, t);
        if (!(tt > 1e-12f)) return vec3(0.0f);
        t = t / sqrt(tt);
        b = cross(n, t);
    }
    return t * direction.x + b * direction.y;
}

// Origin of a shadow or reflected ray leaving hit point p: off the surface along its facing
// normal by eps (UniformGrid::rayOffset, 1e-4 of the grid box's largest extent).
GPURT_FN vec3 offsetOrigin(vec3 p, vec3 n, float eps) { return p + n * eps; }

// Whether the light at lightPos is on the side of the surface that n faces.
GPURT_FN bool lightInFront(vec3 p, vec3 n, vec3 lightPos) {
    return dot(n, contractNormalize(lightPos - p)) > 0.0f;
}

// Punctual lights (CONTRACT.md, "Lights"; Scene.h Light): point, spot and directional, in the
// units above (a directional light of intensity I gives a white diffuse surface facing it the
// radiance I). Each lights a hit p as the point light punctualAsPoint makes for p, so that every
// material answers all kinds with its one point-light function.
#define GPURT_LIGHT_POINT 0
#define GPURT_LIGHT_SPOT 1
#define GPURT_LIGHT_DIRECTIONAL 2

struct PunctualLight {
    int kind;
    vec3 position;   // point, spot
    vec3 direction;  // spot, directional: the way the light travels (unit)
    vec3 color;
    float intensity;
    vec2 cone;    // spot: (scale, offset) of the cone's falloff (spotCone)
    float range;  // point, spot: 0 unlimited
};

// A spot's falloff between the cone's inner and outer angles as the KHR_lights_punctual
// specification's reference implementation: saturate(cos * scale + offset)^2 with scale =
// 1 / max(0.001, cos inner - cos outer) and offset = -cos outer * scale.
GPURT_FN vec2 spotCone(float innerAngle, float outerAngle) {
    float scale = 1.0f / max(0.001f, cos(innerAngle) - cos(outerAngle));
    return vec2(scale, -cos(outerAngle) * scale);
}

// The point light that lights p as light L does: its position (for a directional light one unit
// from p against its direction, so that intensity / distance^2 is its own intensity) and its
// intensity at p (a spot's dimmed by its cone; KHR_lights_punctual's range window
// clamp(1 - (d / range)^4, 0, 1) for a point or spot light with a range). False where L does not
// light p at all.
// Without SCENE_LIGHT_KINDS (SceneTextures::bind: every light of the scene a point light without a
// range) only that case is compiled: llvmpipe runs both sides of a branch.
GPURT_FN bool punctualAsPoint(PunctualLight L, vec3 p, GPURT_OUT(vec3) position, GPURT_OUT(float) intensity) {
#if !defined(__cplusplus) && !defined(SCENE_LIGHT_KINDS)
    position = L.position;
    intensity = L.intensity;
    return intensity > 0.0f;
#else
    if (L.kind == GPURT_LIGHT_DIRECTIONAL) {
        position = p - L.direction;
        intensity = L.intensity;
        return intensity > 0.0f;
    }
    position = L.position;
    intensity = L.intensity;
    vec3 toP = p - L.position;
    if (L.kind == GPURT_LIGHT_SPOT) {
        float a = clamp(dot(L.direction, contractNormalize(toP)) * L.cone.x + L.cone.y, 0.0f, 1.0f);
        intensity = intensity * (a * a);
    }
    if (L.range > 0.0f) {
        float r = dot(toP, toP) / (L.range * L.range);
        intensity = intensity * clamp(1.0f - r * r, 0.0f, 1.0f);
    }
    return intensity > 0.0f;
#endif
}

// The shadow ray from a hit towards a light: it is occluded if the traversal finds a hit with
// 0 < t < tLimit.
GPURT_FN void shadowRay(vec3 p, vec3 n, float eps, vec3 lightPos, GPURT_OUT(vec3) origin,
                        GPURT_OUT(vec3) dir, GPURT_OUT(float) tLimit) {
    origin = offsetOrigin(p, n, eps);
    vec3 toLight = lightPos - origin;
    dir = contractNormalize(toLight);
    tLimit = sqrt(dot(toLight, toLight));
}

// The shadow ray from a hit towards light L, whose point light for p is at `position`
// (punctualAsPoint): shadowRay's, or for a directional light the light's way back, unlimited.
GPURT_FN void punctualShadowRay(PunctualLight L, vec3 p, vec3 n, float eps, vec3 position, GPURT_OUT(vec3) origin,
                                GPURT_OUT(vec3) dir, GPURT_OUT(float) tLimit) {
    shadowRay(p, n, eps, position, origin, dir, tLimit);
#if defined(__cplusplus) || defined(SCENE_LIGHT_KINDS)
    if (L.kind == GPURT_LIGHT_DIRECTIONAL) {
        dir = -L.direction;
        tLimit = GPURT_FAR;
    }
#endif
}

// Direction of the mirror ray after a hit (normalised again, as the reflected vector drifts).
GPURT_FN vec3 reflectedDirection(vec3 d, vec3 n) {
    return contractNormalize(mirrorDirection(d, n));
}

// The mirror ray about the shading normal ns, or about the geometric normal ng where the former
// would point into the surface (a smooth normal far from the facet's, at grazing angles).
GPURT_FN vec3 shadingReflection(vec3 d, vec3 ns, vec3 ng) {
    vec3 r = reflectedDirection(d, ns);
    return dot(r, ng) > 0.0f ? r : reflectedDirection(d, ng);
}

// The exact Fresnel reflectance of unpolarised light at a smooth dielectric boundary, for the
// cosine cosI of the angle of incidence and eta = n_transmitted / n_incident: the mean of the
// s- and p-polarised reflectances (Born & Wolf; pbrt-v3 FrDielectric). 1 beyond the critical
// angle (total internal reflection).
GPURT_FN float fresnelDielectric(float cosI, float eta) {
    float sin2T = (1.0f - cosI * cosI) / (eta * eta);
    if (sin2T >= 1.0f) return 1.0f;
    float cosT = sqrt(1.0f - sin2T);
    float rs = (cosI - eta * cosT) / (cosI + eta * cosT);
    float rp = (eta * cosI - cosT) / (eta * cosI + cosT);
    return 0.5f * (rs * rs + rp * rp);
}

// The refracted direction of d through a boundary with normal n facing d (cosI = -dot(d, n))
// by Snell's law, eta = n_transmitted / n_incident; the caller has excluded total internal
// reflection (fresnelDielectric < 1).
GPURT_FN vec3 refractedDirection(vec3 d, vec3 n, float eta, float cosI) {
    float sin2T = (1.0f - cosI * cosI) / (eta * eta);
    float cosT = sqrt(max(0.0f, 1.0f - sin2T));
    return contractNormalize(d / eta + (cosI / eta - cosT) * n);
}

// The point at (u.x, u.y) in [0, 1)^2 of the triangle v0 + a e1 + b e2, uniform by area
// (Shirley 1997: a = sqrt(u.x) (1 - u.y), b = sqrt(u.x) u.y).
GPURT_FN vec3 emitterPoint(vec3 v0, vec3 e1, vec3 e2, vec2 u) {
    float su = sqrt(u.x);
    return v0 + e1 * (su * (1.0f - u.y)) + e2 * (su * u.y);
}

// u in [lo, hi) stretched back to [0, 1): after choosing the emitter by its share [lo, hi) of
// the emitters' area, the same number picks the point, still stratified.
GPURT_FN float remapToUnit(float u, float lo, float hi) {
    return min((u - lo) / (hi - lo), 0.99999994f);
}

// The shadow ray from a hit towards the emitter point q: as shadowRay, ending rayOffset before
// q so that the emitter's own triangle does not block it.
GPURT_FN void emitterShadowRay(vec3 p, vec3 n, float eps, vec3 q, GPURT_OUT(vec3) origin,
                               GPURT_OUT(vec3) dir, GPURT_OUT(float) tLimit) {
    shadowRay(p, n, eps, q, origin, dir, tLimit);
    tLimit = max(tLimit - eps, 0.0f);
}

// The intensity of the point light that stands for the emitter point q (edges e1, e2 of its
// triangle) seen from p, with totalArea the area of all emitters (see the units above).
GPURT_FN float emitterIntensity(vec3 p, vec3 q, vec3 e1, vec3 e2, float totalArea) {
    vec3 l = contractNormalize(q - p);
    vec3 nq = facingNormal(e1, e2, l);
    return abs(dot(nq, l)) * totalArea * 0.31830988f;  // 1 / pi
}

#define GPURT_PI 3.14159265f
#define GPURT_INV_PI 0.31830988f
GPURT_FN float maxChannel(vec3 c) { return max(c.x, max(c.y, c.z)); }

// Two unit vectors t, b that make (t, b, a) a right-handed orthonormal basis about the unit axis
// a: the branchless basis of Duff et al. 2017 ("Building an Orthonormal Basis, Revisited").
GPURT_FN void orthonormalBasis(vec3 a, GPURT_OUT(vec3) t, GPURT_OUT(vec3) b) {
    float s = a.z >= 0.0f ? 1.0f : -1.0f;
    float k = -1.0f / (s + a.z);
    float m = a.x * a.y * k;
    t = vec3(1.0f + s * a.x * a.x * k, s * m, -s * a.x);
    b = vec3(m, s + a.y * a.y * k, -a.y);
}

// The unit vector at angle acos(cosTheta) from the unit axis a, at azimuth 2 pi u about it
// (orthonormalBasis).
GPURT_FN vec3 directionAbout(vec3 a, float cosTheta, float u) {
    vec3 t, b;
    orthonormalBasis(a, t, b);
    float sinTheta = sqrt(max(0.0f, 1.0f - cosTheta * cosTheta));
    float phi = 2.0f * GPURT_PI * u;
    return contractNormalize(t * (sinTheta * cos(phi)) + b * (sinTheta * sin(phi)) + a * cosTheta);
}

#endif
