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

#include <glm/glm.hpp>

namespace gpurt::test {

struct GltfParams {
    glm::dvec3 base{0.8};
    double metallic = 0.0, roughness = 0.5;
};

namespace gltfref {

constexpr double kPi = 3.14159265358979323846;

inline double schlick(double c) { return std::pow(std::clamp(1.0 - c, 0.0, 1.0), 5.0); }

// (1 - m) Fd + m Fm, the specular lobe's Fresnel weight at v.h.
inline glm::dvec3 specularWeight(const GltfParams& p, double vh) {
    const double w = schlick(vh);
    return (1.0 - p.metallic) * glm::dvec3(0.04 + 0.96 * w) + p.metallic * (p.base + (1.0 - p.base) * w);
}

// (1 - m)(1 - Fd) c, pi times the diffuse part.
inline glm::dvec3 diffuseWeight(const GltfParams& p, double vh) {
    return (1.0 - p.metallic) * (1.0 - (0.04 + 0.96 * schlick(vh))) * p.base;
}

inline double ggx(double a2, double nh) {
    const double k = nh * nh * (a2 - 1.0) + 1.0;
    return a2 / (kPi * k * k);
}

// Smith height-correlated G2 / (4 n.l n.v).
inline double visibility(double a2, double nl, double nv) {
    return 0.5 / (nl * std::sqrt(nv * nv * (1.0 - a2) + a2) + nv * std::sqrt(nl * nl * (1.0 - a2) + a2));
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
    if (p.roughness > 0.0) {
        const double a2 = std::pow(p.roughness, 4.0);
        f += specularWeight(p, vh) * (ggx(a2, glm::dot(n, h)) * visibility(a2, nl, nv));
    }
    return f;
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

}  // namespace gpurt::test
