#include "raytrace/lights/EnvironmentTable.h"

#include <algorithm>
#include <cmath>

#include "base/Parallel.h"
#include "raytrace/common/RayMath.h"

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

// The columns' direction factors: a texel centre's direction is (sin(theta) a, cos(theta),
// -sin(theta) b) with a = sin(phi - rot), b = cos(phi - rot) (environment.h environmentDirection).
struct ColumnFactors {
    std::vector<double> a, b;
};

ColumnFactors columnFactors(size_t w, glm::vec2 rotation) {
    ColumnFactors c{std::vector<double>(w), std::vector<double>(w)};
    for (size_t i = 0; i < w; ++i) {
        const double phi = ((double(i) + 0.5) / double(w) - 0.5) * 2.0 * kPi;
        const double sp = std::sin(phi), cp = std::cos(phi);
        c.a[i] = double(rotation.x) * sp - double(rotation.y) * cp;
        c.b[i] = double(rotation.x) * cp + double(rotation.y) * sp;
    }
    return c;
}

// Row j's share of the 9 spherical-harmonic coefficients (environment.h's order, scene axes).
// Each is a quadratic polynomial of the direction, so a row needs only the sums of L, L a, L b,
// L a^2 and L a b over its columns (s0, sa, sb, saa, sab); the row is weighed by its texels'
// exact solid angle (a constant map projects exactly).
std::array<glm::dvec3, 9> rowHarmonics(size_t j, size_t w, size_t h, const glm::dvec3& s0, const glm::dvec3& sa,
                                       const glm::dvec3& sb, const glm::dvec3& saa, const glm::dvec3& sab) {
    const double theta = (double(j) + 0.5) / double(h) * kPi, st = std::sin(theta), y = std::cos(theta);
    const double dOmega = (2.0 * kPi / double(w)) * (std::cos(double(j) / double(h) * kPi) - std::cos(double(j + 1) / double(h) * kPi));
    const glm::dvec3 sbb = s0 - saa;  // a^2 + b^2 = 1
    std::array<glm::dvec3, 9> c;
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
    return c;
}

// sin(theta) at row j's centre: the distribution's weight of a row's texels besides luminance.
float rowSine(size_t j, size_t h) { return float(std::sin((double(j) + 0.5) / double(h) * kPi)); }

// The sampling distribution's weight of texel i of row j: the largest luminance of it and its 8
// neighbours (wrapping across u, clamped at the poles: the bilinear filter blends those into the
// radiance inside it, so a bright texel's halo is sampled as often as it shines, and BSDF
// directions that find the halo of a small sun do not meet the dim sky's pdf there) times
// sin(theta) at the row's centre. `across` holds each texel's maximum along its row (of it and
// its 2 neighbours); the maximum over the rows above and below completes the 3 x 3 one.
struct RowWeights {
    const float *up, *mid, *down;
    float s;
    RowWeights(const float* across, size_t j, size_t w, size_t h)
        : up(across + (j == 0 ? 0 : j - 1) * w), mid(across + j * w), down(across + std::min(h - 1, j + 1) * w), s(rowSine(j, h)) {}
    float operator()(size_t i) const { return std::max(std::max(up[i], mid[i]), down[i]) * s; }
};

// The sum of row j's weights, in double, in four partial sums (no chain through every column).
double rowSum(const float* across, size_t j, size_t w, size_t h) {
    const RowWeights weight(across, j, w, h);
    double p0 = 0.0, p1 = 0.0, p2 = 0.0, p3 = 0.0;
    size_t i = 0;
    for (; i + 4 <= w; i += 4) {
        p0 += double(weight(i));
        p1 += double(weight(i + 1));
        p2 += double(weight(i + 2));
        p3 += double(weight(i + 3));
    }
    for (; i < w; ++i) p0 += double(weight(i));
    return (p0 + p1) + (p2 + p3);
}

// Row j's distribution from `across` (see RowWeights), its weights' sum `sum` known: the
// conditional cumulative distribution of its columns into cdf[0, w) and each texel's density in
// (u, v), its probability (weight / total) times W H = weight x `scale`, into texels[].w. The
// running sum is in double, four columns a step: the four partial sums come off the chain, so
// the additions that wait on each other are a quarter of the columns.
void buildRow(const float* across, size_t j, size_t w, size_t h, double sum, double scale, float* cdf, glm::vec4* texels) {
    const RowWeights weight(across, j, w, h);
    for (size_t i = 0; i < w; ++i) {
        const float x = weight(i);
        cdf[i] = x;
        texels[i].w = float(double(x) * scale);
    }
    if (!(sum > 0.0)) {  // a row without light is never drawn; its columns stay uniform
        for (size_t i = 0; i < w; ++i) cdf[i] = float(double(i + 1) / double(w));
        return;
    }
    const double inv = 1.0 / sum;
    double run = 0.0;
    size_t i = 0;
    for (; i + 4 <= w; i += 4) {
        const double p0 = double(cdf[i]), p1 = p0 + double(cdf[i + 1]), p2 = p1 + double(cdf[i + 2]), p3 = p2 + double(cdf[i + 3]);
        cdf[i] = float((run + p0) * inv);
        cdf[i + 1] = float((run + p1) * inv);
        cdf[i + 2] = float((run + p2) * inv);
        cdf[i + 3] = float((run + p3) * inv);
        run += p3;
    }
    for (; i < w; ++i) {
        run += double(cdf[i]);
        cdf[i] = float(run * inv);
    }
    cdf[w - 1] = 1.0f;
}

}  // namespace

// One pass over the rows (in parallel) turns the map's texels into the table's (times the
// strength, density 0), sums the spherical harmonics' row terms and, when the distribution is
// asked for, each texel's luminance maximum along its row. Then, with the distribution: each
// row's weight sum (a second pass over those maxima, 8 MB); the rows' marginal; a last pass writes
// each row's conditional distribution and its texels' densities. The big arrays are LargeArrays:
// written once, never zeroed first, in huge pages where the kernel gives them.
EnvironmentTable buildEnvironmentTable(const Scene& scene) {
    EnvironmentTable t;
    if (!scene.environment) return t;
    const Environment& env = *scene.environment;
    const EnvironmentImage& image = *env.image;
    t.width = image.width;
    t.height = image.height;
    const size_t w = size_t(t.width), h = size_t(t.height);
    const double angle = double(env.rotation) * kPi / 180.0;
    t.rotation = glm::vec2(float(std::cos(angle)), float(std::sin(angle)));
    t.texels.resize(w * h);
    LargeArray<float> across;
    if (env.sampled) across.resize(w * h);
    const ColumnFactors factors = columnFactors(w, t.rotation);
    std::vector<std::array<glm::dvec3, 9>> harmonicRows(h);
    const float strength = env.strength;
    parallelChunks(h, 16, 0, [&](size_t begin, size_t end, size_t) {
        std::vector<float> luminance(w);
        for (size_t j = begin; j < end; ++j) {
            const glm::vec3* src = &image.texels[j * w];
            glm::vec4* dst = &t.texels[j * w];
            glm::dvec3 s0(0.0), sa(0.0), sb(0.0), saa(0.0), sab(0.0);
            for (size_t i = 0; i < w; ++i) {
                const glm::vec3 c = src[i] * strength;
                dst[i] = glm::vec4(c, 0.0f);
                luminance[i] = raymath::environmentLuminance(c);
                const glm::dvec3 L(c);
                const double a = factors.a[i], b = factors.b[i];
                s0 += L;
                sa += L * a;
                sb += L * b;
                saa += L * (a * a);
                sab += L * (a * b);
            }
            harmonicRows[j] = rowHarmonics(j, w, h, s0, sa, sb, saa, sab);
            if (across.empty()) continue;
            float* out = &across[j * w];
            const float* l = luminance.data();
            if (w == 1) {
                out[0] = l[0];
                continue;
            }
            out[0] = std::max(std::max(l[w - 1], l[0]), l[1]);
            for (size_t i = 1; i + 1 < w; ++i) out[i] = std::max(std::max(l[i - 1], l[i]), l[i + 1]);
            out[w - 1] = std::max(std::max(l[w - 2], l[w - 1]), l[0]);
        }
    });
    std::array<glm::dvec3, 9> harmonics{};
    for (const std::array<glm::dvec3, 9>& c : harmonicRows)
        for (size_t k = 0; k < 9; ++k) harmonics[k] += c[k];
    for (size_t k = 0; k < 9; ++k) t.harmonics[k] = glm::vec3(harmonics[k]);
    if (!env.sampled) return t;

    std::vector<double> rowSums(h);
    forRows(h, [&](size_t j) { rowSums[j] = rowSum(across.data(), j, w, h); });
    double total = 0.0;
    for (double r : rowSums) total += r;
    t.sampled = total > 0.0 && std::isfinite(total);
    if (!t.sampled) return t;  // texels[].w stay 0: no pdf anywhere
    t.marginal.resize(h);
    double run = 0.0;
    for (size_t j = 0; j < h; ++j) {
        run += rowSums[j];
        t.marginal[j] = float(run / total);
    }
    t.marginal[h - 1] = 1.0f;
    t.conditional.resize(w * h);
    const double scale = double(w) * double(h) / total;
    forRows(h, [&](size_t j) { buildRow(across.data(), j, w, h, rowSums[j], scale, &t.conditional[j * w], &t.texels[j * w]); });
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
