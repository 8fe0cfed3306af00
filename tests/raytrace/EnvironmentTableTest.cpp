// The environment light's table without GL (raytrace/EnvironmentTable, glsl/common/environment.h):
// the maps read back from .hdr and .exr files the test writes, the direction convention against
// the contract's formula, the sampling pdf against itself and against the sphere (it integrates
// to 1), and the cost of building the table for a 2048 x 1024 map (docs/PERFORMANCE.md).
#include "EnvironmentTestMaps.h"

#include "raytrace/EnvironmentTable.h"
#include "raytrace/RayMath.h"

#include <gtest/gtest.h>

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

// The cost of the table of a 2048 x 1024 map: the sampling distribution (the 3 x 3 maxima, the
// rows' and columns' cumulative sums) and the spherical harmonics, apart; printed for
// docs/PERFORMANCE.md and bounded loosely (a slow machine shared with other builds).
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
    EXPECT_LT(ms[1], 5000.0);
}

}  // namespace
}  // namespace gpurt::test
