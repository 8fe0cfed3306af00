#include "raytrace/EnvironmentTable.h"

#include <algorithm>
#include <cmath>

#include "raytrace/Parallel.h"
#include "raytrace/RayMath.h"

namespace gpurt {

namespace {

// The first k in [0, n) with u < cdf[k] (environment.glsl searchDistribution).
size_t search(const float* cdf, size_t n, float u) {
    const float* at = std::upper_bound(cdf, cdf + n, u);
    return std::min(size_t(at - cdf), n - 1);
}

constexpr double kPi = 3.14159265358979323846;

// Rows of the map in parallel chunks (the build of a 2k map is a few passes over 2M texels).
template <typename Body>
void forRows(size_t rows, const Body& body) {
    parallelChunks(rows, 16, 0, [&](size_t begin, size_t end, size_t) {
        for (size_t j = begin; j < end; ++j) body(j);
    });
}

// The 9 spherical-harmonic coefficients of the map, in environment.h's order and scene axes.
// Each is a quadratic polynomial of the direction; a texel centre's direction is
// (sin(theta) a, cos(theta), -sin(theta) b) with a = sin(phi - rot), b = cos(phi - rot), so each
// row needs only the sums of L, L a, L b, L a^2 and L a b over its columns; each row's sums are
// weighed by its texels' exact solid angle (a constant map projects exactly).
std::array<glm::vec3, 9> projectHarmonics(const EnvironmentTable& t) {
    const size_t w = size_t(t.width), h = size_t(t.height);
    std::vector<double> ca(w), cb(w);
    for (size_t i = 0; i < w; ++i) {
        const double phi = ((double(i) + 0.5) / double(w) - 0.5) * 2.0 * kPi;
        const double sp = std::sin(phi), cp = std::cos(phi);
        ca[i] = double(t.rotation.x) * sp - double(t.rotation.y) * cp;  // environment.h environmentDirection
        cb[i] = double(t.rotation.x) * cp + double(t.rotation.y) * sp;
    }
    std::vector<std::array<glm::dvec3, 9>> rows(h);
    forRows(h, [&](size_t j) {
        glm::dvec3 s0(0.0), sa(0.0), sb(0.0), saa(0.0), sab(0.0);
        const glm::vec4* row = &t.texels[j * w];
        for (size_t i = 0; i < w; ++i) {
            const glm::dvec3 L(row[i].x, row[i].y, row[i].z);
            s0 += L;
            sa += L * ca[i];
            sb += L * cb[i];
            saa += L * (ca[i] * ca[i]);
            sab += L * (ca[i] * cb[i]);
        }
        const double theta = (double(j) + 0.5) / double(h) * kPi, st = std::sin(theta), y = std::cos(theta);
        const double dOmega = (2.0 * kPi / double(w)) * (std::cos(double(j) / double(h) * kPi) - std::cos(double(j + 1) / double(h) * kPi));
        const glm::dvec3 sbb = s0 - saa;  // a^2 + b^2 = 1
        std::array<glm::dvec3, 9>& c = rows[j];
        c[0] = s0 * 0.282095;
        c[1] = s0 * (0.488603 * y);
        c[2] = sb * (-0.488603 * st);
        c[3] = sa * (0.488603 * st);
        c[4] = sa * (1.092548 * st * y);
        c[5] = sb * (-1.092548 * y * st);
        c[6] = (sbb * (3.0 * st * st) - s0) * 0.315392;
        c[7] = sab * (-1.092548 * st * st);
        c[8] = (saa * (st * st) - s0 * (y * y)) * 0.546274;
        for (glm::dvec3& v : c) v *= dOmega;
    });
    std::array<glm::dvec3, 9> sum{};
    for (const std::array<glm::dvec3, 9>& c : rows)
        for (size_t k = 0; k < 9; ++k) sum[k] += c[k];
    std::array<glm::vec3, 9> out;
    for (size_t k = 0; k < 9; ++k) out[k] = glm::vec3(sum[k]);
    return out;
}

// The sampling distribution: per texel its weight (the largest luminance of it and its 8
// neighbours, wrapping across u, clamped at the poles: the bilinear filter blends those into the
// radiance inside it, so a bright texel's halo is sampled as often as it shines, and BSDF
// directions that find the halo of a small sun do not meet the dim sky's pdf there) times
// sin(theta) at its row's centre; each row's cumulative distribution, the rows' marginal one, and
// each texel's density in (u, v) in texels[].w.
void buildDistribution(EnvironmentTable& t) {
    const size_t w = size_t(t.width), h = size_t(t.height);
    std::vector<float> luminance(w * h);
    forRows(h, [&](size_t j) {
        for (size_t i = 0; i < w; ++i) luminance[j * w + i] = raymath::environmentLuminance(glm::vec3(t.texels[j * w + i]));
    });
    std::vector<double> rowSums(h, 0.0);
    std::vector<float> weight(w * h);
    t.conditional.assign(w * h, 0.0f);
    forRows(h, [&](size_t j) {
        const float* rows[3] = {&luminance[(j == 0 ? 0 : j - 1) * w], &luminance[j * w], &luminance[std::min(h - 1, j + 1) * w]};
        const float s = float(std::sin((double(j) + 0.5) / double(h) * kPi));
        double sum = 0.0;
        for (size_t i = 0; i < w; ++i) {
            const size_t l = i == 0 ? w - 1 : i - 1, r = i + 1 == w ? 0 : i + 1;
            float m = 0.0f;
            for (const float* row : rows) m = std::max(m, std::max(row[l], std::max(row[i], row[r])));
            weight[j * w + i] = m * s;
            sum += double(m * s);
        }
        double run = 0.0;
        float* cdf = &t.conditional[j * w];
        for (size_t i = 0; i < w; ++i) {
            run += double(weight[j * w + i]);
            // A row without light is never drawn; its columns stay uniform.
            cdf[i] = sum > 0.0 ? float(run / sum) : float(double(i + 1) / double(w));
        }
        cdf[w - 1] = 1.0f;
        rowSums[j] = sum;
    });
    double total = 0.0;
    for (double r : rowSums) total += r;
    t.marginal.assign(h, 0.0f);
    t.sampled = total > 0.0 && std::isfinite(total);
    if (!t.sampled) return;  // texels[].w stay 0: no pdf anywhere
    double run = 0.0;
    for (size_t j = 0; j < h; ++j) {
        run += rowSums[j];
        t.marginal[j] = float(run / total);
    }
    t.marginal[h - 1] = 1.0f;
    // Texel (i, j)'s density in (u, v): its probability (weight / total) times W H.
    const double scale = double(w) * double(h) / total;
    forRows(h, [&](size_t j) {
        for (size_t i = 0; i < w; ++i) t.texels[j * w + i].w = float(double(weight[j * w + i]) * scale);
    });
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
    const size_t w = size_t(t.width);
    forRows(size_t(t.height), [&](size_t j) {
        for (size_t i = j * w; i < (j + 1) * w; ++i) t.texels[i] = glm::vec4(image.texels[i] * env.strength, 0.0f);
    });
    const double a = double(env.rotation) * kPi / 180.0;
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
