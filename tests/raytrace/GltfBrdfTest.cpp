// The glTF model's BRDF and its sampling (glsl/common/materials/gltf.h, shared by the kernels)
// against the glTF 2.0 specification's Appendix B written again in the test (GltfReference.h):
// the same values, reciprocity f(l, v) = f(v, l), hemispherical albedo at most 1, and the
// sampling: the factor it returns is f cos / pdf, its pdf integrates to the share of samples
// that stay above the surface, and the samples follow the pdf (chi-square over a grid of solid
// angle cells).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "GltfReference.h"
#include "raytrace/common/RayMath.h"
#include "raytrace/materials/SheenTable.h"

namespace gpurt::test {
namespace {

using raymath::MaterialRecord;

MaterialRecord record(const GltfParams& p) {
    MaterialRecord m{};
    m.model = GPURT_MODEL_GLTF;
    m.kd = glm::vec3(p.base);
    m.metallic = float(p.metallic);
    m.roughness = float(p.roughness);
    m.occlusion = 1.0f;
    m.emitterLight = true;
    m.specularColor = glm::vec3(p.specularColor);  // KHR_materials_specular
    m.specularWeight = float(p.specularFactor);
    m.coat = float(p.clearcoat);  // KHR_materials_clearcoat
    m.coatRoughness = float(p.clearcoatRoughness);
    m.coatNormal = glm::vec3(glm::normalize(p.clearcoatNormal));
    m.sheenColor = glm::vec3(p.sheenColor);  // KHR_materials_sheen
    m.sheenRoughness = float(p.sheenRoughness);
    m.iridescence = float(p.iridescence);  // KHR_materials_iridescence
    m.iridescenceIor = float(p.iridescenceIor);
    m.iridescenceThickness = float(p.iridescenceThickness);
    m.anisotropy = float(p.anisotropy);  // KHR_materials_anisotropy
    m.anisotropyDirection = glm::vec3(p.anisotropyDirection);
    if (p.transmission > 0.0 || p.ior != 1.5) {  // the loader's KHR_materials_ior / _transmission
        m.ior = float(p.ior);
        m.tf = glm::vec3(float(p.transmission));
    }
    m.thin = p.thin;
    return m;
}

glm::dvec3 hemisphere(std::mt19937& rng, double minCos = 0.02) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (;;) {
        const double z = u(rng), phi = 2.0 * gltfref::kPi * u(rng), r = std::sqrt(1.0 - z * z);
        if (z > minCos) return {r * std::cos(phi), r * std::sin(phi), z};
    }
}

GltfParams randomParams(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    GltfParams p;
    p.base = glm::dvec3(u(rng), u(rng), u(rng));
    p.metallic = u(rng);
    p.roughness = 0.1 + 0.9 * u(rng);
    return p;
}

// Pearson's chi-square of a histogram against its expected counts, cells expecting fewer than 5
// pooled into one, and the 0.001 critical value for its degrees of freedom (Wilson-Hilferty).
struct ChiSquare {
    double statistic = 0.0, critical = 0.0;
    int cells = 0;
};

ChiSquare chiSquare(const std::vector<double>& histogram, const std::vector<double>& expected) {
    ChiSquare r;
    double pooledObserved = 0.0, pooledExpected = 0.0;
    for (size_t c = 0; c < histogram.size(); ++c) {
        if (expected[c] < 5.0) {  // sparse cells pooled into one
            pooledObserved += histogram[c];
            pooledExpected += expected[c];
            continue;
        }
        r.statistic += (histogram[c] - expected[c]) * (histogram[c] - expected[c]) / expected[c];
        ++r.cells;
    }
    if (pooledExpected >= 5.0) {
        r.statistic += (pooledObserved - pooledExpected) * (pooledObserved - pooledExpected) / pooledExpected;
        ++r.cells;
    }
    const double k = r.cells - 1, z = 3.09;
    r.critical = k * std::pow(1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k)), 3.0);
    return r;
}

TEST(GltfBrdf, IsAppendixBAndReciprocal) {
    std::mt19937 rng(7);
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    for (int k = 0; k < 2000; ++k) {
        const GltfParams p = randomParams(rng);
        const glm::dvec3 v = hemisphere(rng), l = hemisphere(rng);
        const glm::vec3 f = raymath::gltfBrdf(record(p), n, glm::vec3(v), glm::vec3(l));
        const glm::vec3 back = raymath::gltfBrdf(record(p), n, glm::vec3(l), glm::vec3(v));
        const glm::dvec3 expected = gltfReferenceBrdf(p, glm::dvec3(n), v, l);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(f[c], expected[c], 1e-4 + 1e-4 * expected[c]) << k;
            EXPECT_NEAR(f[c], back[c], 1e-5 + 1e-5 * f[c]) << k;
        }
    }
}

// The directional albedo (the reference quadrature) and the sampler's estimate of the same
// integral (the mean of its throughput factor) agree. The albedo is at most 1 for metals at every
// view and for every material seen head-on; Appendix B's mix is not energy conserving for
// dielectrics at grazing views (its diffuse term is weighed by 1 - F at v.h, not at n.v): a white
// base of metallic 0 and roughness 0 reflects 1.7 times the light at n.v = 0.05 by the
// specification's formula, and gpurt renders the formula (CONTRACT.md: "exactly").
TEST(GltfBrdf, AlbedoIsAtMostOneAndTheSamplerEstimatesIt) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int k = 0; k < 24; ++k) {
        GltfParams p = randomParams(rng);
        if (k % 4 == 0) p.base = glm::dvec3(1.0);  // the brightest material there is
        if (k % 6 == 0) p.roughness = 0.0;          // a smooth coat
        if (k % 3 == 0) p.metallic = 1.0;           // a metal
        const double mu = 0.05 + 0.95 * u(rng);
        const glm::dvec3 e = gltfReferenceAlbedo(p, mu, 300), headOn = gltfReferenceAlbedo(p, 1.0, 300);
        for (int c = 0; c < 3; ++c) {
            EXPECT_LE(headOn[c], 1.0 + 1e-3) << k;
            if (p.metallic == 1.0) {
                EXPECT_LE(e[c], 1.0 + 1e-3) << k;
            }
        }
        // Sampling: the mean of the throughput factor is the albedo.
        const MaterialRecord m = record(p);
        const glm::vec3 n(0.0f, 0.0f, 1.0f), v(float(std::sqrt(1.0 - mu * mu)), 0.0f, float(mu));
        const int samples = 200000;
        glm::dvec3 sum(0.0), sum2(0.0);
        for (int s = 0; s < samples; ++s) {
            glm::vec3 dir, factor;
            float pdf, side;
            if (!raymath::materialSample(m, -v, n, n, true, glm::vec2(float(u(rng)), float(u(rng))), float(u(rng)), dir, factor,
                                         pdf, side))
                continue;
            sum += glm::dvec3(factor);
            sum2 += glm::dvec3(factor) * glm::dvec3(factor);
        }
        for (int c = 0; c < 3; ++c) {
            const double mean = sum[c] / samples, var = std::max(0.0, sum2[c] / samples - mean * mean);
            EXPECT_NEAR(mean, e[c], 5.0 * std::sqrt(var / samples) + 2e-3) << "case " << k << " channel " << c;
        }
    }
}

// materialEval / materialPdf / materialSample agree: a sampled direction's factor is
// eval cos / (pi pdf) and its pdf is materialPdf's.
TEST(GltfBrdf, SampleFactorIsEvalCosOverPdf) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    int taken = 0;
    for (int k = 0; k < 5000; ++k) {
        const MaterialRecord m = record(randomParams(rng));
        const glm::vec3 v(hemisphere(rng, 0.1));
        glm::vec3 dir, factor;
        float pdf, side;
        if (!raymath::materialSample(m, -v, n, n, true, glm::vec2(float(u(rng)), float(u(rng))), float(u(rng)), dir, factor, pdf, side))
            continue;
        ++taken;
        ASSERT_GT(pdf, 0.0f);
        EXPECT_NEAR(pdf, raymath::materialPdf(m, n, -v, dir), 1e-3f * pdf);
        const glm::vec3 expected = raymath::materialEval(m, n, -v, dir) * float(glm::dot(n, dir) / (gltfref::kPi * pdf));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(factor[c], expected[c], 1e-3f * (1.0f + expected[c]));
    }
    EXPECT_GT(taken, 4000);
}

// The pdf over a grid of cells of equal solid angle (cos theta, phi): its integral is the share
// of samples that are kept, and the histogram of 400000 samples follows it (chi-square with
// cells of expected count 5 or more; the 0.001 critical value of the statistic).
void expectSamplesFollowThePdf(const std::vector<GltfParams>& cases, uint32_t seed) {
    const int cosCells = 24, phiCells = 48, samples = 400000;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (const GltfParams& p : cases) {
        SCOPED_TRACE("metallic " + std::to_string(p.metallic) + " roughness " + std::to_string(p.roughness));
        const MaterialRecord m = record(p);
        const glm::vec3 n(0.0f, 0.0f, 1.0f), v = glm::normalize(glm::vec3(0.6f, 0.0f, 0.8f));
        std::vector<double> histogram(size_t(cosCells * phiCells), 0.0), expected(histogram.size(), 0.0);
        int kept = 0;
        for (int s = 0; s < samples; ++s) {
            glm::vec3 dir, factor;
            float pdf, side;
            if (!raymath::materialSample(m, -v, n, n, true, glm::vec2(float(u(rng)), float(u(rng))), float(u(rng)), dir, factor,
                                         pdf, side))
                continue;
            ++kept;
            const int i = std::min(cosCells - 1, int(dir.z * cosCells));
            double phi = std::atan2(double(dir.y), double(dir.x));
            if (phi < 0.0) phi += 2.0 * gltfref::kPi;
            const int j = std::min(phiCells - 1, int(phi / (2.0 * gltfref::kPi) * phiCells));
            histogram[size_t(i * phiCells + j)] += 1.0;
        }
        // The pdf integrated over each cell by a 16 x 16 midpoint rule (cells of equal solid angle).
        const double cellArea = 2.0 * gltfref::kPi / (cosCells * phiCells);
        double integral = 0.0;
        for (int i = 0; i < cosCells; ++i)
            for (int j = 0; j < phiCells; ++j) {
                double sum = 0.0;
                for (int a = 0; a < 16; ++a)
                    for (int b = 0; b < 16; ++b) {
                        const double z = (i + (a + 0.5) / 16.0) / cosCells, phi = 2.0 * gltfref::kPi * (j + (b + 0.5) / 16.0) / phiCells;
                        const double r = std::sqrt(1.0 - z * z);
                        const glm::vec3 l(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
                        sum += raymath::materialPdf(m, n, -v, l);
                    }
                const double mass = sum / 256.0 * cellArea;
                expected[size_t(i * phiCells + j)] = mass * samples;
                integral += mass;
            }
        EXPECT_NEAR(integral, double(kept) / samples, 0.01);
        const ChiSquare chi = chiSquare(histogram, expected);
        ASSERT_GT(chi.cells, 100);
        EXPECT_LT(chi.statistic, chi.critical) << chi.cells << " cells";
    }
}

TEST(GltfBrdf, SamplesFollowThePdf) {
    expectSamplesFollowThePdf({GltfParams{glm::dvec3(0.8, 0.6, 0.2), 1.0, 0.3}, GltfParams{glm::dvec3(0.5), 0.0, 0.6},
                               GltfParams{glm::dvec3(0.9), 0.3, 0.35}},
                              5);
}

// Random layers of KHR_materials_specular (factor, colour, beyond 1 too) and KHR_materials_clearcoat
// (factor, roughness).
GltfParams randomLayers(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    GltfParams p = randomParams(rng);
    p.specularFactor = u(rng);
    p.specularColor = glm::dvec3(1.5 * u(rng), 1.5 * u(rng), 1.5 * u(rng));
    p.clearcoat = u(rng);
    p.clearcoatRoughness = 0.1 + 0.9 * u(rng);
    return p;
}

// The layers are the extensions' formulas (GltfReference.h, written from the specifications):
// fresnel_mix's specular layer and the base under it, fresnel_coat's mix at the coat normal's n.v.
TEST(GltfBrdf, LayersAreTheExtensionsFormulas) {
    std::mt19937 rng(29);
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    for (int k = 0; k < 2000; ++k) {
        const GltfParams p = randomLayers(rng);
        const glm::dvec3 v = hemisphere(rng), l = hemisphere(rng);
        const glm::vec3 f = raymath::gltfBrdf(record(p), n, glm::vec3(v), glm::vec3(l));
        const glm::dvec3 expected = gltfReferenceBrdf(p, glm::dvec3(n), v, l);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], expected[c], 1e-4 + 1e-4 * expected[c]) << k;
    }
    // Head-on, a smooth coat over a base without a specular layer reflects 0.04 x clearcoat.
    GltfParams coat;
    coat.base = glm::dvec3(0.0);
    coat.specularFactor = 0.0;
    coat.clearcoat = 0.5;
    EXPECT_FLOAT_EQ(raymath::gltfCoatWeight(record(coat), glm::vec3(0.0f, 0.0f, 1.0f)), 0.02f);
}

// A coat with a normal of its own (its normal texture) is a microfacet lobe about that normal:
// over a black base without a specular layer, the reflected radiance f (n.l) that every integrator
// takes with the shading normal n is clearcoat x Fresnel(nc.v) x D V (nc) x (nc.l), the coat's own
// cosine (the glTF Sample Viewer's clearcoat term), whatever n is; 0 where l is below either.
TEST(GltfBrdf, CoatLobeLiesAboutTheCoatsNormal) {
    std::mt19937 rng(53);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int checked = 0;
    for (int k = 0; k < 4000; ++k) {
        GltfParams p;
        p.base = glm::dvec3(0.0);
        p.specularFactor = 0.0;
        p.clearcoat = u(rng);
        p.clearcoatRoughness = 0.1 + 0.9 * u(rng);
        p.clearcoatNormal = glm::normalize(glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, 0.6));
        const glm::dvec3 v = hemisphere(rng), l = hemisphere(rng);
        const glm::dvec3 n = glm::normalize(glm::dvec3(0.4 * (u(rng) - 0.5), 0.4 * (u(rng) - 0.5), 1.0));  // the base's
        const glm::dvec3 nc = p.clearcoatNormal, h = glm::normalize(v + l);
        const double nl = glm::dot(n, l), ncl = glm::dot(nc, l), ncv = glm::dot(nc, v);
        if (!(nl > 0.05 && glm::dot(n, v) > 0.05 && ncv > 0.05)) continue;
        const double a2 = std::pow(p.clearcoatRoughness, 4.0);
        const double expected = ncl > 0.0 ? gltfref::coatWeight(p, ncv) * gltfref::ggx(a2, glm::dot(nc, h)) *
                                                gltfref::visibility(a2, ncl, ncv) * ncl
                                          : 0.0;
        const glm::vec3 f = raymath::gltfBrdf(record(p), glm::vec3(n), glm::vec3(v), glm::vec3(l));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c] * nl, expected, 1e-4 * (1.0 + expected)) << k;
        ++checked;
    }
    EXPECT_GT(checked, 1000);
}

// KHR_materials_sheen's albedo table (SheenTable.cpp, by quadrature of the shared lobe) is the
// lobe's directional albedo as the test integrates the formula written again (GltfReference.h, on
// another grid; both at most 1), and the lookup between entries stays close to the exact albedo.
TEST(GltfBrdf, SheenTableIsTheLobesAlbedo) {
    const std::vector<float>& table = sheenAlbedoTable();
    const int n = GPURT_SHEEN_TABLE;
    ASSERT_EQ(table.size(), size_t(n * n));
    for (int j = 0; j < n; j += 3)
        for (int i = 0; i < n; i += 3) {
            const double x = double(i) / (n - 1), mu = std::max(x * x, 1e-4), r = double(j) / (n - 1);  // sqrt(mu) along a row
            const double e = std::min(1.0, gltfref::sheenAlbedo(mu, r, 128));  // at most 1 (SheenTable.cpp)
            EXPECT_NEAR(table[size_t(j * n + i)], e, 2e-3 + 1e-2 * e) << "mu " << mu << " r " << r;
            EXPECT_GE(table[size_t(j * n + i)], 0.0f);
        }
    for (double mu : {0.1, 0.37, 0.8})
        for (double r : {0.2, 0.55, 0.9})
            EXPECT_NEAR(raymath::sheenAlbedo(float(mu), float(r)), gltfref::sheenAlbedo(mu, r, 128), 1e-2) << mu << " " << r;
}

// The sheen over the rest is the extension's: sheen colour D V + the rest x min(1 - max(colour)
// E(n.v), 1 - max(colour) E(n.l)), under a coat where there is one.
TEST(GltfBrdf, SheenIsTheExtensionsFormula) {
    std::mt19937 rng(41);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    for (int k = 0; k < 400; ++k) {
        GltfParams p = k % 2 ? randomLayers(rng) : randomParams(rng);
        p.sheenColor = glm::dvec3(u(rng), u(rng), u(rng));
        p.sheenRoughness = 0.1 + 0.3 * (k % 4);  // a few: the reference tabulates E once a roughness
        const glm::dvec3 v = hemisphere(rng), l = hemisphere(rng);
        const glm::vec3 f = raymath::gltfBrdf(record(p), n, glm::vec3(v), glm::vec3(l));
        const glm::dvec3 expected = gltfReferenceBrdf(p, glm::dvec3(n), v, l);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], expected[c], 3e-3 + 3e-3 * expected[c]) << k;
    }
}

// KHR_materials_iridescence's thin film (gltf.h thinFilmFresnel):
//  - the sensitivities (Belcour and Barla's Gaussian fits in Fourier space) are the CIE 1931
//    functions' integrals against cos(2 pi opd / lambda + shift), here integrated over wavelength
//    with Wyman et al.'s fits of the functions: at opd 0 each of X, Y, Z integrates to Y's (the CIE
//    functions' equal-energy white), and the film's orders' XYZ at 100..1500 nm within what the
//    two fits of the CIE functions differ by (0.03, 0.07 at 1500 nm where their tails matter);
//  - a film far thicker than the light's coherence is the incoherent sum of its two interfaces'
//    reflections, R12 + T^2 R23 / (1 - R12 R23);
//  - a vanishing film seen head-on is the base's F0 (within its clamped orders' 1%; at an angle
//    the extension's Schlick term of the index-matched interface, (1 - cos)^5, remains);
//  - factor 0 changes nothing; the layer mixes the film by the factor; a metal's film is over its
//    base colour.
TEST(GltfBrdf, ThinFilmIsBelcourAndBarlasAsTheExtensionSpecifies) {
    const glm::dvec3 white = thinfilm::toRgb(glm::dvec3(1.0));
    const glm::vec3 s0 = raymath::thinFilmSensitivity(0.0f, glm::vec3(0.0f));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(s0[c], white[c], 3e-3 * white[c]) << c;
    for (double opd : {100.0, 250.0, 400.0, 600.0, 900.0, 1500.0})
        for (double shift : {0.0, gltfref::kPi}) {
            const glm::dvec3 got = thinfilm::toXyz(glm::dvec3(raymath::thinFilmSensitivity(float(opd), glm::vec3(float(shift)))));
            const glm::dvec3 expected = thinfilm::sensitivity(opd, glm::dvec3(shift));
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(got[c], expected[c], opd < 1000.0 ? 0.03 : 0.07) << "opd " << opd << " shift " << shift << " channel " << c;
        }
    const glm::vec3 far = raymath::thinFilmSensitivity(20000.0f, glm::vec3(0.0f));
    EXPECT_LT(glm::length(far), 1e-6f);
    for (double n2 : {1.2, 1.5, 2.0})
        for (double f0 : {0.02, 0.04, 0.3, 0.8})
            for (double c : {1.0, 0.7, 0.3}) {
                SCOPED_TRACE("film " + std::to_string(n2) + " base F0 " + std::to_string(f0) + " cos " + std::to_string(c));
                const glm::vec3 thick = raymath::thinFilmFresnel(float(n2), 1e5f, float(c), glm::vec3(float(f0)));
                const double expected = thinfilm::incoherent(n2, c, f0);
                for (int k = 0; k < 3; ++k) EXPECT_NEAR(thick[k], expected, 1e-4 + 2e-5 * expected);
                if (c == 1.0) {
                    const glm::vec3 none = raymath::thinFilmFresnel(float(n2), 0.0f, float(c), glm::vec3(float(f0)));
                    for (int k = 0; k < 3; ++k) EXPECT_NEAR(none[k], f0, 0.01);
                }
            }
    GltfParams dielectric{glm::dvec3(0.3, 0.2, 0.1), 0.0, 0.3}, metal{glm::dvec3(0.9, 0.6, 0.3), 1.0, 0.3};
    for (GltfParams p : {dielectric, metal}) {
        const float vh = 0.8f;
        const glm::vec3 plain = raymath::gltfSpecularFresnel(record(p), vh);
        p.iridescenceIor = 1.6;
        p.iridescenceThickness = 350.0;
        EXPECT_EQ(raymath::gltfSpecularFresnel(record(p), vh), plain) << "factor 0";
        p.iridescence = 0.75;
        const glm::vec3 f0 = p.metallic > 0.0 ? glm::vec3(p.base) : glm::vec3(0.04f);
        const glm::vec3 film = raymath::thinFilmFresnel(1.6f, 350.0f, vh, f0);
        const glm::vec3 expected = glm::mix(plain, film, 0.75f);
        const glm::vec3 got = raymath::gltfSpecularFresnel(record(p), vh);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 1e-5f) << c;
        EXPECT_GT(glm::length(got - plain), 0.01f);
    }
}

// With layers the sampler stays consistent: a sampled direction's factor is eval cos / (pi pdf)
// (a smooth coat's mirror: its weight over its probability), the samples follow the pdf, and the
// mean factor is the coated albedo (GltfReference.h gltfReferenceCoatedAlbedo).
TEST(GltfBrdf, LayeredSamplingIsConsistent) {
    std::mt19937 rng(31);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    int taken = 0, deltas = 0;
    for (int k = 0; k < 5000; ++k) {
        GltfParams p = randomLayers(rng);
        if (k % 3 == 0) p.clearcoatRoughness = 0.0;  // a smooth coat: a delta lobe
        if (k % 2 == 0) {                              // a sheen under the coat
            p.sheenColor = glm::dvec3(u(rng), u(rng), u(rng));
            p.sheenRoughness = u(rng);
        }
        if (k % 4 == 1)  // a coat normal bent by its normal texture, up to about 35 degrees from n
            p.clearcoatNormal = glm::dvec3(0.7 * (u(rng) - 0.5), 0.7 * (u(rng) - 0.5), 0.5);
        if (k % 5 == 0) {  // a thin film
            p.iridescence = u(rng);
            p.iridescenceIor = 1.0 + u(rng);
            p.iridescenceThickness = 800.0 * u(rng);
        }
        const MaterialRecord m = record(p);
        const glm::vec3 v(hemisphere(rng, 0.1));
        glm::vec3 dir, factor;
        float pdf, side;
        if (!raymath::materialSample(m, -v, n, n, true, glm::vec2(float(u(rng)), float(u(rng))), float(u(rng)), dir, factor, pdf, side))
            continue;
        ++taken;
        if (pdf == 0.0f) {  // the coat's mirror
            ++deltas;
            EXPECT_EQ(p.clearcoatRoughness, 0.0);
            // The mirror about the coat's normal (about n where that one would go below the surface).
            const glm::vec3 nc = m.coatNormal, bent = 2.0f * glm::dot(nc, v) * nc - v;
            const glm::vec3 mirror = bent.z > 0.0f ? bent : glm::vec3(-v.x, -v.y, v.z);
            EXPECT_LT(glm::length(dir - mirror), 1e-5f) << "coat normal " << nc.x << " " << nc.y << " " << nc.z;
            continue;
        }
        EXPECT_NEAR(pdf, raymath::materialPdf(m, n, -v, dir), 1e-3f * pdf);
        const glm::vec3 expected = raymath::materialEval(m, n, -v, dir) * float(glm::dot(n, dir) / (gltfref::kPi * pdf));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(factor[c], expected[c], 1e-3f * (1.0f + expected[c]));
    }
    EXPECT_GT(taken, 4000);
    EXPECT_GT(deltas, 100);

    GltfParams coated{glm::dvec3(0.8, 0.6, 0.2), 0.0, 0.5};
    coated.clearcoat = 0.8;
    coated.clearcoatRoughness = 0.25;
    GltfParams tinted{glm::dvec3(0.5), 0.2, 0.4};
    tinted.specularFactor = 0.6;
    tinted.specularColor = glm::dvec3(1.2, 0.5, 0.1);
    tinted.clearcoat = 0.4;
    tinted.clearcoatRoughness = 0.6;
    GltfParams velvet{glm::dvec3(0.3, 0.05, 0.1), 0.0, 0.8};
    velvet.sheenColor = glm::dvec3(1.0, 0.6, 0.8);
    velvet.sheenRoughness = 0.4;
    GltfParams bent = coated;  // the coat's normal bent by its normal texture, toward and away from v
    bent.clearcoatNormal = glm::dvec3(0.3, 0.1, 1.0);
    GltfParams bentAway = tinted;
    bentAway.clearcoatNormal = glm::dvec3(-0.4, 0.2, 1.0);
    expectSamplesFollowThePdf({coated, tinted, velvet, bent, bentAway}, 37);

    GltfParams smoothCoat{glm::dvec3(0.9, 0.3, 0.3), 0.0, 0.7};
    smoothCoat.clearcoat = 1.0;
    for (const GltfParams& p : {coated, tinted, smoothCoat, velvet})
        for (double mu : {0.2, 0.7, 1.0}) {
            const glm::dvec3 e = gltfReferenceCoatedAlbedo(p, mu, p.sheenColor == glm::dvec3(0.0) ? 300 : 200);
            const MaterialRecord m = record(p);
            const glm::vec3 v(float(std::sqrt(1.0 - mu * mu)), 0.0f, float(mu));
            const int samples = 100000;
            glm::dvec3 sum(0.0), sum2(0.0);
            for (int s = 0; s < samples; ++s) {
                glm::vec3 dir, factor;
                float pdf, side;
                if (!raymath::materialSample(m, -v, n, n, true, glm::vec2(float(u(rng)), float(u(rng))), float(u(rng)), dir,
                                             factor, pdf, side))
                    continue;
                sum += glm::dvec3(factor);
                sum2 += glm::dvec3(factor) * glm::dvec3(factor);
            }
            for (int c = 0; c < 3; ++c) {
                const double mean = sum[c] / samples, var = std::max(0.0, sum2[c] / samples - mean * mean);
                EXPECT_NEAR(mean, e[c], 5.0 * std::sqrt(var / samples) + 2e-3) << "mu " << mu << " channel " << c;
            }
        }
}

// Random anisotropy (KHR_materials_anisotropy) on a random base: strength in [0, 1], a direction
// that is any vector not along n (the record's is the tangent frame's, made orthogonal to the
// shading normal where it is used).
GltfParams randomAnisotropic(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    GltfParams p = randomParams(rng);
    p.anisotropy = u(rng);
    const double phi = 2.0 * gltfref::kPi * u(rng);
    p.anisotropyDirection = glm::dvec3(std::cos(phi), std::sin(phi), 0.8 * (u(rng) - 0.5));
    return p;
}

// KHR_materials_anisotropy's lobe is the extension's D and V (GltfReference.h, in the form its
// "Implementation" section writes them), in the frame of the direction made orthogonal to n, and
// reciprocal; strength 0 is the isotropic lobe.
TEST(GltfBrdf, AnisotropyIsTheExtensionsGgx) {
    std::mt19937 rng(41);
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    for (int k = 0; k < 2000; ++k) {
        GltfParams p = randomAnisotropic(rng);
        if (k % 10 == 0) p.anisotropy = 0.0;
        const glm::dvec3 v = hemisphere(rng), l = hemisphere(rng);
        const glm::vec3 f = raymath::gltfBrdf(record(p), n, glm::vec3(v), glm::vec3(l));
        const glm::vec3 back = raymath::gltfBrdf(record(p), n, glm::vec3(l), glm::vec3(v));
        const glm::dvec3 expected = gltfReferenceBrdf(p, glm::dvec3(n), v, l);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(f[c], expected[c], 1e-4 + 2e-4 * expected[c]) << k;
            EXPECT_NEAR(f[c], back[c], 1e-5 + 1e-4 * f[c]) << k;
        }
    }
    // Turning the direction about n turns the lobe: the highlight of a light along the direction
    // seen from across it differs from the one seen along it.
    GltfParams brushed{glm::dvec3(0.9), 1.0, 0.3};
    brushed.anisotropy = 0.9;
    const glm::vec3 v(glm::normalize(glm::dvec3(0.7, 0.0, 0.7))), along(glm::normalize(glm::dvec3(-0.5, 0.5, 0.7)));
    GltfParams turned = brushed;
    turned.anisotropyDirection = glm::dvec3(0.0, 1.0, 0.0);
    EXPECT_GT(raymath::gltfBrdf(record(turned), n, v, along).x, 1.5f * raymath::gltfBrdf(record(brushed), n, v, along).x);
}

// The map's direction and strength (gltfAnisotropyAt): RG from [0, 1] to [-1, 1], normalized,
// turned counter-clockwise by the rotation; B times the strength; without a map (texel (1, 0.5,
// 1)) the rotation's direction and the strength.
TEST(GltfBrdf, AnisotropyDirectionIsTheMapTurnedByTheRotation) {
    const float quarter = float(gltfref::kPi / 2.0);
    const glm::vec2 turn(std::cos(quarter), std::sin(quarter));
    glm::vec3 a = raymath::gltfAnisotropyAt(0.6f, glm::vec2(1.0f, 0.0f), glm::vec3(1.0f, 0.5f, 1.0f));
    EXPECT_FLOAT_EQ(a.x, 1.0f);
    EXPECT_FLOAT_EQ(a.y, 0.0f);
    EXPECT_FLOAT_EQ(a.z, 0.6f);
    a = raymath::gltfAnisotropyAt(0.6f, turn, glm::vec3(1.0f, 0.5f, 1.0f));  // the tangent turned to the bitangent
    EXPECT_NEAR(a.x, 0.0f, 1e-6f);
    EXPECT_NEAR(a.y, 1.0f, 1e-6f);
    a = raymath::gltfAnisotropyAt(0.5f, turn, glm::vec3(1.0f, 1.0f, 0.4f));  // (1, 1) / sqrt(2) turned: (-1, 1) / sqrt(2)
    EXPECT_NEAR(a.x, -std::sqrt(0.5f), 1e-6f);
    EXPECT_NEAR(a.y, std::sqrt(0.5f), 1e-6f);
    EXPECT_FLOAT_EQ(a.z, 0.2f);
    a = raymath::gltfAnisotropyAt(0.5f, glm::vec2(1.0f, 0.0f), glm::vec3(0.5f, 0.5f, 1.0f));  // no direction
    EXPECT_EQ(a.z, 0.0f);
}

// Anisotropic sampling stays consistent: a sampled direction's factor is eval cos / (pi pdf) and
// its pdf is materialPdf's (a roughness of 0 with anisotropy is rough along the direction, not a
// mirror), the samples follow the pdf, and the pdf integrates to the share kept (lobes the
// quadrature's cells resolve: alpha 0.02 and more).
TEST(GltfBrdf, AnisotropicSamplingIsConsistent) {
    std::mt19937 rng(43);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    int taken = 0;
    for (int k = 0; k < 5000; ++k) {
        GltfParams p = randomAnisotropic(rng);
        if (k % 4 == 0) p.roughness = 0.0;
        const MaterialRecord m = record(p);
        const glm::vec3 v(hemisphere(rng, 0.1));
        glm::vec3 dir, factor;
        float pdf, side;
        if (!raymath::materialSample(m, -v, n, n, true, glm::vec2(float(u(rng)), float(u(rng))), float(u(rng)), dir, factor, pdf, side))
            continue;
        ++taken;
        ASSERT_GT(pdf, 0.0f) << k;
        EXPECT_NEAR(pdf, raymath::materialPdf(m, n, -v, dir), 1e-3f * pdf);
        const glm::vec3 expected = raymath::materialEval(m, n, -v, dir) * float(glm::dot(n, dir) / (gltfref::kPi * pdf));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(factor[c], expected[c], 1e-3f * (1.0f + expected[c]));
    }
    EXPECT_GT(taken, 4000);
    GltfParams brushed{glm::dvec3(0.9, 0.7, 0.5), 1.0, 0.3}, across{glm::dvec3(0.8), 0.2, 0.5}, sharp{glm::dvec3(0.9), 1.0, 0.15};
    brushed.anisotropy = 0.8;
    across.anisotropy = 0.5;
    across.anisotropyDirection = glm::dvec3(1.0, 2.0, 0.5);
    sharp.anisotropy = 0.6;
    sharp.anisotropyDirection = glm::dvec3(0.0, 1.0, 0.0);
    expectSamplesFollowThePdf({brushed, across, sharp}, 47);
}

// A transmissive material (KHR_materials_transmission, KHR_materials_ior), seen from outside
// (relative index ior) or from inside (1 / ior).
GltfParams randomTransmissive(std::mt19937& rng, bool inside) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    GltfParams p = randomParams(rng);
    p.metallic = u(rng) < 0.5 ? 0.0 : 0.5 * u(rng);
    p.transmission = 0.2 + 0.8 * u(rng);
    const double ior = 1.1 + u(rng);
    p.ior = inside ? 1.0 / ior : ior;
    return p;
}

glm::dvec3 onSphere(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double z = 2.0 * u(rng) - 1.0, phi = 2.0 * gltfref::kPi * u(rng), r = std::sqrt(1.0 - z * z);
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// Above the surface the BRDF is Appendix B's with the diffuse part weighed by 1 - t and F0 from
// the index; below it, Walter et al.'s BTDF (GltfReference.h, written in their form); seen from
// inside, Fresnel at the angle outside with total internal reflection. The BTDF obeys the
// generalized reciprocity of refraction (Veach 1997, 5.2): f(v -> l) ior^2 = f(l -> v) seen from
// the other side (relative index 1 / ior).
TEST(GltfBrdf, TransmissionIsWaltersBtdfMixedAsTheExtensionSays) {
    std::mt19937 rng(17);
    const glm::dvec3 n(0.0, 0.0, 1.0);
    int below = 0;
    for (int k = 0; k < 4000; ++k) {
        const GltfParams p = randomTransmissive(rng, k % 2 == 1);
        const MaterialRecord m = record(p);
        const glm::dvec3 v = hemisphere(rng), l = onSphere(rng);
        if (std::abs(l.z) < 0.02) continue;
        const glm::vec3 f = l.z > 0.0 ? raymath::gltfBrdf(m, glm::vec3(n), glm::vec3(v), glm::vec3(l))
                                      : raymath::gltfBtdf(m, glm::vec3(n), glm::vec3(v), glm::vec3(l));
        const glm::dvec3 expected = l.z > 0.0 ? gltfReferenceBrdf(p, n, v, l) : gltfReferenceBtdf(p, n, v, l);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], expected[c], 2e-4 + 2e-4 * expected[c]) << k;
        if (l.z > 0.0) continue;
        below += expected[0] + expected[1] + expected[2] > 1e-3;
        GltfParams other = p;
        other.ior = 1.0 / p.ior;
        const glm::vec3 back = raymath::gltfBtdf(record(other), glm::vec3(-n), glm::vec3(l), glm::vec3(v));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], f[c] * float(p.ior * p.ior), 1e-4f + 1e-4f * back[c]) << k;
    }
    EXPECT_GT(below, 200);  // the BTDF was compared where it is not 0 (331 of ~2000 below)
}

// A thin wall (KHR_materials_transmission without a volume): gltfBtdf is the extension's
// specular_btdf written again (the reflection's D V at the light's mirror image), also stretched by
// anisotropy; it is reciprocal (f(l, v) seen from the other side is f(v, l)); a smooth wall passes
// the ray straight on with the weight T at n.v and nothing divided by ior^2, and Whitted's child
// ray does too.
TEST(GltfBrdf, ThinWallIsTheReflectionsLobeMirroredThroughTheSurface) {
    std::mt19937 rng(29);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const glm::dvec3 n(0.0, 0.0, 1.0);
    int below = 0;
    for (int k = 0; k < 4000; ++k) {
        GltfParams p = randomTransmissive(rng, false);
        p.thin = true;
        if (k % 3 == 0) {
            p.anisotropy = u(rng);
            p.anisotropyDirection = glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, 0.0);
        }
        const MaterialRecord m = record(p);
        const glm::dvec3 v = hemisphere(rng), l = onSphere(rng);
        if (l.z > -0.02) continue;
        const glm::vec3 f = raymath::gltfBtdf(m, glm::vec3(n), glm::vec3(v), glm::vec3(l));
        const glm::dvec3 expected = gltfReferenceThinBtdf(p, n, v, l);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], expected[c], 2e-4 + 2e-4 * expected[c]) << k;
        below += expected[0] + expected[1] + expected[2] > 1e-3;
        // Reciprocity: the view l and the light v, about the normal facing l.
        if (p.anisotropy == 0.0) {
            const glm::vec3 back = raymath::gltfBtdf(m, glm::vec3(-n), glm::vec3(l), glm::vec3(v));
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], f[c], 1e-4f + 1e-3f * f[c]) << k;
        }
    }
    EXPECT_GT(below, 500);
    // Smooth: straight on, T at n.v, and the mirror of the rest (the sampler's delta lobes).
    GltfParams p;
    p.base = glm::dvec3(0.9, 0.6, 0.3);
    p.roughness = 0.0;
    p.transmission = 1.0;
    p.ior = 1.5;
    p.thin = true;
    const MaterialRecord m = record(p);
    const glm::vec3 d = glm::normalize(glm::vec3(0.3f, 0.2f, -1.0f));
    const float nv = -d.z;
    int through = 0;
    for (int s = 0; s < 64; ++s) {
        glm::vec3 dir, factor;
        float pdf, side;
        ASSERT_TRUE(raymath::materialSample(m, d, glm::vec3(n), glm::vec3(n), true, glm::vec2(0.5f), (s + 0.5f) / 64.0f, dir,
                                            factor, pdf, side));
        if (side > 0.0f) continue;
        ++through;
        EXPECT_NEAR(glm::length(dir - d), 0.0f, 1e-6f);
        const float pSpecular = raymath::gltfSpecularProbability(m, nv), pr = raymath::gltfReflectProbability(m, nv);
        const glm::dvec3 weight = gltfref::transmissionWeight(p, nv) / (double(pSpecular) * (1.0 - pr));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(factor[c], weight[c], 1e-5) << s;
    }
    EXPECT_GT(through, 32);
    glm::vec3 dirA, weightA, dirB, weightB;
    float sideA;
    raymath::gltfChildren(m, d, glm::vec3(n), glm::vec3(n), glm::vec3(1.0f), dirA, weightA, sideA, dirB, weightB);
    EXPECT_EQ(sideA, -1.0f);
    EXPECT_NEAR(glm::length(dirA - d), 0.0f, 1e-6f);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(weightA[c], gltfref::transmissionWeight(p, nv)[c], 1e-5);
}

// The sampler of a transmissive material: the mean of its throughput factor is the integral of
// f |cos| over the sphere (quadrature of the reference), and its directions follow its pdf over
// the sphere (chi-square as above); a refracted direction reports pdf 0 (light sampling never
// draws it) and leaves on the far side. A smooth one: Fd + (1 - Fd) c / ior^2 at n.v.
TEST(GltfBrdf, TransmissionSamplerEstimatesTheAlbedoAndFollowsThePdf) {
    std::mt19937 rng(23);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const GltfParams cases[] = {
        {glm::dvec3(0.9, 0.8, 0.7), 0.0, 0.4, 1.0, 1.5},        {glm::dvec3(1.0), 0.0, 0.7, 0.6, 1.33},
        {glm::dvec3(0.9, 0.9, 1.0), 0.2, 0.5, 1.0, 1.0 / 1.5}, {glm::dvec3(1.0), 0.0, 0.0, 1.0, 1.5},
        {glm::dvec3(0.8), 0.0, 0.0, 1.0, 1.0 / 1.5},
        {glm::dvec3(0.9, 0.8, 0.7), 0.0, 0.4, 1.0, 1.5},        {glm::dvec3(1.0), 0.0, 0.5, 1.0, 1.0 / 1.5},
    };
    // Two stretched (KHR_materials_anisotropy): the BTDF shares the reflection's lobe; three thin
    // walls (KHR_materials_transmission without a volume), rough, stretched and smooth.
    GltfParams anisotropic[10];
    std::copy(std::begin(cases), std::end(cases), anisotropic);
    anisotropic[5].anisotropy = 0.8;
    anisotropic[6].anisotropy = 0.6;
    anisotropic[6].anisotropyDirection = glm::dvec3(1.0, 1.0, 0.0);
    anisotropic[7] = cases[0];
    anisotropic[8] = cases[1];
    anisotropic[8].anisotropy = 0.7;
    anisotropic[9] = cases[3];
    for (int k = 7; k < 10; ++k) anisotropic[k].thin = true;
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    for (const GltfParams& p : anisotropic) {
        for (const double mu : {0.9, 0.5, 0.2}) {
            SCOPED_TRACE("roughness " + std::to_string(p.roughness) + " ior " + std::to_string(p.ior) + " mu " +
                         std::to_string(mu) + (p.thin ? " thin" : ""));
            const MaterialRecord m = record(p);
            const glm::dvec3 vd(std::sqrt(1.0 - mu * mu), 0.0, mu);
            const glm::vec3 v(vd);
            // The albedo: quadrature over the sphere, or the smooth surface's closed form.
            glm::dvec3 albedo(0.0);
            if (p.roughness > 0.0) {
                const int zs = 1200, phis = 600;
                for (int i = 0; i < zs; ++i)
                    for (int j = 0; j < phis; ++j) {
                        const double z = -1.0 + 2.0 * (i + 0.5) / zs, phi = 2.0 * gltfref::kPi * (j + 0.5) / phis;
                        const double r = std::sqrt(1.0 - z * z);
                        const glm::dvec3 l(r * std::cos(phi), r * std::sin(phi), z);
                        const glm::dvec3 f = z > 0.0 ? gltfReferenceBrdf(p, glm::dvec3(n), vd, l) : gltfReferenceBtdf(p, glm::dvec3(n), vd, l);
                        albedo += f * std::abs(z);
                    }
                albedo *= (2.0 / zs) * (2.0 * gltfref::kPi / phis);
            } else {
                const bool refracts = (1.0 - mu * mu) < p.ior * p.ior;
                albedo = gltfref::specularWeight(p, mu) + gltfref::diffuseWeight(p, mu) +
                         (p.thin ? gltfref::transmissionWeight(p, mu)
                                 : refracts ? gltfref::transmissionWeight(p, mu) / (p.ior * p.ior) : glm::dvec3(0.0));
            }
            const int samples = 300000, cosCells = 48, phiCells = 48;
            std::vector<double> histogram(size_t(cosCells * phiCells), 0.0), expected(histogram.size(), 0.0);
            glm::dvec3 sum(0.0), sum2(0.0);
            int kept = 0;
            for (int s = 0; s < samples; ++s) {
                glm::vec3 dir, factor;
                float pdf, side;
                if (!raymath::materialSample(m, -v, n, n, p.ior > 1.0, glm::vec2(float(u(rng)), float(u(rng))), float(u(rng)), dir,
                                             factor, pdf, side))
                    continue;
                ASSERT_EQ(side < 0.0f, dir.z < 0.0f);
                if (dir.z < 0.0f) {
                    ASSERT_EQ(pdf, 0.0f);
                }
                ++kept;
                sum += glm::dvec3(factor);
                sum2 += glm::dvec3(factor) * glm::dvec3(factor);
                const int i = std::clamp(int((dir.z + 1.0f) * 0.5f * cosCells), 0, cosCells - 1);
                double phi = std::atan2(double(dir.y), double(dir.x));
                if (phi < 0.0) phi += 2.0 * gltfref::kPi;
                const int j = std::min(phiCells - 1, int(phi / (2.0 * gltfref::kPi) * phiCells));
                histogram[size_t(i * phiCells + j)] += 1.0;
            }
            for (int c = 0; c < 3; ++c) {
                const double mean = sum[c] / samples, var = std::max(0.0, sum2[c] / samples - mean * mean);
                EXPECT_NEAR(mean, albedo[c], 5.0 * std::sqrt(var / samples) + 3e-3) << "channel " << c;
            }
            if (p.roughness <= 0.0) continue;  // delta lobes and a cosine lobe: nothing to bin
            const float pSpecular = raymath::gltfSpecularProbability(m, float(mu));
            const double cellArea = 4.0 * gltfref::kPi / (cosCells * phiCells);
            double integral = 0.0;
            for (int i = 0; i < cosCells; ++i)
                for (int j = 0; j < phiCells; ++j) {
                    double pdfSum = 0.0;
                    for (int a = 0; a < 12; ++a)
                        for (int b = 0; b < 12; ++b) {
                            const double z = -1.0 + 2.0 * (i + (a + 0.5) / 12.0) / cosCells;
                            const double phi = 2.0 * gltfref::kPi * (j + (b + 0.5) / 12.0) / phiCells, r = std::sqrt(1.0 - z * z);
                            const glm::vec3 l(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
                            pdfSum += raymath::gltfPdf(m, 0.0f, pSpecular, n, v, l);
                        }
                    const double mass = pdfSum / 144.0 * cellArea;
                    expected[size_t(i * phiCells + j)] = mass * samples;
                    integral += mass;
                }
            EXPECT_NEAR(integral, double(kept) / samples, 0.01);
            const ChiSquare chi = chiSquare(histogram, expected);
            ASSERT_GT(chi.cells, 100);
            EXPECT_LT(chi.statistic, chi.critical) << chi.cells << " cells";
        }
    }
}

// KHR_materials_dispersion's index (common/material.h dispersedIor): the Abbe number its indices
// at the d, F and C lines make, (n_d - 1) / (n_F - n_C), is 20 / dispersion, as the extension
// defines the factor; the d line sees n_d (to the formula's 1.5168, 1.7e-4 off 523655 / 587.6^2);
// no index falls below 1. materialAtChannel gives each channel its wavelength's index, and a record
// seen from inside the solid (materialFacing's 1 / index) one over it.
TEST(GltfBrdf, DispersionKeepsTheAbbeNumberItNames) {
    for (double nd : {1.33, 1.5, 1.7, 2.42})
        for (double dispersion : {0.05, 0.5, 1.0, 5.0}) {
            SCOPED_TRACE(testing::Message() << "n_d " << nd << ", dispersion " << dispersion);
            const double nF = raymath::dispersedIor(float(nd), float(dispersion), 486.1f);
            const double nDLine = raymath::dispersedIor(float(nd), float(dispersion), 587.6f);
            const double nC = raymath::dispersedIor(float(nd), float(dispersion), 656.3f);
            EXPECT_NEAR((nDLine - 1.0) / (nF - nC), 20.0 / dispersion, 2e-3 * 20.0 / dispersion);
            EXPECT_NEAR(nDLine, nd, 2e-4 * (nd - 1.0) * dispersion + 1e-6);
            EXPECT_GT(nF, nDLine);
            EXPECT_LT(nC, nDLine);
        }
    EXPECT_EQ(raymath::dispersedIor(1.05f, 1000.0f, 656.3f), 1.0f);
    MaterialRecord m{};
    m.model = GPURT_MODEL_GLTF;
    m.ior = 1.6f;
    m.dispersion = 2.0f;
    for (int c = 0; c < 3; ++c) {
        const float n = raymath::dispersedIor(1.6f, 2.0f, raymath::channelWavelength(c));
        EXPECT_EQ(raymath::materialAtChannel(m, c).ior, n);
        EXPECT_EQ(raymath::materialAtChannel(m, c).dispersion, 0.0f);
        MaterialRecord inside = m;
        inside.ior = 1.0f / 1.6f;
        EXPECT_NEAR(raymath::materialAtChannel(inside, c).ior, 1.0f / n, 1e-6f);
    }
    EXPECT_EQ(raymath::channelWavelength(0), 656.3f);
    EXPECT_EQ(raymath::channelWavelength(2), 486.1f);
    MaterialRecord still = m;
    still.dispersion = 0.0f;
    EXPECT_EQ(raymath::materialAtChannel(still, 2).ior, 1.6f);
}

// Next-event estimation at a dispersing solid (common/path.h pathLightContribution; lights are
// sampled on the side the ray comes from): each channel of a point light's contribution off a
// rough glass of dispersion 5, seen from outside and from inside (its record as materialFacing
// makes it), is the reference BRDF's at that channel's index (the extension's formula) times
// pi cos I / r^2, as if the glass did not disperse.
TEST(GltfBrdf, DispersingNextEventTakesEachChannelAtItsIndex) {
    std::mt19937 rng(11);
    const glm::vec3 n(0.0f, 0.0f, 1.0f), p(0.0f);
    const double nd = 1.55, dispersion = 5.0, lambdas[3] = {656.3, 587.6, 486.1};
    for (int k = 0; k < 500; ++k) {
        const bool inside = k % 2 == 1;
        GltfParams glass{glm::dvec3(0.9, 0.8, 0.7), 0.0, 0.35};
        glass.transmission = 1.0;
        glass.ior = inside ? 1.0 / nd : nd;
        MaterialRecord m = record(glass);
        m.dispersion = float(dispersion);
        const glm::dvec3 v = hemisphere(rng), l = hemisphere(rng);
        const double dist = 2.5;
        const glm::vec3 light = p + glm::vec3(l) * float(dist);
        const glm::vec3 got = raymath::pathLightContribution(m, p, n, -glm::vec3(v), light, glm::vec3(1.0f), 3.0f);
        for (int c = 0; c < 3; ++c) {
            GltfParams at = glass;
            const double nc = gltfref::specDispersedIor(nd, dispersion, lambdas[c]);
            at.ior = inside ? 1.0 / nc : nc;
            // A point light of intensity I gives pi I / r^2 (common/path.h, units).
            const double expected = gltfReferenceBrdf(at, glm::dvec3(n), v, l)[c] * l.z * gltfref::kPi * 3.0 / (dist * dist);
            EXPECT_NEAR(got[c], expected, 2e-3 * expected + 1e-5) << k << " channel " << c;
        }
    }
}

}  // namespace
}  // namespace gpurt::test
