// The glTF 2.0 BRDF (specification, Appendix B, B.3.5's mix) written again for the tests, in
// double and independently of glsl/common/materials/gltf.h, and its directional albedo
// E(mu) = integral of f cos over the hemisphere for a view at cosine mu from the normal, by
// deterministic quadrature: the specular part over half vectors drawn on a midpoint grid through
// GGX's inverse distribution (its pdf D(h) n.h divides out), the diffuse part over a
// cosine-weighted grid of light directions. A smooth coat (roughness 0) adds its mirror's
// Fresnel weight at mu.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include <glm/glm.hpp>

namespace gpurt::test {

struct GltfParams {
    glm::dvec3 base{0.8};
    double metallic = 0.0, roughness = 0.5;
    // KHR_materials_transmission's factor and KHR_materials_ior's index, relative across the
    // boundary in the view's direction (below 1: the view is inside the solid).
    double transmission = 0.0, ior = 1.5;
    // KHR_materials_specular: the specular layer's weight and F0 colour.
    double specularFactor = 1.0;
    glm::dvec3 specularColor{1.0};
    // KHR_materials_clearcoat: the coat's weight and roughness, and its normal (the coat's normal
    // texture bends it away from n; only the sampler tests set it, the reference formulas take n).
    double clearcoat = 0.0, clearcoatRoughness = 0.0;
    glm::dvec3 clearcoatNormal{0.0, 0.0, 1.0};
    // KHR_materials_sheen: the sheen's colour (black: none) and roughness.
    glm::dvec3 sheenColor{0.0};
    double sheenRoughness = 0.0;
    // KHR_materials_iridescence: the film's weight (0: none), index and thickness (nm).
    double iridescence = 0.0, iridescenceIor = 1.3, iridescenceThickness = 400.0;
    // KHR_materials_anisotropy: the strength (0: isotropic) and the direction (any vector not
    // along n: the tangent is its part orthogonal to n).
    double anisotropy = 0.0;
    glm::dvec3 anisotropyDirection{1.0, 0.0, 0.0};
    // KHR_materials_transmission's thin wall (no KHR_materials_volume): no bending.
    bool thin = false;
};

namespace gltfref {

constexpr double kPi = 3.14159265358979323846;

// KHR_materials_dispersion's index at wavelength lambda (nm), written from the extension's text:
// max(n_d + (n_d - 1) / V_d (523655 / lambda^2 - 1.5168), 1), V_d = 20 / dispersion.
inline double specDispersedIor(double nd, double dispersion, double lambda) {
    return std::max(nd + (nd - 1.0) / (20.0 / dispersion) * (523655.0 / (lambda * lambda) - 1.5168), 1.0);
}

inline double schlick(double c) { return std::pow(std::clamp(1.0 - c, 0.0, 1.0), 5.0); }

// The dielectric's reflectance Fd at v.h: Schlick's with F0 = ((ior - 1) / (ior + 1))^2 (0.04 at
// 1.5); seen from inside a transmissive solid, at the angle outside (Snell), 1 past the critical
// angle.
inline double dielectric(const GltfParams& p, double vh) {
    const double r = (p.ior - 1.0) / (p.ior + 1.0), f0 = r * r;
    if (p.transmission > 0.0 && p.ior < 1.0) {
        const double sinOut2 = (1.0 - vh * vh) / (p.ior * p.ior);
        if (sinOut2 >= 1.0) return 1.0;
        vh = std::sqrt(1.0 - sinOut2);
    }
    return f0 + (1.0 - f0) * schlick(vh);
}

// KHR_materials_specular's fresnel_mix: the dielectric's layer, weight x fr with fr Schlick's from
// F0 = min(F0(ior) x colour, 1) to 1 (at the angle outside, as dielectric(); 1 past the critical
// angle); the base under it keeps 1 - weight x max(fr). Without the extension (weight 1, colour 1):
// Fd and 1 - Fd.
inline glm::dvec3 dielectricLayer(const GltfParams& p, double vh) {
    const double r = (p.ior - 1.0) / (p.ior + 1.0);
    const glm::dvec3 f0 = glm::min(r * r * p.specularColor, glm::dvec3(1.0));
    double w = 1.0;
    if (p.transmission > 0.0 && p.ior < 1.0) {
        const double sinOut2 = (1.0 - vh * vh) / (p.ior * p.ior);
        if (sinOut2 < 1.0) w = schlick(std::sqrt(1.0 - sinOut2));
    } else {
        w = schlick(vh);
    }
    return p.specularFactor * (f0 + (1.0 - f0) * w);
}
inline double dielectricBase(const GltfParams& p, double vh) {
    const glm::dvec3 layer = dielectricLayer(p, vh);
    return 1.0 - std::max(layer.x, std::max(layer.y, layer.z));
}

// (1 - m) Fd + m Fm, the specular lobe's Fresnel weight at v.h.
inline glm::dvec3 specularWeight(const GltfParams& p, double vh) {
    const double w = schlick(vh);
    return (1.0 - p.metallic) * dielectricLayer(p, vh) + p.metallic * (p.base + (1.0 - p.base) * w);
}

// (1 - m)(1 - t)(1 - Fd) c, pi times the diffuse part.
inline glm::dvec3 diffuseWeight(const GltfParams& p, double vh) {
    return (1.0 - p.metallic) * (1.0 - p.transmission) * dielectricBase(p, vh) * p.base;
}

// (1 - m) t (1 - Fd) c, the transmission's weight.
inline glm::dvec3 transmissionWeight(const GltfParams& p, double vh) {
    return (1.0 - p.metallic) * p.transmission * dielectricBase(p, vh) * p.base;
}

// KHR_materials_sheen's lobe as the extension's implementation notes write it: Charlie's D and
// the visibility with the fitted Lambda, alpha = max(roughness, 0.07)^2 (gpurt's floor).
inline double sheenAlpha(double r) { return std::pow(std::max(r, 0.07), 2.0); }
inline double charlieL(double x, double a) {
    const double k = (1.0 - a) * (1.0 - a);
    auto lerp = [k](double p, double q) { return p + (q - p) * k; };
    return lerp(21.5473, 25.3245) / (1.0 + lerp(3.82987, 3.32435) * std::pow(x, lerp(0.19823, 0.16801))) +
           lerp(-1.97760, -1.27393) * x + lerp(-4.32054, -4.85967);
}
inline double charlieLambda(double c, double a) {
    c = std::abs(c);
    return c < 0.5 ? std::exp(charlieL(c, a)) : std::exp(2.0 * charlieL(0.5, a) - charlieL(1.0 - c, a));
}
inline double sheenLobe(double r, double nh, double nl, double nv) {
    const double a = sheenAlpha(r), d = (2.0 + 1.0 / a) * std::pow(std::max(0.0, 1.0 - nh * nh), 0.5 / a) / (2.0 * kPi);
    return d / ((1.0 + charlieLambda(nv, a) + charlieLambda(nl, a)) * 4.0 * nv * nl);
}
// Its directional albedo at view cosine mu, by the midpoint rule over cos theta and phi in [0, 2 pi).
inline double sheenAlbedo(double mu, double r, int grid = 64) {
    const glm::dvec3 v(std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu);
    double sum = 0.0;
    for (int i = 0; i < grid; ++i)
        for (int j = 0; j < 2 * grid; ++j) {
            const double c = (i + 0.5) / grid, phi = kPi * (j + 0.5) / grid, s = std::sqrt(1.0 - c * c);
            const glm::dvec3 l(s * std::cos(phi), s * std::sin(phi), c), h = glm::normalize(l + v);
            sum += sheenLobe(r, h.z, c, mu) * c;
        }
    return sum * (1.0 / grid) * (kPi / grid);
}

// The same, at most 1 (as gpurt's table: a smooth sheen's lobe integrates above 1 at grazing
// views), on a fine grid of mu (257 points, linear between), computed once a roughness.
inline double sheenAlbedoFine(double mu, double r) {
    static std::map<double, std::vector<double>> tables;
    std::vector<double>& t = tables[r];
    if (t.empty())
        for (int k = 0; k <= 256; ++k) t.push_back(std::min(1.0, sheenAlbedo(std::max(k / 256.0, 1e-4), r)));
    const double x = std::clamp(mu, 0.0, 1.0) * 256.0;
    const int k = std::min(255, int(x));
    return t[size_t(k)] + (t[size_t(k + 1)] - t[size_t(k)]) * (x - k);
}

// KHR_materials_clearcoat's fresnel_coat weight at n.v: clearcoat x Schlick's with F0 0.04.
inline double coatWeight(const GltfParams& p, double nv) { return p.clearcoat * (0.04 + 0.96 * schlick(std::abs(nv))); }

// Smith's Lambda of GGX at cosine mu (Heitz 2014): G2 = 1 / (1 + Lambda(v) + Lambda(l)).
inline double lambda(double a2, double mu) {
    const double tan2 = std::max(0.0, 1.0 - mu * mu) / (mu * mu);
    return 0.5 * (std::sqrt(1.0 + a2 * tan2) - 1.0);
}

inline double ggx(double a2, double nh) {
    const double k = nh * nh * (a2 - 1.0) + 1.0;
    return a2 / (kPi * k * k);
}

// Smith height-correlated G2 / (4 n.l n.v).
inline double visibility(double a2, double nl, double nv) {
    return 0.5 / (nl * std::sqrt(nv * nv * (1.0 - a2) + a2) + nv * std::sqrt(nl * nl * (1.0 - a2) + a2));
}

// KHR_materials_anisotropy's frame and roughnesses: T = the direction made orthogonal to n,
// B = n x T, alpha_t = mix(alpha, 1, strength^2), alpha_b = alpha.
struct AnisotropicFrame {
    glm::dvec3 t, b;
    double at, ab;
};
inline AnisotropicFrame anisotropicFrame(const GltfParams& p, glm::dvec3 n) {
    const glm::dvec3 t = glm::normalize(p.anisotropyDirection - n * glm::dot(n, p.anisotropyDirection));
    const double alpha = p.roughness * p.roughness, s = p.anisotropy;
    return {t, glm::normalize(glm::cross(n, t)), alpha * (1.0 - s * s) + s * s, alpha};
}

// Its lobe D V as the extension's "Implementation" section writes it (D_GGX_anisotropic,
// V_GGX_anisotropic without its clamp).
inline double anisotropicLobe(const GltfParams& p, glm::dvec3 n, glm::dvec3 v, glm::dvec3 l, glm::dvec3 h) {
    const auto [t, b, at, ab] = anisotropicFrame(p, n);
    const double a2 = at * ab;
    const glm::dvec3 f(ab * glm::dot(t, h), at * glm::dot(b, h), a2 * glm::dot(n, h));
    const double w2 = a2 / glm::dot(f, f);
    const double d = a2 * w2 * w2 / kPi;
    const double nl = glm::dot(n, l), nv = glm::dot(n, v);
    const double ggxV = nl * glm::length(glm::dvec3(at * glm::dot(t, v), ab * glm::dot(b, v), nv));
    const double ggxL = nv * glm::length(glm::dvec3(at * glm::dot(t, l), ab * glm::dot(b, l), nl));
    return d * 0.5 / (ggxV + ggxL);
}

}  // namespace gltfref

// f(l, v) at normal n (all unit; zero when l or v is below the surface); without the smooth
// coat's mirror.
inline glm::dvec3 gltfReferenceBrdf(const GltfParams& p, glm::dvec3 n, glm::dvec3 v, glm::dvec3 l) {
    using namespace gltfref;
    const double nl = glm::dot(n, l), nv = glm::dot(n, v);
    if (nl <= 0.0 || nv <= 0.0) return glm::dvec3(0.0);
    const glm::dvec3 h = glm::normalize(l + v);
    const double vh = std::abs(glm::dot(v, h));
    glm::dvec3 f = diffuseWeight(p, vh) / kPi;
    if (p.anisotropy > 0.0) {
        f += specularWeight(p, vh) * anisotropicLobe(p, n, v, l, h);
    } else if (p.roughness > 0.0) {
        const double a2 = std::pow(p.roughness, 4.0);
        f += specularWeight(p, vh) * (ggx(a2, glm::dot(n, h)) * visibility(a2, nl, nv));
    }
    if (p.sheenColor != glm::dvec3(0.0)) {  // sheen colour D V + base x min(scaling at v, at l)
        const double c = std::max(p.sheenColor.x, std::max(p.sheenColor.y, p.sheenColor.z));
        f = f * std::min(1.0 - c * sheenAlbedoFine(nv, p.sheenRoughness), 1.0 - c * sheenAlbedoFine(nl, p.sheenRoughness)) +
            p.sheenColor * sheenLobe(p.sheenRoughness, glm::dot(n, h), nl, nv);
    }
    if (p.clearcoat > 0.0) {  // mix(base, coat's D V, coat weight at n.v)
        const double w = coatWeight(p, nv);
        f *= 1.0 - w;
        if (p.clearcoatRoughness > 0.0) {
            const double a2 = std::pow(p.clearcoatRoughness, 4.0);
            f += glm::dvec3(w * ggx(a2, glm::dot(n, h)) * visibility(a2, nl, nv));
        }
    }
    return f;
}

// A thin wall's BTDF for l below the surface, as KHR_materials_transmission's specular_btdf: the
// reflection's microfacet lobe D V evaluated at l's mirror image l' = l - 2 (n.l) n through the
// surface (h = normalize(v + l')), times the transmission's weight T at v.h.
inline glm::dvec3 gltfReferenceThinBtdf(const GltfParams& p, glm::dvec3 n, glm::dvec3 v, glm::dvec3 l) {
    using namespace gltfref;
    const double nl = glm::dot(n, l), nv = glm::dot(n, v);
    if (nl >= 0.0 || nv <= 0.0 || p.roughness <= 0.0 || p.transmission <= 0.0) return glm::dvec3(0.0);
    const glm::dvec3 mirrored = l - 2.0 * nl * n;
    const glm::dvec3 h = glm::normalize(v + mirrored);
    const double vh = glm::dot(v, h);
    if (vh <= 0.0) return glm::dvec3(0.0);
    const double a2 = std::pow(p.roughness, 4.0);
    const double lobe = p.anisotropy > 0.0 ? anisotropicLobe(p, n, v, mirrored, h) : ggx(a2, glm::dot(n, h)) * visibility(a2, -nl, nv);
    return transmissionWeight(p, vh) * lobe;
}

// The rough dielectric's BTDF for l below the surface, as Walter et al. (2007, eq. 21) write it
// with l the incident direction (index ior) and v the outgoing one (index 1):
//   f = |l.h| |v.h| / (|n.l| |n.v|) 1^2 T G2 D / (ior l.h + v.h)^2, h = -(ior l + v) / |...|
// (radiance: no further factor), T the transmission's weight at v.h.
inline glm::dvec3 gltfReferenceBtdf(const GltfParams& p, glm::dvec3 n, glm::dvec3 v, glm::dvec3 l) {
    using namespace gltfref;
    const double nl = glm::dot(n, l), nv = glm::dot(n, v);
    if (p.thin) return gltfReferenceThinBtdf(p, n, v, l);
    if (nl >= 0.0 || nv <= 0.0 || p.roughness <= 0.0 || p.transmission <= 0.0) return glm::dvec3(0.0);
    glm::dvec3 h = -(p.ior * l + v);
    if (glm::dot(h, h) <= 0.0) return glm::dvec3(0.0);
    h = glm::normalize(h);
    if (glm::dot(h, n) < 0.0) h = -h;
    const double vh = glm::dot(v, h), lh = glm::dot(l, h);
    if (vh <= 0.0 || lh >= 0.0) return glm::dvec3(0.0);
    const double a2 = std::pow(p.roughness, 4.0);
    double g2 = 1.0 / (1.0 + lambda(a2, nv) + lambda(a2, -nl)), d = ggx(a2, glm::dot(n, h));
    if (p.anisotropy > 0.0) {  // KHR_materials_anisotropy: D and G2 = 4 V |n.l| n.v of the same lobe
        const double dv = anisotropicLobe(p, n, v, -l, h);
        const auto [t, b, at, ab] = anisotropicFrame(p, n);
        const double x = glm::dot(t, h) / at, y = glm::dot(b, h) / ab, k = x * x + y * y + glm::dot(n, h) * glm::dot(n, h);
        d = 1.0 / (kPi * at * ab * k * k);
        g2 = dv / d * 4.0 * (-nl) * nv;
    }
    const double denom = p.ior * lh + vh;
    return transmissionWeight(p, vh) * (std::abs(lh) * vh / (-nl * nv) * g2 * d / (denom * denom));
}

// The directional albedo at view cosine mu (n = +z, v in the xz plane).
inline glm::dvec3 gltfReferenceAlbedo(const GltfParams& p, double mu, int grid = 400) {
    using namespace gltfref;
    const glm::dvec3 n(0.0, 0.0, 1.0), v(std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu);
    glm::dvec3 diffuse(0.0), specular(0.0);
    const double alpha = p.roughness * p.roughness, a2 = alpha * alpha;
    for (int i = 0; i < grid; ++i)
        for (int j = 0; j < grid; ++j) {
            const double u1 = (i + 0.5) / grid, u2 = (j + 0.5) / grid, phi = 2.0 * kPi * u2;
            // Cosine-weighted l: f_diffuse cos / (cos / pi) = diffuseWeight.
            const double r = std::sqrt(u1);
            const glm::dvec3 l(r * std::cos(phi), r * std::sin(phi), std::sqrt(1.0 - u1));
            diffuse += diffuseWeight(p, std::abs(glm::dot(v, glm::normalize(l + v))));
            if (p.roughness <= 0.0) continue;
            // h from GGX's D(h) n.h: tan^2 theta = a2 u1 / (1 - u1).
            const double tan2 = a2 * u1 / (1.0 - u1), cosH = 1.0 / std::sqrt(1.0 + tan2);
            const double sinH = std::sqrt(std::max(0.0, 1.0 - cosH * cosH));
            const glm::dvec3 h(sinH * std::cos(phi), sinH * std::sin(phi), cosH);
            const double vh = glm::dot(v, h);
            if (vh <= 0.0) continue;
            const glm::dvec3 ls = 2.0 * vh * h - v;
            const double nl = ls.z;
            if (nl <= 0.0) continue;
            // f cos dl = F D V nl 4 vh dh; divided by the pdf D nh.
            specular += specularWeight(p, vh) * (visibility(a2, nl, mu) * nl * 4.0 * vh / cosH);
        }
    const double count = double(grid) * double(grid);
    glm::dvec3 e = (diffuse + specular) / count;
    if (p.roughness <= 0.0) e += specularWeight(p, mu);
    return e;
}

// The directional albedo under a clearcoat (its normal n): mix(base, coat lobe, w(mu)) integrates to
// (1 - w) E_base + w E_lobe, E_lobe the albedo of the coat's D V alone (a white metal's of the
// coat's roughness: its Fresnel is 1; 1 for a smooth coat's mirror). Without a coat: E_base.
inline glm::dvec3 gltfReferenceCoatedAlbedo(const GltfParams& p, double mu, int grid = 400) {
    if (p.sheenColor != glm::dvec3(0.0)) {
        // The sheen's scaling couples v and l: the BRDF integrated over a cosine-weighted grid of
        // l (rough lobes only: no smooth coat or base with a sheen here).
        const glm::dvec3 n(0.0, 0.0, 1.0), v(std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu);
        glm::dvec3 e(0.0);
        for (int i = 0; i < grid; ++i)
            for (int j = 0; j < grid; ++j) {
                const double u1 = (i + 0.5) / grid, phi = 2.0 * gltfref::kPi * (j + 0.5) / grid, r = std::sqrt(u1);
                const glm::dvec3 l(r * std::cos(phi), r * std::sin(phi), std::sqrt(1.0 - u1));
                e += gltfReferenceBrdf(p, n, v, l) * gltfref::kPi;  // f cos / (cos / pi)
            }
        return e / (double(grid) * double(grid));
    }
    GltfParams base = p;
    base.clearcoat = 0.0;
    const glm::dvec3 e = gltfReferenceAlbedo(base, mu, grid);
    if (p.clearcoat <= 0.0) return e;
    GltfParams lobe;
    lobe.base = glm::dvec3(1.0);
    lobe.metallic = 1.0;
    lobe.roughness = p.clearcoatRoughness;
    const double w = gltfref::coatWeight(p, mu);
    return (1.0 - w) * e + w * gltfReferenceAlbedo(lobe, mu, grid);
}

// KHR_materials_iridescence, computed another way than Belcour and Barla's Fourier-space fits:
// the CIE 1931 colour matching functions as Wyman, Sloan and Shirley's multi-lobe Gaussians (2013,
// "Simple Analytic Approximations to the CIE XYZ Color Matching Functions"), integrated over
// wavelength.
namespace thinfilm {

inline double lobe(double lambda, double mean, double below, double above) {
    const double t = (lambda - mean) / (lambda < mean ? below : above);
    return std::exp(-0.5 * t * t);
}

// x, y, z at wavelength lambda (nm).
inline glm::dvec3 cie(double lambda) {
    return {1.056 * lobe(lambda, 599.8, 37.9, 31.0) + 0.362 * lobe(lambda, 442.0, 16.0, 26.7) -
                0.065 * lobe(lambda, 501.1, 20.4, 26.2),
            0.821 * lobe(lambda, 568.8, 46.9, 40.5) + 0.286 * lobe(lambda, 530.9, 16.3, 31.1),
            1.217 * lobe(lambda, 437.0, 11.8, 36.0) + 0.681 * lobe(lambda, 459.0, 26.0, 13.8)};
}

// XYZ to linear sRGB (IEC 61966-2-1), row by row.
inline glm::dvec3 toRgb(glm::dvec3 c) {
    return {3.2404542 * c.x - 1.5371385 * c.y - 0.4985314 * c.z, -0.9692660 * c.x + 1.8760108 * c.y + 0.0415560 * c.z,
            0.0556434 * c.x - 0.2040259 * c.y + 1.0572252 * c.z};
}

// Linear sRGB to XYZ (IEC 61966-2-1's matrix, not the inverse of toRgb computed).
inline glm::dvec3 toXyz(glm::dvec3 c) {
    return {0.4124564 * c.x + 0.3575761 * c.y + 0.1804375 * c.z, 0.2126729 * c.x + 0.7151522 * c.y + 0.0721750 * c.z,
            0.0193339 * c.x + 0.1191920 * c.y + 0.9503041 * c.z};
}

// The integral of cos(2 pi opd / lambda + shift[channel]) against x, y, z over 360..830 nm, over
// the integral of y (XYZ): what the film's orders contribute per unit amplitude.
inline glm::dvec3 sensitivity(double opd, glm::dvec3 shift) {
    glm::dvec3 xyz(0.0);
    double norm = 0.0;
    for (double lambda = 360.0; lambda <= 830.0; lambda += 0.05) {
        const glm::dvec3 w = cie(lambda);
        const double phase = 2.0 * gltfref::kPi * opd / lambda;
        xyz += glm::dvec3(w.x * std::cos(phase + shift.x), w.y * std::cos(phase + shift.y), w.z * std::cos(phase + shift.z));
        norm += w.y;
    }
    return xyz / norm;
}

inline double schlick(double f0, double c) { return f0 + (1.0 - f0) * gltfref::schlick(c); }

// A film's reflectance where the waves add without interference (the film much thicker than the
// light's coherence length): R12 + T^2 R23 / (1 - R12 R23), T = 1 - R12, the two interfaces'
// Schlick reflectances (film index n2 over a base of reflectance f0 at normal incidence).
inline double incoherent(double n2, double c, double f0) {
    const double r12 = schlick(std::pow((n2 - 1.0) / (n2 + 1.0), 2.0), c);
    const double cos2 = std::sqrt(1.0 - (1.0 - c * c) / (n2 * n2));
    const double n3 = (1.0 + std::sqrt(f0)) / (1.0 - std::sqrt(f0));
    const double r23 = schlick(std::pow((n3 - n2) / (n3 + n2), 2.0), cos2);
    return r12 + (1.0 - r12) * (1.0 - r12) * r23 / (1.0 - r12 * r23);
}

}  // namespace thinfilm

}  // namespace gpurt::test
