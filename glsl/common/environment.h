// The environment light (CONTRACT.md, "Environment light and the default light"), shared word for
// word by the kernels (glsl/scene/scene.glsl, which fetches the map's texels and searches its
// distribution) and the CPU backend (src/raytrace/lights/EnvironmentTable), after common/shading.h and
// common/texture.h. Same rules as raymath.h.
//
// Direction d (unit, scene coordinates, +Y up) reads the map at u = 0.5 + atan2(d.x, -d.z) / (2 pi),
// v = acos(d.y) / pi (v = 0 the top row), filtered bilinearly (repeating across u, clamped at the
// poles). The map is turned by the rotation a about +Y, positive counter-clockwise seen from
// above: what the unturned map shows in direction m the scene sees in direction R_y(a) m, so a
// direction d reads the map at R_y(-a) d. `rotation` is (cos a, sin a).
//
// Importance sampling: texel (i, j) is drawn with probability proportional to its luminance (the
// largest of it and its 8 neighbours, which the bilinear filter blends into it) times sin(theta)
// at its row's centre (EnvironmentTable: the marginal distribution of the rows, the
// conditional one of each row's columns), uniformly within it in (u, v); its density in (u, v) is
// the texel's `uvPdf` (W H times its probability), and in solid angle uvPdf / (2 pi^2 sin(theta)).
//
// The ambient term of Whitted's diffuse surfaces is the environment's irradiance at the shading
// normal from its first 9 spherical harmonics (Ramamoorthi & Hanrahan 2001, "An Efficient
// Representation for Irradiance Environment Maps", eq. 13), exact for an environment of degree 2
// or less (a constant, a + b d.y).
#ifndef GPURT_ENVIRONMENT_H
#define GPURT_ENVIRONMENT_H

#ifndef GPURT_TEXTURE_H
#error "include common/texture.h before common/environment.h"
#endif

// The sample dimension of the environment's direction at hit depth b: GPURT_DIM_ENVIRONMENT + b.
#define GPURT_DIM_ENVIRONMENT 3072u

// The map's (u, v) of the scene direction d.
GPURT_FN vec2 environmentUv(vec3 d, vec2 rotation) {
    float x = rotation.x * d.x - rotation.y * d.z;
    float z = rotation.y * d.x + rotation.x * d.z;
    float u = x == 0.0f && z == 0.0f ? 0.5f : 0.5f + atan(x, -z) * (0.5f * GPURT_INV_PI);
    float v = acos(min(max(d.y, -1.0f), 1.0f)) * GPURT_INV_PI;
    return vec2(u, v);
}

// The scene direction of the map's (u, v) (environmentUv's inverse).
GPURT_FN vec3 environmentDirection(vec2 uv, vec2 rotation) {
    float phi = (uv.x - 0.5f) * (2.0f * GPURT_PI);
    float theta = uv.y * GPURT_PI;
    float s = sin(theta);
    vec3 m = vec3(s * sin(phi), cos(theta), -s * cos(phi));
    return vec3(rotation.x * m.x + rotation.y * m.z, m.y, rotation.x * m.z - rotation.y * m.x);
}

// The texel of a w x h map that contains (u, v).
GPURT_FN ivec2 environmentTexel(vec2 uv, int w, int h) {
    int i = int(uv.x * float(w));
    int j = int(uv.y * float(h));
    return ivec2(min(max(i, 0), w - 1), min(max(j, 0), h - 1));
}

// The solid-angle pdf of a direction at v whose texel has density uvPdf in (u, v).
GPURT_FN float environmentPdf(float uvPdf, float v) {
    float s = sin(v * GPURT_PI);
    return s > 0.0f ? uvPdf / (2.0f * GPURT_PI * GPURT_PI * s) : 0.0f;
}

// Rec. 709 luminance: what the importance sampling follows.
GPURT_FN float environmentLuminance(vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// The irradiance at unit normal n of the environment whose 9 spherical-harmonic coefficients (in
// the order L00, L1-1 (y), L10 (z), L11 (x), L2-2 (xy), L2-1 (yz), L20 (3z^2 - 1), L21 (xz),
// L22 (x^2 - y^2), in scene axes) are c0..c8.
GPURT_FN vec3 environmentIrradiance(vec3 n, vec3 c0, vec3 c1, vec3 c2, vec3 c3, vec3 c4, vec3 c5, vec3 c6, vec3 c7,
                                    vec3 c8) {
    float x = n.x, y = n.y, z = n.z;
    vec3 e = 0.429043f * c8 * (x * x - y * y) + 0.743125f * c6 * (z * z) + 0.886227f * c0 - 0.247708f * c6 +
             2.0f * 0.429043f * (c4 * (x * y) + c7 * (x * z) + c5 * (y * z)) +
             2.0f * 0.511664f * (c3 * x + c1 * y + c2 * z);
    return max(e, vec3(0.0f));
}

#endif
