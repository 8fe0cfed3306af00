// The denoiser (render --denoise, gpurt denoise, the viewer), shared word for word by its kernels
// (glsl/denoise/) and the cpu backend (src/raytrace/denoise/DenoiseCpu.cpp), after raymath.h.
// Same rules as raymath.h.
//
// An edge-avoiding a-trous wavelet filter with variance-driven weights (Dammertz et al. 2010, the
// spatial filter of SVGF, Schied et al. 2017) over the colour with its albedo divided out:
//  1. Demodulate: the irradiance e = colour / albedo' (albedo' = the albedo, at least
//     GPURT_DENOISE_ALBEDO_MIN a channel, so that remodulating undoes it exactly) and the variance
//     of its luminance from the colour mean's variance (the variance AOV). A pixel with a value
//     that is not finite is refused: it weighs nothing, and its own value comes from its
//     neighbours.
//  2. denoiseIterations iterations i = 0, 1, ... of a 5 x 5 B3-spline kernel with holes of
//     2^i pixels; each tap weighs by how alike its features are to the centre's: the shading
//     normal and albedo (means over the samples, so that a pixel half covered by an edge takes
//     part as half of each), the depth (relative), and the irradiance's luminance against the
//     centre's standard deviation (prefiltered over 3 x 3). The variance falls with each
//     iteration as the weighted mean's does, so that edges in the light stay sharp.
//  3. Remodulate: colour = irradiance * albedo'.
// For denoiseIteration, the includer defines how the images are read at pixel q (an ivec2 inside
// the image):
//   GPURT_DENOISE_PARAMS     leading parameters of denoiseIteration (empty in GLSL)
//   GPURT_DENOISE_SIGNAL(q)  vec4: (irradiance, the variance of its luminance; < 0: refused)
//   GPURT_DENOISE_ALBEDO(q)  vec3: the albedo
//   GPURT_DENOISE_NORMAL(q)  vec4: (shading normal, depth; a depth >= GPURT_FAR or +inf: no hit)
// and for denoiseVarianceEstimate:
//   GPURT_DENOISE_COLOR(q)   vec3: the colour mean
#ifndef GPURT_DENOISE_H
#define GPURT_DENOISE_H

#define GPURT_DENOISE_ALBEDO_MIN 0.01f
// The weights' scales: the luminance difference in the centre's standard deviations (SVGF's
// sigma_l = 4), the squared differences of the normals (16 |n_p - n_q|^2 = 32 (1 - cos) for unit
// normals: about SVGF's cos^32) and of the albedos, and the relative depth difference a pixel of
// offset may show. Chosen on the Cornell blocks and the bunny under the sky at 16 samples against
// 4096 (docs/PERFORMANCE.md, "The denoiser").
#define GPURT_DENOISE_SIGMA_LUMINANCE 4.0f
#define GPURT_DENOISE_NORMAL_SHARPNESS 16.0f
#define GPURT_DENOISE_ALBEDO_SHARPNESS 8.0f
#define GPURT_DENOISE_DEPTH_SLOPE 0.01f

// The iterations for an image whose smaller side is `side` pixels: 3 up to 255 pixels, and one
// more each time the side doubles, so that their reach (2 (2^n - 1) pixels) stays about an eighth
// of the image as its detail grows in pixels with it. Measured at 16 samples a pixel
// (docs/PERFORMANCE.md, "The denoiser"): at 128 x 128, 3 iterations gave less error than 2, 4, 5
// or 6 on the Cornell blocks and than 4 to 6 on the bunny; at 256 x 256, 4 gave the Cornell blocks
// 0.74x the error of 3, the bunny and the textured spheres 1.06-1.08x.
GPURT_FN int denoiseIterations(int side) {
    int n = 3;
    for (int s = side; s >= 256; s = s / 2) n = n + 1;
    return n;
}

GPURT_FN float denoiseLuminance(vec3 c) { return dot(c, vec3(0.2126f, 0.7152f, 0.0722f)); }

GPURT_FN bool denoiseFinite(vec3 v) { return !(any(isnan(v)) || any(isinf(v))); }

// The albedo that divides the colour, and multiplies the irradiance back.
GPURT_FN vec3 denoiseAlbedoFloor(vec3 albedo) {
    return denoiseFinite(albedo) ? max(albedo, vec3(GPURT_DENOISE_ALBEDO_MIN)) : vec3(1.0f);
}

// Step 1 for a pixel of colour mean c, its variance v (per channel) and albedo a.
GPURT_FN vec4 denoiseDemodulate(vec3 c, vec3 v, vec3 a) {
    if (!denoiseFinite(c) || !denoiseFinite(v) || !denoiseFinite(a)) return vec4(0.0f, 0.0f, 0.0f, -1.0f);
    vec3 floorA = denoiseAlbedoFloor(a);
    vec3 ve = max(v, vec3(0.0f)) / (floorA * floorA);
    vec3 k = vec3(0.2126f, 0.7152f, 0.0722f);
    return vec4(c / floorA, dot(ve, k * k));
}

// Step 3: the colour of a filtered signal s at albedo a.
GPURT_FN vec3 denoiseRemodulate(vec4 s, vec3 a) { return vec3(s.x, s.y, s.z) * denoiseAlbedoFloor(a); }

// The B3-spline's taps (1, 4, 6, 4, 1) / 16 at offset k in -2..2.
GPURT_FN float atrousTap(int k) { return k == 0 ? 0.375f : (k == 1 || k == -1) ? 0.25f : 0.0625f; }

// A depth as a finite number (a miss: GPURT_FAR).
GPURT_FN float denoiseDepth(float z) { return isnan(z) ? GPURT_FAR : min(z, GPURT_FAR); }

// How much the features of q (albedo aQ, normal and depth nQ) count against the centre's, at an
// offset of `pixels`.
GPURT_FN float denoiseFeatureDistance(vec3 aP, vec4 nP, vec3 aQ, vec4 nQ, float pixels) {
    vec3 dn = vec3(nP.x, nP.y, nP.z) - vec3(nQ.x, nQ.y, nQ.z);
    vec3 da = aP - aQ;
    float zP = denoiseDepth(nP.w), zQ = denoiseDepth(nQ.w);
    float dz = abs(zP - zQ) / max(max(zP, zQ), 1e-6f);
    return GPURT_DENOISE_NORMAL_SHARPNESS * dot(dn, dn) + GPURT_DENOISE_ALBEDO_SHARPNESS * dot(da, da) +
           dz / (GPURT_DENOISE_DEPTH_SLOPE * (pixels + 1.0f));
}

#ifdef GPURT_DENOISE_COLOR
// The variance of pixel p's mean where it is unknown (0 in every channel: one sample, or no
// variance image): the sample variance of the finite colours of its 3 x 3 neighbourhood, per
// channel, as if each were one sample of the pixel.
GPURT_FN vec3 denoiseVarianceEstimate(GPURT_DENOISE_PARAMS ivec2 p, ivec2 size) {
    vec3 sum = vec3(0.0f);
    vec3 squares = vec3(0.0f);
    float n = 0.0f;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = p + ivec2(dx, dy);
            if (q.x < 0 || q.y < 0 || q.x >= size.x || q.y >= size.y) continue;
            vec3 c = GPURT_DENOISE_COLOR(q);
            if (!denoiseFinite(c)) continue;
            sum = sum + c;
            squares = squares + c * c;
            n = n + 1.0f;
        }
    }
    return sampleMeanVariance(sum, squares, n) * n;
}
#endif

#ifdef GPURT_DENOISE_SIGNAL  // (the includer reads images)
// The iteration with holes of `stride` pixels at pixel p of an image of `size` pixels: the weighted
// mean of the signal over the 5 x 5 taps and its variance, or (0, -1) when no tap counts.
GPURT_FN vec4 denoiseIteration(GPURT_DENOISE_PARAMS ivec2 p, ivec2 size, int stride) {
    vec3 aP = GPURT_DENOISE_ALBEDO(p);
    vec4 nP = GPURT_DENOISE_NORMAL(p);
    vec4 centre = GPURT_DENOISE_SIGNAL(p);
    // The centre's luminance variance over 3 x 3 (weights 1/4, 1/8, 1/16), refused pixels apart.
    float variance = 0.0f;
    float varianceWeight = 0.0f;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = p + ivec2(dx, dy);
            if (q.x < 0 || q.y < 0 || q.x >= size.x || q.y >= size.y) continue;
            float v = GPURT_DENOISE_SIGNAL(q).w;
            float k = (dx == 0 ? 0.5f : 0.25f) * (dy == 0 ? 0.5f : 0.25f);
            if (v >= 0.0f) {
                variance = variance + k * v;
                varianceWeight = varianceWeight + k;
            }
        }
    }
    // (A refused centre has no luminance of its own: its neighbours count by their features.)
    float scale = centre.w < 0.0f ? GPURT_FAR
                                  : GPURT_DENOISE_SIGMA_LUMINANCE * sqrt(varianceWeight > 0.0f ? variance / varianceWeight : 0.0f) + 1e-10f;
    float lP = denoiseLuminance(vec3(centre.x, centre.y, centre.z));
    vec3 sum = vec3(0.0f);
    float weights = 0.0f;
    float sumVariance = 0.0f;
    for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
            ivec2 q = p + ivec2(dx, dy) * stride;
            if (q.x < 0 || q.y < 0 || q.x >= size.x || q.y >= size.y) continue;
            vec4 s = GPURT_DENOISE_SIGNAL(q);
            if (s.w < 0.0f) continue;
            vec3 e = vec3(s.x, s.y, s.z);
            float pixels = float(stride) * sqrt(float(dx * dx + dy * dy));
            float distance = abs(denoiseLuminance(e) - lP) / scale +
                             denoiseFeatureDistance(aP, nP, GPURT_DENOISE_ALBEDO(q), GPURT_DENOISE_NORMAL(q), pixels);
            float w = atrousTap(dx) * atrousTap(dy) * exp(-distance);
            sum = sum + w * e;
            weights = weights + w;
            sumVariance = sumVariance + w * w * s.w;
        }
    }
    if (!(weights > 0.0f)) return vec4(0.0f, 0.0f, 0.0f, -1.0f);
    return vec4(sum / weights, sumVariance / (weights * weights));
}

#endif

#endif
