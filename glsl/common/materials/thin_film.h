// KHR_materials_iridescence's thin film (thinFilmFresnel), shared word for word by the kernels
// and the CPU backend; included by materials/gltf.h (after schlickWeight) for scenes with a film.
#ifndef GPURT_MATERIALS_THIN_FILM_H
#define GPURT_MATERIALS_THIN_FILM_H

// KHR_materials_iridescence: the reflectance of a thin film over the base, Belcour and Barla's
// (2017, "A Practical Extension to Microfacet Theory for the Modeling of Varying Iridescence") as
// the extension specifies it. The film's interfaces reflect Schlick's amounts; the Airy sum of the
// waves they send back is the incoherent part (order 0) plus orders 1 and 2, each a cosine of the
// optical path difference, integrated against the CIE 1931 sensitivities in Fourier space (the
// paper's Gaussian fits of x, y, z, normalised so that y integrates to 1) and taken to linear sRGB.

// The spectral integral of cos(2 pi opd / lambda + shift) against the sensitivities, in linear
// sRGB, for the optical path difference opd (nm) and a phase shift per channel.
GPURT_FN vec3 thinFilmSensitivity(float opd, vec3 shift) {
    float phase = 2.0f * GPURT_PI * opd * 1.0e-9f;
    vec3 amplitude = vec3(5.4856e-13f, 4.4201e-13f, 5.2481e-13f);
    vec3 centre = vec3(1.6810e+06f, 1.7953e+06f, 2.2084e+06f);
    vec3 variance = vec3(4.3278e+09f, 9.3046e+09f, 6.6121e+09f);
    vec3 xyz = amplitude * sqrt(2.0f * GPURT_PI * variance) * cos(centre * phase + shift) * exp(-(phase * phase) * variance);
    xyz.x = xyz.x + 9.7470e-14f * sqrt(2.0f * GPURT_PI * 4.5282e+09f) * cos(2.2399e+06f * phase + shift.x) *
                        exp(-4.5282e+09f * (phase * phase));  // x's second lobe
    xyz = xyz / 1.0685e-7f;
    // XYZ to linear sRGB (IEC 61966-2-1), column by column.
    mat3 toRgb = mat3(3.2404542f, -0.9692660f, 0.0556434f, -1.5371385f, 1.8760108f, -0.2040259f, -0.4985314f,
                      0.0415560f, 1.0572252f);
    return toRgb * xyz;
}

// The reflectance at cosine c (outside, index 1) of a film of index filmIor and thickness d (nm)
// over a base of reflectance baseF0 at normal incidence (its index ((1 + sqrt F0) / (1 - sqrt F0))).
// A film of no thickness has the outside's index (the film vanishes); past the film's critical
// angle all is reflected.
GPURT_FN vec3 thinFilmFresnel(float filmIor, float d, float c, vec3 baseF0) {
    float n2 = mix(1.0f, filmIor, smoothstep(0.0f, 0.03f, d));
    float cos2Sq = 1.0f - (1.0f - c * c) / (n2 * n2);  // Snell into the film
    if (cos2Sq <= 0.0f) return vec3(1.0f);
    float cos2 = sqrt(cos2Sq);
    float r0 = (n2 - 1.0f) / (n2 + 1.0f);
    r0 = r0 * r0;
    float r12 = r0 + (1.0f - r0) * schlickWeight(c);  // outside to film, the same back (r21)
    float t121 = 1.0f - r12;
    float phi21 = n2 < 1.0f ? 0.0f : GPURT_PI;  // the phase the film's top gives a wave from below
    vec3 s = sqrt(clamp(baseF0, vec3(0.0f), vec3(0.9999f)));
    vec3 n3 = (vec3(1.0f) + s) / (vec3(1.0f) - s);
    vec3 r1 = (n3 - vec3(n2)) / (n3 + vec3(n2));
    r1 = r1 * r1;
    vec3 r23 = r1 + (vec3(1.0f) - r1) * schlickWeight(cos2);  // film to base
    vec3 phi23 = vec3(n3.x < n2 ? GPURT_PI : 0.0f, n3.y < n2 ? GPURT_PI : 0.0f, n3.z < n2 ? GPURT_PI : 0.0f);
    float opd = 2.0f * n2 * d * cos2;
    vec3 phi = vec3(phi21) + phi23;
    vec3 r123 = clamp(r12 * r23, vec3(1e-5f), vec3(0.9999f));
    vec3 rs = (t121 * t121) * r23 / (vec3(1.0f) - r123);
    vec3 reflectance = vec3(r12) + rs;  // order 0: the film's interfaces summed incoherently
    vec3 cm = rs - vec3(t121);
    vec3 ratio = sqrt(r123);
    for (int order = 1; order <= 2; ++order) {
        cm = cm * ratio;
        reflectance = reflectance + cm * (2.0f * thinFilmSensitivity(float(order) * opd, float(order) * phi));
    }
    return max(reflectance, vec3(0.0f));  // the fits' colours outside the gamut
}

#endif
