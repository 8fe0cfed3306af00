// The path integrator's surface model (glsl/common/path.h) against independent computations,
// without GL: the pdfs integrate to the lobes' shares (quadrature), the directions scatterPath
// draws follow the pdf it reports (the mean of f cos / pdf over many draws is the albedo that
// quadrature gives), glass reflects with probability F, the basis and the MIS weights.
#include <cmath>

#include <gtest/gtest.h>

#include "raytrace/common/RayMath.h"

namespace gpurt::raymath {
#include "../../glsl/common/shading.h"
#include "../../glsl/common/path.h"
}  // namespace gpurt::raymath

namespace gpurt {
namespace {

using namespace raymath;

// The integral of g over the unit sphere by the midpoint rule in (theta, phi) about +z (even
// steps in theta resolve lobes peaked about the pole).
template <typename G>
double sphereIntegral(G g, int steps = 1000) {
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double theta = (i + 0.5) * M_PI / steps;
        const double z = std::cos(theta), r = std::sin(theta);
        double ring = 0.0;
        for (int j = 0; j < 2 * steps; ++j) {
            const double phi = (j + 0.5) * M_PI / steps;
            ring += g(glm::vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)));
        }
        sum += ring * r;
    }
    return sum * (M_PI / steps) * (M_PI / steps);
}

const glm::vec3 kNormal(0.0f, 0.0f, 1.0f);

TEST(PathMath, PdfsIntegrateToTheShareOfTheirLobes) {
    // Seen head on, the glossy lobe about the mirror direction (the normal) lies in the hemisphere.
    const glm::vec3 probs(0.5f, 0.3f, 0.2f);
    for (float ns : {1.0f, 20.0f, 200.0f}) {
        const double total = sphereIntegral([&](glm::vec3 wi) { return double(bsdfPdf(probs, ns, kNormal, -kNormal, wi)); });
        EXPECT_NEAR(total, 0.8, 2e-3) << "ns " << ns;
    }
    const double diffuse = sphereIntegral([&](glm::vec3 wi) {
        return double(bsdfPdf(glm::vec3(1.0f, 0.0f, 0.0f), 1.0f, kNormal, glm::normalize(glm::vec3(1, 0, -1)), wi));
    });
    EXPECT_NEAR(diffuse, 1.0, 1e-3);
}

// Draws of scatterPath from well-spread numbers: the mean factor (0 for a path that ends) is the
// directional albedo: the reflectivity (delta) plus the integral of f cos over the hemisphere.
TEST(PathMath, ScatteredDirectionsFollowTheirPdf) {
    struct Case {
        glm::vec3 kd, ks, reflectivity;
        float ns;
        glm::vec3 d;
    };
    const Case cases[] = {
        {glm::vec3(0.5f, 0.2f, 0.1f), glm::vec3(0.3f), glm::vec3(0.0f), 30.0f, glm::normalize(glm::vec3(0.3f, 0.0f, -1.0f))},
        {glm::vec3(0.1f), glm::vec3(0.6f), glm::vec3(0.0f), 5.0f, glm::normalize(glm::vec3(1.0f, 0.5f, -0.4f))},
        {glm::vec3(0.4f), glm::vec3(0.0f), glm::vec3(0.3f, 0.5f, 0.2f), 1.0f, glm::normalize(glm::vec3(-0.2f, 0.1f, -1.0f))},
    };
    for (const Case& c : cases) {
        glm::vec3 diffuse, glossy;
        pathLobes(c.kd, c.ks, c.reflectivity, 0.0f, diffuse, glossy);
        const double albedoR = double(c.reflectivity.x) + sphereIntegral([&](glm::vec3 wi) {
            const double cosI = glm::dot(kNormal, wi);
            return cosI > 0.0 ? double(bsdfTimesPi(diffuse, glossy, c.ns, kNormal, c.d, wi).x) / M_PI * cosI : 0.0;
        });
        const int n = 1 << 20;
        double sum = 0.0, sum2 = 0.0;
        for (int k = 0; k < n; ++k) {
            const uint32_t h = hashPcg(uint32_t(k));
            const glm::vec2 u(unitFloat(hashPcg(h ^ 0x1234u)), unitFloat(hashPcg(h ^ 0x9876u)));
            const float lobe = unitFloat(hashPcg(h ^ 0x5555u));
            glm::vec3 dir, factor;
            float pdf, side;
            double x = 0.0;
            if (scatterPath(c.d, kNormal, kNormal, true, diffuse, glossy, c.ns, c.reflectivity, 0.0f, glm::vec3(1.0f), u,
                            lobe, dir, factor, pdf, side)) {
                x = factor.x;
                EXPECT_NEAR(glm::length(dir), 1.0f, 1e-5f);
                if (pdf > 0.0f) {
                    EXPECT_GT(dir.z, 0.0f);
                }
            }
            sum += x;
            sum2 += x * x;
        }
        const double mean = sum / n, error = std::sqrt((sum2 / n - mean * mean) / n);
        EXPECT_NEAR(mean, albedoR, 5.0 * error + 1e-3) << "kd " << c.kd.x << " ks " << c.ks.x;
    }
}

TEST(PathMath, GlassReflectsWithTheProbabilityOfFresnel) {
    const glm::vec3 d = glm::normalize(glm::vec3(0.6f, 0.0f, -0.8f));  // 36.9 degrees off the normal
    const int n = 100000;
    int reflected = 0;
    for (int k = 0; k < n; ++k) {
        glm::vec3 dir, factor;
        float pdf, side;
        ASSERT_TRUE(scatterPath(d, kNormal, kNormal, true, glm::vec3(0.0f), glm::vec3(0.0f), 1.0f, glm::vec3(0.0f), 1.5f,
                                glm::vec3(0.9f), glm::vec2(0.5f), (float(k) + 0.5f) / float(n), dir, factor, pdf, side));
        EXPECT_EQ(pdf, 0.0f);  // a delta lobe
        if (side > 0.0f) {
            ++reflected;
            EXPECT_EQ(factor, glm::vec3(1.0f));
        } else {
            EXPECT_EQ(factor, glm::vec3(0.9f));  // the transmission filter
            EXPECT_NEAR(std::sqrt(dir.x * dir.x + dir.y * dir.y) * 1.5f, 0.6f, 1e-5f);  // Snell
        }
    }
    EXPECT_NEAR(double(reflected) / n, fresnelDielectric(0.8f, 1.5f), 2.0 / n);
}

TEST(PathMath, DirectionsAboutAnAxisHaveTheirAngle) {
    for (const glm::vec3 a : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::normalize(glm::vec3(1, -2, 0.5f)),
                              glm::normalize(glm::vec3(-0.3f, 0.1f, -0.9f))}) {
        for (float c : {1.0f, 0.7f, 0.0f, -0.5f})
            for (float u : {0.0f, 0.3f, 0.8f}) {
                const glm::vec3 w = directionAbout(a, c, u);
                EXPECT_NEAR(glm::length(w), 1.0f, 1e-6f);
                EXPECT_NEAR(glm::dot(w, a), c, 1e-5f);
            }
        // The azimuth turns the direction about the axis: a quarter turn apart, orthogonal arms.
        const glm::vec3 p = directionAbout(a, 0.0f, 0.0f), q = directionAbout(a, 0.0f, 0.25f);
        EXPECT_NEAR(glm::dot(p, q), 0.0f, 1e-5f);
    }
}

TEST(PathMath, PowerHeuristicWeightsSumToOne) {
    for (float a : {0.01f, 0.5f, 3.0f, 1e6f})
        for (float b : {0.0f, 0.02f, 0.5f, 40.0f}) {
            EXPECT_NEAR(powerHeuristic(a, b) + (b > 0.0f ? powerHeuristic(b, a) : 0.0f), 1.0f, 1e-6f);
            EXPECT_NEAR(powerHeuristic(a, b), a * a / (a * a + b * b), 1e-6f);
        }
    EXPECT_EQ(powerHeuristic(0.0f, 1.0f), 0.0f);
    EXPECT_EQ(emissionWeight(0.0f, 1.0f, kNormal, -kNormal, 1.0f), 1.0f);  // after a delta lobe: in full
}

}  // namespace
}  // namespace gpurt
