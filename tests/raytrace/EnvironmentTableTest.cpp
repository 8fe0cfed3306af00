// The environment light's table without GL (raytrace/EnvironmentTable, glsl/common/environment.h):
// the maps read back from .hdr and .exr files the test writes, the direction convention against
// the contract's formula, the sampling pdf against itself and against the sphere (it integrates
// to 1), the table against its definition computed texel by texel, and the cost of building the
// table for a 2048 x 1024 map (docs/PERFORMANCE.md).
#include "EnvironmentTestMaps.h"

#include "raytrace/lights/EnvironmentTable.h"
#include "raytrace/common/RayMath.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iostream>
#include <random>

namespace gpurt::test {
namespace {

EnvironmentImage sunAndSky(int width) {
    const glm::vec3 sun = glm::normalize(glm::vec3(0.3f, 0.8f, -0.5f));
    return makeMap(width, width / 2, [&](glm::vec3 d) {
        return glm::vec3(0.2f + 0.1f * d.y, 0.3f, 0.4f) + (glm::dot(d, sun) > 0.995f ? glm::vec3(300.0f) : glm::vec3(0.0f));
    });
}

TEST(EnvironmentTable, FilesReadBackAsWritten) {
    const EnvironmentImage image = sunAndSky(64);
    const Environment exr = environmentThroughFile(image, "back.exr");
    ASSERT_EQ(exr.image->width, 64);
    ASSERT_EQ(exr.image->height, 32);
    EXPECT_EQ(exr.image->texels, image.texels);  // 32-bit float: exact
    const Environment hdr = environmentThroughFile(image, "back.hdr");
    ASSERT_EQ(hdr.image->texels.size(), image.texels.size());
    for (size_t k = 0; k < image.texels.size(); ++k)
        for (int c = 0; c < 3; ++c)  // RGBE: 8 bits of mantissa shared by the channels
            ASSERT_NEAR(hdr.image->texels[k][c], image.texels[k][c], 0.5f / 128.0f * std::max(image.texels[k].x, std::max(image.texels[k].y, image.texels[k].z)));
}

// environmentUv is the contract's formula; environmentDirection its inverse; the rotation turns
// counter-clockwise seen from above (+x to -z at 90 degrees).
TEST(EnvironmentTable, DirectionsFollowTheContract) {
    const double pi = 3.14159265358979323846;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int k = 0; k < 1000; ++k) {
        const glm::vec2 uv(unit(rng), unit(rng));
        const glm::vec3 d = raymath::environmentDirection(uv, glm::vec2(1.0f, 0.0f));
        const glm::vec3 expected = contractDirection(uv.x, uv.y);
        ASSERT_NEAR(glm::length(d - expected), 0.0f, 1e-5f);
        const glm::vec2 back = raymath::environmentUv(d, glm::vec2(1.0f, 0.0f));
        const double u = 0.5 + std::atan2(double(d.x), -double(d.z)) / (2.0 * pi), v = std::acos(double(d.y)) / pi;
        ASSERT_NEAR(back.x, u, 1e-5);
        ASSERT_NEAR(back.y, v, 1e-5);
    }
    const glm::vec2 quarter(std::cos(float(pi / 2)), std::sin(float(pi / 2)));
    // What the map shows at +x (u = 0.75, v = 0.5) the scene sees at -z.
    const glm::vec3 turned = raymath::environmentDirection(glm::vec2(0.75f, 0.5f), quarter);
    EXPECT_NEAR(glm::length(turned - glm::vec3(0.0f, 0.0f, -1.0f)), 0.0f, 1e-5f);
    const glm::vec2 at = raymath::environmentUv(glm::vec3(0.0f, 0.0f, -1.0f), quarter);
    EXPECT_NEAR(at.x, 0.75f, 1e-5f);
}

// sample() gives the pdf that pdf() gives its direction, and the pdf integrates to 1 over the
// sphere (a quadrature far finer than the map).
TEST(EnvironmentTable, SamplesCarryTheirPdfWhichIntegratesToOne) {
    Scene scene;
    scene.environment = environmentThroughFile(sunAndSky(128), "pdf.exr", 1.0f, 37.0f);
    const EnvironmentTable table = buildEnvironmentTable(scene);
    ASSERT_TRUE(table.sampled);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int agree = 0;
    for (int k = 0; k < 2000; ++k) {
        glm::vec3 dir;
        float pdf;
        ASSERT_TRUE(table.sample(glm::vec2(unit(rng), unit(rng)), dir, pdf));
        ASSERT_NEAR(glm::length(dir), 1.0f, 1e-5f);
        agree += std::abs(table.pdf(dir) - pdf) <= 1e-3f * pdf;  // texel borders may round across
    }
    EXPECT_GT(agree, 1990);
    const double pi = 3.14159265358979323846;
    const int n = 1024;
    double integral = 0.0;
    for (int j = 0; j < n; ++j) {
        const double theta = (j + 0.5) / n * pi;
        for (int i = 0; i < 2 * n; ++i) {
            const double phi = (i + 0.5) / (2 * n) * 2.0 * pi;
            const glm::vec3 d(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)), float(std::sin(theta) * std::sin(phi)));
            integral += table.pdf(d) * std::sin(theta) * (pi / n) * (pi / n);
        }
    }
    EXPECT_NEAR(integral, 1.0, 2e-3);
}

// The table against the definitions computed directly, texel by texel, in double: the radiance
// times the strength; each texel's weight (the largest luminance of its 3 x 3 neighbourhood,
// wrapping across u and clamped at the poles, times sin(theta) at its row's centre), its density
// W H weight / total, the rows' and columns' cumulative shares (uniform in a row without light);
// the 9 spherical harmonics as the sum over the texels of the basis at each texel centre's
// direction times the radiance and the texel's solid angle. A width of 37 leaves a column beyond
// the groups of 4 and the bottom rows are black.
TEST(EnvironmentTable, MatchesItsDefinitionTexelByTexel) {
    const double pi = 3.14159265358979323846;
    const int w = 37, h = 19;
    const glm::vec3 sun = glm::normalize(glm::vec3(-0.4f, 0.5f, 0.6f));
    auto image = std::make_shared<EnvironmentImage>(makeMap(w, h, [&](glm::vec3 d) {
        if (d.y < -0.75f) return glm::vec3(0.0f);
        return glm::vec3(0.3f + 0.2f * d.x, 0.5f + 0.4f * d.z * d.y, 0.2f + 0.1f * d.y) +
               (glm::dot(d, sun) > 0.97f ? glm::vec3(80.0f, 60.0f, 40.0f) : glm::vec3(0.0f));
    }));
    Scene scene;
    Environment env;
    env.image = image;
    env.strength = 1.7f;
    env.rotation = 37.0f;
    scene.environment = env;
    const EnvironmentTable table = buildEnvironmentTable(scene);
    ASSERT_EQ(table.width, w);
    ASSERT_EQ(table.height, h);
    ASSERT_TRUE(table.sampled);
    ASSERT_EQ(table.texels.size(), size_t(w * h));
    ASSERT_EQ(table.conditional.size(), size_t(w * h));
    ASSERT_EQ(table.marginal.size(), size_t(h));
    auto at = [&](int i, int j) { return size_t(j) * size_t(w) + size_t(i); };
    std::vector<double> luminance(size_t(w * h)), weight(size_t(w * h)), rowSum(size_t(h), 0.0);
    for (size_t k = 0; k < luminance.size(); ++k) {
        const glm::vec3 c = image->texels[k] * 1.7f;
        luminance[k] = 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
    }
    double total = 0.0;
    for (int j = 0; j < h; ++j) {
        const double s = std::sin((j + 0.5) / h * pi);
        for (int i = 0; i < w; ++i) {
            double m = 0.0;
            for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di)
                    m = std::max(m, luminance[at((i + di + w) % w, std::clamp(j + dj, 0, h - 1))]);
            weight[at(i, j)] = m * s;
            rowSum[size_t(j)] += m * s;
        }
        total += rowSum[size_t(j)];
    }
    ASSERT_EQ(rowSum[h - 1], 0.0);  // the bottom rows without light
    double rowsBefore = 0.0;
    for (int j = 0; j < h; ++j) {
        rowsBefore += rowSum[size_t(j)];
        ASSERT_NEAR(table.marginal[size_t(j)], rowsBefore / total, 1e-6) << "row " << j;
        double columnsBefore = 0.0;
        for (int i = 0; i < w; ++i) {
            const glm::vec4 texel = table.texels[at(i, j)];
            const glm::vec3 expected = image->texels[at(i, j)] * 1.7f;
            ASSERT_EQ(glm::vec3(texel), expected) << i << " " << j;
            const double density = weight[at(i, j)] * w * h / total;
            ASSERT_NEAR(texel.w, density, 1e-5 * density) << i << " " << j;
            columnsBefore += weight[at(i, j)];
            const double share = rowSum[size_t(j)] > 0.0 ? columnsBefore / rowSum[size_t(j)] : (i + 1.0) / w;
            ASSERT_NEAR(table.conditional[at(i, j)], share, 1e-6) << i << " " << j;
        }
        ASSERT_EQ(table.conditional[at(w - 1, j)], 1.0f);
    }
    ASSERT_EQ(table.marginal[h - 1], 1.0f);
    const double a = 37.0 * pi / 180.0, rc = std::cos(a), rs = std::sin(a);
    std::array<glm::dvec3, 9> harmonics{};
    for (int j = 0; j < h; ++j) {
        const double theta = (j + 0.5) / h * pi;
        const double dOmega = 2.0 * pi / w * (std::cos(j * pi / h) - std::cos((j + 1) * pi / h));
        for (int i = 0; i < w; ++i) {
            const double phi = ((i + 0.5) / w - 0.5) * 2.0 * pi;
            // The map's direction (contractDirection), turned counter-clockwise about +y by a.
            const double mx = std::sin(theta) * std::sin(phi), my = std::cos(theta), mz = -std::sin(theta) * std::cos(phi);
            const double x = rc * mx + rs * mz, y = my, z = rc * mz - rs * mx;
            const double basis[9] = {0.282095,          0.488603 * y,      0.488603 * z,
                                     0.488603 * x,      1.092548 * x * y,  1.092548 * y * z,
                                     0.315392 * (3.0 * z * z - 1.0), 1.092548 * x * z, 0.546274 * (x * x - y * y)};
            const glm::dvec3 L(image->texels[at(i, j)] * 1.7f);
            for (int k = 0; k < 9; ++k) harmonics[size_t(k)] += L * (basis[k] * dOmega);
        }
    }
    for (int k = 0; k < 9; ++k)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(table.harmonics[size_t(k)][c], harmonics[size_t(k)][c], 1e-5 * harmonics[0][c]) << "c" << k << " channel " << c;
}

// A map without light has no distribution: nothing to sample, pdf 0 everywhere.
TEST(EnvironmentTable, ABlackMapHasNoDistribution) {
    auto image = std::make_shared<EnvironmentImage>(makeMap(16, 8, [](glm::vec3) { return glm::vec3(0.0f); }));
    Scene scene;
    Environment env;
    env.image = image;
    scene.environment = env;
    const EnvironmentTable table = buildEnvironmentTable(scene);
    EXPECT_FALSE(table.sampled);
    EXPECT_TRUE(table.conditional.empty());
    EXPECT_TRUE(table.marginal.empty());
    for (const glm::vec4& t : table.texels) ASSERT_EQ(t, glm::vec4(0.0f));
    glm::vec3 dir;
    float pdf = 1.0f;
    EXPECT_FALSE(table.sample(glm::vec2(0.5f), dir, pdf));
    EXPECT_EQ(pdf, 0.0f);
    EXPECT_EQ(table.pdf(glm::vec3(0.0f, 1.0f, 0.0f)), 0.0f);
}

// The cost of the table of a 2048 x 1024 map: the sampling distribution (the 3 x 3 maxima, the
// rows' and columns' cumulative sums) and the spherical harmonics, apart; printed for
// docs/PERFORMANCE.md, a measurement only (no bound on the time: speed is measured, not asserted).
TEST(EnvironmentTable, BuildTimeOfA2kMap) {
    auto image = std::make_shared<EnvironmentImage>(sunAndSky(2048));
    Scene scene;
    Environment env;
    env.image = image;
    scene.environment = env;
    double ms[2] = {1e30, 1e30};
    for (int run = 0; run < 3; ++run)
        for (int sampled = 0; sampled < 2; ++sampled) {
            scene.environment->sampled = sampled == 1;
            const auto start = std::chrono::steady_clock::now();
            const EnvironmentTable table = buildEnvironmentTable(scene);
            ms[sampled] = std::min(ms[sampled], std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
            ASSERT_EQ(table.sampled, sampled == 1);
        }
    std::cout << "[ environment table 2048x1024 ] without the distribution (texels, harmonics) " << ms[0]
              << " ms, with it " << ms[1] << " ms: the distribution " << ms[1] - ms[0] << " ms\n";
}

}  // namespace
}  // namespace gpurt::test
