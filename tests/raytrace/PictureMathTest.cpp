// The math of the pictures against independent formulas, without GL: the dielectric Fresnel
// reflectance (against the Fresnel equations in their angle form), Snell's law and the critical
// angle, the ray tree's children, the stratification of the sample patterns, the tone map's
// fixed points, and smooth vertex normals on a cube and a sphere.
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "image/Colour.h"
#include "raytrace/common/RayMath.h"
#include "scene/SmoothNormals.h"

namespace gpurt::raymath {
#include "../../glsl/common/shading.h"
}  // namespace gpurt::raymath

namespace gpurt {
namespace {

using namespace raymath;

// Unpolarised reflectance from the Fresnel equations in their angle form (Hecht, Optics):
// Rs = sin^2(ti - tt) / sin^2(ti + tt), Rp = tan^2(ti - tt) / tan^2(ti + tt), in double.
double fresnelByAngles(double thetaI, double eta) {
    const double sinT = std::sin(thetaI) / eta;
    if (sinT >= 1.0) return 1.0;
    const double thetaT = std::asin(sinT);
    if (thetaI == 0.0) return std::pow((eta - 1.0) / (eta + 1.0), 2.0);  // the limit at normal incidence
    const double rs = std::pow(std::sin(thetaI - thetaT) / std::sin(thetaI + thetaT), 2.0);
    const double rp = std::pow(std::tan(thetaI - thetaT) / std::tan(thetaI + thetaT), 2.0);
    return 0.5 * (rs + rp);
}

TEST(PictureMath, FresnelReflectanceMatchesTheFresnelEquations) {
    for (double eta : {1.33, 1.5, 2.42, 1.0 / 1.5, 1.0 / 2.42}) {
        for (double degrees : {0.0, 10.0, 30.0, 45.0, 60.0, 75.0, 85.0, 89.0}) {
            const double theta = degrees * M_PI / 180.0;
            const double expected = fresnelByAngles(theta, eta);
            EXPECT_NEAR(fresnelDielectric(float(std::cos(theta)), float(eta)), expected, 2e-5)
                << "eta " << eta << " at " << degrees << " degrees";
        }
    }
    EXPECT_NEAR(fresnelDielectric(1.0f, 1.5f), 0.04f, 1e-6f);  // ((n - 1) / (n + 1))^2
    EXPECT_NEAR(fresnelDielectric(0.0f, 1.5f), 1.0f, 1e-6f);   // grazing: all reflected
}

TEST(PictureMath, TotalInternalReflectionBeyondTheCriticalAngle) {
    for (double n : {1.33, 1.5, 2.42}) {
        const double critical = std::asin(1.0 / n);  // leaving the denser medium
        const float eta = float(1.0 / n);
        EXPECT_LT(fresnelDielectric(float(std::cos(critical - 1e-3)), eta), 1.0f) << n;
        EXPECT_EQ(fresnelDielectric(float(std::cos(critical + 1e-3)), eta), 1.0f) << n;
        // The reflectance rises steeply towards 1 at the critical angle.
        EXPECT_GT(fresnelDielectric(float(std::cos(critical - 1e-4)), eta),
                  fresnelDielectric(float(std::cos(critical - 1e-2)), eta) + 0.3f) << n;
    }
}

TEST(PictureMath, RefractionFollowsSnellsLaw) {
    const vec3 n(0.0f, 0.0f, 1.0f);  // facing the incoming rays (they travel towards -z)
    for (float eta : {1.5f, 1.33f, 1.0f / 1.5f}) {
        for (double degrees : {0.0, 20.0, 40.0}) {
            const double theta = degrees * M_PI / 180.0;
            const vec3 d(float(std::sin(theta)), 0.0f, float(-std::cos(theta)));
            const float cosI = -dot(d, n);
            ASSERT_LT(fresnelDielectric(cosI, eta), 1.0f);
            const vec3 t = refractedDirection(d, n, eta, cosI);
            EXPECT_NEAR(length(t), 1.0f, 1e-6f);
            EXPECT_LT(t.z, 0.0f);                          // on the far side
            EXPECT_NEAR(t.y, 0.0f, 1e-7f);                 // in the plane of incidence
            EXPECT_GE(t.x * d.x, 0.0f);                    // on the same side of the normal
            EXPECT_NEAR(double(eta) * std::sqrt(double(t.x) * t.x + double(t.y) * t.y), std::sin(theta), 2e-6)
                << "eta " << eta << " at " << degrees;
        }
    }
}

TEST(PictureMath, GlassSplitsItsWeightBetweenItsChildren) {
    const vec3 ng(0.0f, 0.0f, 1.0f), w(0.5f, 1.0f, 0.25f), tf(1.0f);
    const vec3 d = normalize(vec3(0.3f, 0.0f, -1.0f));
    vec3 dirA, weightA, dirB, weightB;
    float sideA;
    ASSERT_EQ(hitChildren(d, ng, ng, true, vec3(0.0f), 1.5f, tf, w, dirA, weightA, sideA, dirB, weightB), 2);
    EXPECT_EQ(sideA, -1.0f);  // the refracted ray leaves on the far side
    EXPECT_LT(dirA.z, 0.0f);
    EXPECT_GT(dirB.z, 0.0f);
    const float f = fresnelDielectric(-d.z, 1.5f);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(weightA[c] + weightB[c], w[c], 1e-6f);  // a filter of 1 loses nothing
        EXPECT_NEAR(weightB[c], w[c] * f, 1e-7f);
    }
    // From inside beyond the critical angle: one child, the reflection, with all of the weight.
    const vec3 steep = normalize(vec3(1.0f, 0.0f, -0.5f));
    ASSERT_EQ(hitChildren(steep, ng, ng, false, vec3(0.0f), 1.5f, tf, w, dirA, weightA, sideA, dirB, weightB), 1);
    EXPECT_EQ(sideA, 1.0f);
    EXPECT_EQ(weightA, w);
    EXPECT_NEAR(dirA.z, -steep.z, 1e-6f);
    // A mirror: its reflectivity; a diffuse surface: no child.
    EXPECT_EQ(hitChildren(d, ng, ng, true, vec3(0.5f), 0.0f, tf, w, dirA, weightA, sideA, dirB, weightB), 1);
    EXPECT_EQ(weightA, w * 0.5f);
    EXPECT_EQ(hitChildren(d, ng, ng, true, vec3(0.0f), 0.0f, tf, w, dirA, weightA, sideA, dirB, weightB), 0);
}

// Kensler's pattern is stratified in 2D and in each 1D projection: every sample in its own row
// of height 1/n, its own column of width 1/(m k), and its own cell of the m x k grid.
TEST(PictureMath, SamplePatternsAreStratified) {
    for (uint32_t n : {2u, 3u, 7u, 16u, 25u, 64u, 100u, 1000u}) {
        const uint32_t m = uint32_t(std::sqrt(float(n))), k = (n + m - 1) / m;
        for (uint32_t pattern : {0u, 1u, 0xdeadbeefu}) {
            std::set<uint32_t> rows, columns, cells;
            for (uint32_t s = 0; s < n; ++s) {
                const vec2 p = cmjSample(s, n, pattern);
                ASSERT_TRUE(p.x >= 0.0f && p.x < 1.0f && p.y >= 0.0f && p.y < 1.0f) << n << " " << s;
                rows.insert(uint32_t(double(p.y) * n));
                columns.insert(uint32_t(double(p.x) * m * k));
                cells.insert(uint32_t(double(p.x) * m) * k + uint32_t(double(p.y) * k));
            }
            EXPECT_EQ(rows.size(), n) << n;
            EXPECT_EQ(columns.size(), n) << n;
            EXPECT_EQ(cells.size(), n) << n;
        }
    }
    // One sample is the pixel centre, for every sampler; the patterns of neighbouring pixels differ.
    for (uint32_t sampler : {GPURT_SAMPLER_SOBOL, GPURT_SAMPLER_STRATIFIED, GPURT_SAMPLER_RANDOM}) {
        EXPECT_EQ(pixelSampleOffset(sampler, 3, 4, 0, 1, 7), vec2(0.5f));
        EXPECT_NE(pixelSampleOffset(sampler, 3, 4, 0, 4, 7), pixelSampleOffset(sampler, 4, 4, 0, 4, 7));
        EXPECT_NE(pixelSampleOffset(sampler, 3, 4, 0, 4, 7), pixelSampleOffset(sampler, 3, 4, 0, 4, 8));
    }
}

// Whether `points` (2^k of them in [0, 1)^2) form a (0, k, 2)-net: every elementary interval of
// area 2^-k (2^a columns x 2^(k-a) rows, each a) holds exactly one point.
bool isZeroNet(const std::vector<vec2>& points, uint32_t k) {
    for (uint32_t a = 0; a <= k; ++a) {
        std::set<uint64_t> cells;
        for (const vec2& p : points) {
            if (!(p.x >= 0.0f && p.x < 1.0f && p.y >= 0.0f && p.y < 1.0f)) return false;
            const uint64_t column = uint64_t(std::ldexp(double(p.x), int(a)));
            const uint64_t row = uint64_t(std::ldexp(double(p.y), int(k - a)));
            cells.insert((column << 32) | row);
        }
        if (cells.size() != points.size()) return false;
    }
    return true;
}

// The sobol sampler: every prefix of 2^k samples of every 2D dimension is a (0, k, 2)-net (what
// lets an adaptive render stop a pixel after any power of two); so is each later aligned block of
// 2^k (the rounds of 16 samples an adaptive render adds). The values are pure functions of
// (pixel, index, seed, dimension), and differ between dimensions and seeds.
TEST(PictureMath, SobolPrefixesAreZeroNets) {
    const uint32_t dims[] = {GPURT_DIM_PIXEL, GPURT_DIM_EMITTER, GPURT_DIM_EMITTER + 3u, GPURT_DIM_SCATTER,
                             GPURT_DIM_SCATTER + 1u, GPURT_DIM_ENVIRONMENT + 7u};
    for (uint32_t seed : {0u, 1u, 12345u}) {
        for (uint32_t dim : dims) {
            for (uint32_t k = 0; k <= 10; ++k) {
                const uint32_t n = 1u << k;
                for (uint32_t block : {0u, 1u, 5u}) {
                    if (block > 0 && k > 6) continue;
                    std::vector<vec2> points;
                    for (uint32_t s = block * n; s < (block + 1) * n; ++s)
                        points.push_back(sample2D(GPURT_SAMPLER_SOBOL, 17, 9, s, 1024, seed, dim));
                    EXPECT_TRUE(isZeroNet(points, k)) << "seed " << seed << " dim " << dim << " k " << k << " block " << block;
                }
            }
        }
    }
    // Pure: the same key gives the same value; another dimension, seed or pixel another value.
    const vec2 a = sample2D(GPURT_SAMPLER_SOBOL, 17, 9, 5, 64, 3, GPURT_DIM_SCATTER);
    EXPECT_EQ(a, sample2D(GPURT_SAMPLER_SOBOL, 17, 9, 5, 64, 3, GPURT_DIM_SCATTER));
    EXPECT_EQ(a, sample2D(GPURT_SAMPLER_SOBOL, 17, 9, 5, 4096, 3, GPURT_DIM_SCATTER));  // no count needed
    EXPECT_NE(a, sample2D(GPURT_SAMPLER_SOBOL, 17, 9, 5, 64, 3, GPURT_DIM_SCATTER + 2u));
    EXPECT_NE(a, sample2D(GPURT_SAMPLER_SOBOL, 17, 9, 5, 64, 4, GPURT_DIM_SCATTER));
    EXPECT_NE(a, sample2D(GPURT_SAMPLER_SOBOL, 18, 9, 5, 64, 3, GPURT_DIM_SCATTER));
    // The scramble is a bijection of the 32-bit words (spot check: distinct inputs, distinct outputs).
    std::set<uint32_t> images;
    for (uint32_t x = 0; x < 4096; ++x) images.insert(owenScramble(x * 0x9e3779b9u, 0x1234567u));
    EXPECT_EQ(images.size(), 4096u);
}

// Dimensions are decorrelated: over many pixels, the correlation between the first coordinate of
// two dimensions of the same sample is near 0 (bound: 5 standard errors of a correlation of
// independent numbers, 5 / sqrt(N)); the random sampler's pairs likewise.
TEST(PictureMath, SampleDimensionsAreUncorrelated) {
    for (uint32_t sampler : {GPURT_SAMPLER_SOBOL, GPURT_SAMPLER_RANDOM, GPURT_SAMPLER_STRATIFIED}) {
        const int n = 64 * 64 * 4;
        double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
        for (uint32_t y = 0; y < 64; ++y)
            for (uint32_t x = 0; x < 64; ++x)
                for (uint32_t s = 0; s < 4; ++s) {
                    const double u = sample2D(sampler, x, y, s, 4, 0, GPURT_DIM_SCATTER).x;
                    const double v = sample2D(sampler, x, y, s, 4, 0, GPURT_DIM_SCATTER + 2u).x;
                    sx += u, sy += v, sxx += u * u, syy += v * v, sxy += u * v;
                }
        const double cov = sxy / n - (sx / n) * (sy / n);
        const double r = cov / std::sqrt((sxx / n - sx / n * sx / n) * (syy / n - sy / n * sy / n));
        EXPECT_LT(std::abs(r), 5.0 / std::sqrt(double(n))) << sampler;
    }
}

TEST(PictureMath, ToneMapsKeepBlackAndTheirRanges) {
    const std::vector<glm::vec3> linear = {glm::vec3(0.0f), glm::vec3(0.18f), glm::vec3(1.0f), glm::vec3(100.0f),
                                           glm::vec3(NAN, -1.0f, 0.5f)};
    for (ToneMap mode : {ToneMap::Clamp, ToneMap::Reinhard, ToneMap::Aces}) {
        const std::vector<glm::vec3> out = toneMapImage(linear, {0.0f, mode});
        EXPECT_EQ(out[0], glm::vec3(0.0f)) << toneMapName(mode);
        EXPECT_EQ(out[4].x, 0.0f) << toneMapName(mode);  // NaN and negative give black
        EXPECT_EQ(out[4].y, 0.0f) << toneMapName(mode);
        for (const glm::vec3& c : out) EXPECT_TRUE(c.x >= 0.0f && c.x <= 1.0f) << toneMapName(mode);
        EXPECT_LT(out[1].x, out[2].x) << toneMapName(mode);  // increasing
    }
    EXPECT_EQ(toneMapImage(linear, {0.0f, ToneMap::Clamp})[1].x, 0.18f);
    EXPECT_NEAR(toneMapImage(linear, {0.0f, ToneMap::Reinhard})[2].x, 0.5f, 1e-7f);
    // Narkowicz's curve: f(1) = 2.54 / 3.16.
    EXPECT_NEAR(toneMapImage(linear, {0.0f, ToneMap::Aces})[2].x, 2.54 / 3.16, 1e-6);
    // Exposure: +1 EV doubles the linear value before the tone map.
    EXPECT_EQ(toneMapImage({glm::vec3(0.25f)}, {1.0f, ToneMap::Clamp})[0].x, 0.5f);
}

Scene cube() {
    Scene scene;
    const glm::vec3 c[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};
    for (const auto& f : faces) {
        scene.triangles.push_back({c[f[0]], c[f[1]], c[f[2]]});
        scene.triangles.push_back({c[f[0]], c[f[2]], c[f[3]]});
    }
    scene.materialIds.assign(scene.triangles.size(), 0);
    scene.materials.push_back(Material{});
    return scene;
}

Scene sphere(int segments, int rings) {
    Scene scene;
    auto at = [&](int r, int k) {
        const double theta = M_PI * r / rings, phi = 2 * M_PI * (k % segments) / segments;  // one seam vertex
        return glm::vec3(glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
    };
    for (int r = 0; r < rings; ++r)
        for (int k = 0; k < segments; ++k) {
            if (r > 0) scene.triangles.push_back({at(r, k), at(r, k + 1), at(r + 1, k + 1)});
            if (r < rings - 1) scene.triangles.push_back({at(r, k), at(r + 1, k + 1), at(r + 1, k)});
        }
    scene.materialIds.assign(scene.triangles.size(), 0);
    scene.materials.push_back(Material{});
    return scene;
}

TEST(PictureMath, SmoothNormalsKeepACubesEdgesAndRoundASphere) {
    Scene box = cube();
    smoothNormals(box, kDefaultCreaseDegrees);
    ASSERT_EQ(box.normals.size(), box.triangles.size());
    for (size_t t = 0; t < box.triangles.size(); ++t) {
        const Triangle& tri = box.triangles[t];
        const glm::vec3 face = glm::normalize(glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0));
        for (const glm::vec3& n : {box.normals[t].n0, box.normals[t].n1, box.normals[t].n2})
            EXPECT_NEAR(glm::dot(n, face), 1.0f, 1e-6f) << "triangle " << t;  // 90-degree edges stay sharp
    }
    Scene ball = sphere(32, 16);
    smoothNormals(ball, kDefaultCreaseDegrees);
    double worst = 0.0, worstAwayFromPoles = 0.0;
    for (size_t t = 0; t < ball.triangles.size(); ++t) {
        const Triangle& tri = ball.triangles[t];
        const glm::vec3 p[3] = {tri.v0, tri.v1, tri.v2};
        const glm::vec3 n[3] = {ball.normals[t].n0, ball.normals[t].n1, ball.normals[t].n2};
        for (int k = 0; k < 3; ++k) {
            const double error = std::acos(std::min(1.0, double(glm::dot(n[k], glm::normalize(p[k])))));
            worst = std::max(worst, error);
            // Beyond the first ring the faces around a vertex are alike and the angle-weighted
            // normal is radial; next to the poles the fan's wide angles pull it poleward.
            if (std::fabs(p[k].y) < std::cos(2.5 * M_PI / 16)) worstAwayFromPoles = std::max(worstAwayFromPoles, error);
            EXPECT_NEAR(glm::length(n[k]), 1.0f, 1e-5f);
        }
    }
    EXPECT_LT(worstAwayFromPoles * 180.0 / M_PI, 1.0);
    EXPECT_LT(worst * 180.0 / M_PI, 180.0 / 16 / 2 + 0.1);  // within half the ring spacing
    // Given normals stay; off drops every normal.
    Scene given = cube();
    given.normals.assign(given.triangles.size(), TriangleNormals{});
    given.normals[0] = {glm::vec3(0, 0, 1), glm::vec3(0, 1, 0), glm::vec3(1, 0, 0)};
    smoothNormals(given, kDefaultCreaseDegrees);
    EXPECT_EQ(given.normals[0].n1, glm::vec3(0, 1, 0));
    EXPECT_TRUE(given.normals[1].given());  // filled in
    smoothNormals(given, -1.0f);
    EXPECT_TRUE(given.normals.empty());
}

}  // namespace
}  // namespace gpurt
