// The kernels' access to the environment light (common/environment.h; the textures of
// SceneTextures, built by raytrace/EnvironmentTable): its radiance in a direction, the pdf with
// which next-event estimation samples a direction, the sampling itself (a binary search of the
// rows' marginal distribution, then of the row's columns, as scene.glsl pickEmitter searches the
// emitter table), and the irradiance of its spherical harmonics (Whitted's ambient term).
// EnvironmentTable.cpp does the same in C++.
#include "../common/environment.h"

uniform sampler2D environmentMap;          // W x H: (radiance x strength, uvPdf), top row first
uniform sampler2D environmentMarginal;     // H x 1: the rows' cumulative distribution
uniform sampler2D environmentConditional;  // W x H: each row's columns' cumulative distribution
uniform sampler2D environmentHarmonics;    // 9 x 1: the spherical-harmonic coefficients
uniform vec2 environmentRotation;          // (cos, sin) of the rotation about +Y
uniform ivec2 environmentSize;             // (W, H)

// The filtered radiance the environment sends towards -d (what a ray along d that leaves sees).
vec3 environmentRadiance(vec3 d) {
    vec2 uv = environmentUv(d, environmentRotation);
    ivec2 columns, rows;
    vec2 f;
    bilinearFootprint(uv, environmentSize.x, environmentSize.y, GPURT_WRAP_REPEAT, GPURT_WRAP_CLAMP, columns, rows, f);
    return bilinearBlend(texelFetch(environmentMap, ivec2(columns.x, rows.x), 0).xyz,
                         texelFetch(environmentMap, ivec2(columns.y, rows.x), 0).xyz,
                         texelFetch(environmentMap, ivec2(columns.x, rows.y), 0).xyz,
                         texelFetch(environmentMap, ivec2(columns.y, rows.y), 0).xyz, f);
}

// The solid-angle pdf with which sampleEnvironment draws direction d.
float environmentLightPdf(vec3 d) {
    vec2 uv = environmentUv(d, environmentRotation);
    return environmentPdf(texelFetch(environmentMap, environmentTexel(uv, environmentSize.x, environmentSize.y), 0).w, uv.y);
}

// The first k in [0, n) with u < cdf[k] of one row of a cumulative-distribution texture.
int searchDistribution(sampler2D cdf, int row, int n, float u) {
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (u < texelFetch(cdf, ivec2(mid, row), 0).x) hi = mid;
        else lo = mid + 1;
    }
    return lo;
}

// A direction drawn for the random pair u by the map's luminance x sin(theta), and its pdf.
bool sampleEnvironment(vec2 u, out vec3 dir, out float pdf) {
    int w = environmentSize.x, h = environmentSize.y;
    int j = searchDistribution(environmentMarginal, 0, h, u.y);
    float rowLo = j == 0 ? 0.0f : texelFetch(environmentMarginal, ivec2(j - 1, 0), 0).x;
    float rowHi = texelFetch(environmentMarginal, ivec2(j, 0), 0).x;
    int i = searchDistribution(environmentConditional, j, w, u.x);
    float colLo = i == 0 ? 0.0f : texelFetch(environmentConditional, ivec2(i - 1, j), 0).x;
    float colHi = texelFetch(environmentConditional, ivec2(i, j), 0).x;
    vec2 uv = vec2((float(i) + remapToUnit(u.x, colLo, colHi)) / float(w),
                   (float(j) + remapToUnit(u.y, rowLo, rowHi)) / float(h));
    dir = environmentDirection(uv, environmentRotation);
    pdf = environmentPdf(texelFetch(environmentMap, ivec2(i, j), 0).w, uv.y);
    return pdf > 0.0f;
}

// The environment's irradiance at unit normal n from its spherical harmonics.
vec3 environmentAmbient(vec3 n) {
    return environmentIrradiance(n, texelFetch(environmentHarmonics, ivec2(0, 0), 0).xyz,
                                 texelFetch(environmentHarmonics, ivec2(1, 0), 0).xyz,
                                 texelFetch(environmentHarmonics, ivec2(2, 0), 0).xyz,
                                 texelFetch(environmentHarmonics, ivec2(3, 0), 0).xyz,
                                 texelFetch(environmentHarmonics, ivec2(4, 0), 0).xyz,
                                 texelFetch(environmentHarmonics, ivec2(5, 0), 0).xyz,
                                 texelFetch(environmentHarmonics, ivec2(6, 0), 0).xyz,
                                 texelFetch(environmentHarmonics, ivec2(7, 0), 0).xyz,
                                 texelFetch(environmentHarmonics, ivec2(8, 0), 0).xyz);
}
