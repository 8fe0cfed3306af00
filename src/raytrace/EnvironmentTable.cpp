#include "raytrace/EnvironmentTable.h"

#include <algorithm>
#include <cmath>

#include "raytrace/RayMath.h"

namespace gpurt {

namespace {

// The first k in [0, n) with u < cdf[k] (environment.glsl searchDistribution).
size_t search(const float* cdf, size_t n, float u) {
    const float* at = std::upper_bound(cdf, cdf + n, u);
    return std::min(size_t(at - cdf), n - 1);
}

// The 9 spherical-harmonic coefficients of the map, in environment.h's order and scene axes.
std::array<glm::vec3, 9> projectHarmonics(const EnvironmentTable& t) {
    std::array<glm::dvec3, 9> c{};
    const double pi = 3.14159265358979323846;
    for (int j = 0; j < t.height; ++j) {
        // The texel's exact solid angle (a constant map projects exactly).
        const double dOmega = (2.0 * pi / t.width) * (std::cos(double(j) / t.height * pi) - std::cos(double(j + 1) / t.height * pi));
        for (int i = 0; i < t.width; ++i) {
            const glm::vec2 uv((i + 0.5f) / float(t.width), float((j + 0.5) / t.height));
            const glm::dvec3 d(raymath::environmentDirection(uv, t.rotation));
            const glm::dvec3 L = glm::dvec3(glm::vec3(t.texels[size_t(j) * size_t(t.width) + size_t(i)])) * dOmega;
            const double x = d.x, y = d.y, z = d.z;
            c[0] += L * 0.282095;
            c[1] += L * (0.488603 * y);
            c[2] += L * (0.488603 * z);
            c[3] += L * (0.488603 * x);
            c[4] += L * (1.092548 * x * y);
            c[5] += L * (1.092548 * y * z);
            c[6] += L * (0.315392 * (3.0 * z * z - 1.0));
            c[7] += L * (1.092548 * x * z);
            c[8] += L * (0.546274 * (x * x - y * y));
        }
    }
    std::array<glm::vec3, 9> out;
    for (size_t k = 0; k < 9; ++k) out[k] = glm::vec3(c[k]);
    return out;
}

// The sampling distribution: luminance x sin(theta) per texel, in double.
void buildDistribution(EnvironmentTable& t) {
    const size_t w = size_t(t.width), h = size_t(t.height);
    const double pi = 3.14159265358979323846;
    std::vector<double> rowSums(h, 0.0);
    t.conditional.assign(w * h, 0.0f);
    double total = 0.0;
    std::vector<double> f(w);
    for (size_t j = 0; j < h; ++j) {
        const double s = std::sin((double(j) + 0.5) / double(h) * pi);
        double sum = 0.0;
        for (size_t i = 0; i < w; ++i) {
            f[i] = double(raymath::environmentLuminance(glm::vec3(t.texels[j * w + i]))) * s;
            sum += f[i];
        }
        double run = 0.0;
        for (size_t i = 0; i < w; ++i) {
            run += f[i];
            // A row without light is never drawn; its columns stay uniform.
            t.conditional[j * w + i] = sum > 0.0 ? float(run / sum) : float(double(i + 1) / double(w));
        }
        t.conditional[j * w + w - 1] = 1.0f;
        rowSums[j] = sum;
        total += sum;
    }
    t.marginal.assign(h, 0.0f);
    t.sampled = total > 0.0 && std::isfinite(total);
    if (!t.sampled) {
        for (glm::vec4& texel : t.texels) texel.w = 0.0f;
        return;
    }
    double run = 0.0;
    for (size_t j = 0; j < h; ++j) {
        run += rowSums[j];
        t.marginal[j] = float(run / total);
    }
    t.marginal[h - 1] = 1.0f;
    // Texel (i, j)'s density in (u, v): its probability f / total times W H.
    const double s = double(w) * double(h) / total;
    for (size_t j = 0; j < h; ++j) {
        const double sinTheta = std::sin((double(j) + 0.5) / double(h) * pi);
        for (size_t i = 0; i < w; ++i)
            t.texels[j * w + i].w =
                float(double(raymath::environmentLuminance(glm::vec3(t.texels[j * w + i]))) * sinTheta * s);
    }
}

}  // namespace

EnvironmentTable buildEnvironmentTable(const Scene& scene) {
    EnvironmentTable t;
    if (!scene.environment) return t;
    const Environment& env = *scene.environment;
    const EnvironmentImage& image = *env.image;
    t.width = image.width;
    t.height = image.height;
    t.texels.resize(image.texels.size());
    for (size_t k = 0; k < image.texels.size(); ++k) t.texels[k] = glm::vec4(image.texels[k] * env.strength, 0.0f);
    const double a = double(env.rotation) * 3.14159265358979323846 / 180.0;
    t.rotation = glm::vec2(float(std::cos(a)), float(std::sin(a)));
    t.harmonics = projectHarmonics(t);
    if (env.sampled) buildDistribution(t);
    else t.marginal.assign(size_t(t.height), 1.0f), t.conditional.assign(t.texels.size(), 1.0f);
    return t;
}

glm::vec3 EnvironmentTable::radiance(glm::vec3 d) const {
    const glm::vec2 uv = raymath::environmentUv(d, rotation);
    glm::ivec2 columns, rows;
    glm::vec2 f;
    raymath::bilinearFootprint(uv, width, height, GPURT_WRAP_REPEAT, GPURT_WRAP_CLAMP, columns, rows, f);
    auto texel = [&](int x, int y) { return glm::vec3(texels[size_t(y) * size_t(width) + size_t(x)]); };
    return raymath::bilinearBlend(texel(columns.x, rows.x), texel(columns.y, rows.x), texel(columns.x, rows.y),
                                  texel(columns.y, rows.y), f);
}

float EnvironmentTable::pdf(glm::vec3 d) const {
    if (!sampled) return 0.0f;
    const glm::vec2 uv = raymath::environmentUv(d, rotation);
    const glm::ivec2 at = raymath::environmentTexel(uv, width, height);
    return raymath::environmentPdf(texels[size_t(at.y) * size_t(width) + size_t(at.x)].w, uv.y);
}

bool EnvironmentTable::sample(glm::vec2 u, glm::vec3& dir, float& pdf) const {
    pdf = 0.0f;
    if (!sampled) return false;
    const size_t w = size_t(width), h = size_t(height);
    const size_t j = search(marginal.data(), h, u.y);
    const float rowLo = j == 0 ? 0.0f : marginal[j - 1];
    const float* row = conditional.data() + j * w;
    const size_t i = search(row, w, u.x);
    const float colLo = i == 0 ? 0.0f : row[i - 1];
    const glm::vec2 uv((float(int(i)) + raymath::remapToUnit(u.x, colLo, row[i])) / float(width),
                       (float(int(j)) + raymath::remapToUnit(u.y, rowLo, marginal[j])) / float(height));
    dir = raymath::environmentDirection(uv, rotation);
    pdf = raymath::environmentPdf(texels[j * w + i].w, uv.y);
    return pdf > 0.0f;
}

glm::vec3 EnvironmentTable::irradiance(glm::vec3 n) const {
    const std::array<glm::vec3, 9>& c = harmonics;
    return raymath::environmentIrradiance(n, c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8]);
}

}  // namespace gpurt
