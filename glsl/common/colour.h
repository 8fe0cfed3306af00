// From linear radiance to the display: exposure, a tone map, the sRGB transfer function (CONTRACT.md,
// "Colour, sampling and materials"). Shared word for word by C++ (src/image/Colour.h, which
// develops the PNG of both backends) and GLSL (for kernels that present an image), after
// common/raymath.h. Same rules as raymath.h.
#ifndef GPURT_COLOUR_H
#define GPURT_COLOUR_H

#ifndef GPURT_RAYMATH_H
#error "include common/raymath.h before common/colour.h"
#endif

#define GPURT_TONEMAP_CLAMP 0     // scene-linear clipped at 1 (the old behaviour)
#define GPURT_TONEMAP_REINHARD 1  // x / (1 + x) per channel (Reinhard et al. 2002, the simple form)
#define GPURT_TONEMAP_ACES 2      // filmic: Narkowicz's fit of the ACES RRT + sRGB ODT (default)

// Narkowicz 2015, "ACES Filmic Tone Mapping Curve": a rational fit of the ACES reference
// rendering and sRGB output transforms. Unlike the usual shader snippet the input is not
// pre-scaled by 0.6: here 1.0 (a white diffuse surface facing a unit light) maps to 0.80, mid
// grey 0.18 to 0.28, and the curve reaches 1 only at 7.2, so highlights roll off instead of
// clipping.
GPURT_FN vec3 acesFilmic(vec3 x) {
    vec3 mapped = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
    return clamp(mapped, vec3(0.0f), vec3(1.0f));
}

// Display-linear colour in [0, 1] from linear radiance: times exposureScale (2^EV), then the
// tone map. Negative input gives 0 (the tracer produces no negative or NaN radiance; the C++
// side maps NaN to 0 before, as min and max leave NaN to the implementation).
GPURT_FN vec3 toneMap(vec3 linear, float exposureScale, int mode) {
    vec3 x = max(linear * exposureScale, vec3(0.0f));
    if (mode == GPURT_TONEMAP_ACES) return acesFilmic(x);
    if (mode == GPURT_TONEMAP_REINHARD) return x / (vec3(1.0f) + x);
    return min(x, vec3(1.0f));
}

// The sRGB transfer function (IEC 61966-2-1) of one display-linear value in [0, 1].
GPURT_FN float srgbEncode(float c) {
    return c <= 0.0031308f ? 12.92f * c : 1.055f * pow(c, 1.0f / 2.4f) - 0.055f;
}

#endif
