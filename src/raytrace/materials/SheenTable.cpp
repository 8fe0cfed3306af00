#include "raytrace/materials/SheenTable.h"

#include <algorithm>
#include <cmath>

#include "raytrace/common/RayMath.h"

namespace gpurt {

namespace {

// E(mu, r) = the integral of D V cos over the hemisphere of light directions, by the midpoint rule
// over cos theta (kCos cells) and phi (kPhi cells over [0, pi], the lobe being symmetric about
// the plane of v and n). The lobe is smooth (its roughness at least GPURT_SHEEN_MIN_ROUGHNESS).
std::vector<float> integrate() {
    constexpr int kCos = 128, kPhi = 64;
    const int n = GPURT_SHEEN_TABLE;
    std::vector<float> table(size_t(n) * size_t(n));
    const double pi = 3.14159265358979323846, cell = (1.0 / kCos) * (pi / kPhi);
    for (int j = 0; j < n; ++j) {
        const float alpha = raymath::sheenAlpha(float(j) / float(n - 1));
        for (int i = 0; i < n; ++i) {
            const float x = float(i) / float(n - 1), mu = std::max(x * x, 1e-4f);  // sqrt(n.v) along a row
            const glm::vec3 v(std::sqrt(1.0f - mu * mu), 0.0f, mu);
            double sum = 0.0;
            for (int a = 0; a < kCos; ++a) {
                const float nl = (float(a) + 0.5f) / float(kCos), s = std::sqrt(1.0f - nl * nl);
                for (int b = 0; b < kPhi; ++b) {
                    const float phi = float((b + 0.5) * pi / kPhi);
                    const glm::vec3 l(s * std::cos(phi), s * std::sin(phi), nl);
                    const glm::vec3 h = glm::normalize(l + v);
                    sum += double(raymath::sheenLobe(alpha, std::max(h.z, 0.0f), nl, mu)) * nl;
                }
            }
            // At most 1: at the grazing end a smooth sheen's lobe integrates above 1 (2.7 at n.v 1e-4,
            // roughness 0.07: the fitted Lambda's extrapolation), which would turn the albedo
            // scaling of what lies under the sheen negative.
            table[size_t(j * n + i)] = float(std::min(1.0, 2.0 * sum * cell));
        }
    }
    return table;
}

}  // namespace

const std::vector<float>& sheenAlbedoTable() {
    static const std::vector<float> table = integrate();
    return table;
}

float raymath::sheenAlbedoTexel(int i, int j) { return sheenAlbedoTable()[size_t(j * GPURT_SHEEN_TABLE + i)]; }

}  // namespace gpurt
