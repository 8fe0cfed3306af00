// The denoiser (raytrace/denoise, glsl/common/denoise.h) and the features it reads: the path
// integrators' albedo and shading normal on both backends (through a mirror), the filter's
// properties on synthetic images on both backends (identity on constant images, black stays
// black, steps in the albedo or the normal stay steps, a converged image stays, a pixel that is
// not finite is refused and not spread), gl against cpu, and a 16-sample Cornell blocks brought
// closer to a long reference than the raw render by what the filter's footprint allows.
#include "../common/GLTest.h"
#include "TestScenes.h"

#include "raytrace/scene/SceneLoader.h"
#include "raytrace/denoise/DenoiseGl.h"

#include <cmath>
#include <limits>
#include <random>

namespace gpurt::test {
namespace {

class Denoise : public GLTest {};

RenderSettings pathSettings(uint32_t spp) {
    RenderSettings s;
    s.integrator = Integrator::Path;
    s.maxBounces = 4;
    s.samples = spp;
    s.features = true;
    s.variance = true;
    return s;
}

// A blue-ish floor (y = 0) and, behind it, a vertical mirror facing the camera, under the default
// light: the camera looks down at the floor with the mirror above it in the picture.
Scene floorAndMirror() {
    Scene scene;
    const uint32_t floor = addMaterial(scene, glm::vec3(0.2f, 0.5f, 0.8f));
    Material mirror;
    mirror.diffuse = glm::vec3(0.0f);
    mirror.reflectivity = glm::vec3(1.0f);
    scene.materials.push_back(mirror);
    addPolygon(scene, {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}}, floor);
    addPolygon(scene, {{-1, 0.05f, -1}, {1, 0.05f, -1}, {1, 1.5f, -1}, {-1, 1.5f, -1}},
               uint32_t(scene.materials.size() - 1));
    return scene;
}

// The features are the first non-mirror hit's: the floor's albedo and up-facing normal where the
// camera sees the floor, the floor's or the background's (albedo 1, normal 0) through the mirror,
// never the mirror's own; both backends give them alike.
TEST_F(Denoise, FeaturesAreTheFirstHitThroughMirrors) {
    const Scene scene = floorAndMirror();
    const UniformGrid grid = buildGrid(scene, GridOptions{});
    const CameraBasis camera = makeCamera(CameraSpec{{0, 1.2f, 2.5f}, {0, 0.4f, 0}, {0, 1, 0}, 45.0f}, 48, 40);
    const RenderSettings settings = pathSettings(8);
    const RenderOutput gl = GpuTracer(scene, grid).render(camera, settings);
    const RenderOutput cpu = CpuTracer(scene, grid).render(camera, settings);
    ASSERT_EQ(gl.albedo.size(), size_t(48 * 40));
    ASSERT_EQ(gl.shadingNormal.size(), gl.albedo.size());
    ASSERT_EQ(cpu.albedo.size(), gl.albedo.size());
    size_t floorPixels = 0, mirrorPixels = 0, skyPixels = 0;
    for (size_t i = 0; i < gl.albedo.size(); ++i) {
        const glm::vec3 a = gl.albedo[i], n = gl.shadingNormal[i];
        EXPECT_LT(glm::length(a - cpu.albedo[i]), 1e-4f) << "pixel " << i;
        EXPECT_LT(glm::length(n - cpu.shadingNormal[i]), 1e-4f) << "pixel " << i;
        const int x = int(i % 48), y = int(i / 48);
        bool interior = true;  // the pixel and its neighbours' centre rays hit the same triangle group
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int qx = std::clamp(x + dx, 0, 47), qy = std::clamp(y + dy, 0, 39);
                const float q = gl.prim[size_t(qy * 48 + qx)], p = gl.prim[i];
                interior = interior && (q < 0) == (p < 0) && (p < 0 || (q < 2) == (p < 2));
            }
        if (!interior) continue;
        if (gl.prim[i] < 0) {  // the background: albedo 1, normal 0
            ++skyPixels;
            EXPECT_NEAR(a.x, 1.0f, 1e-6f);
            EXPECT_EQ(n, glm::vec3(0.0f));
        } else if (gl.prim[i] < 2) {  // the floor
            ++floorPixels;
            EXPECT_NEAR(a.x, 0.2f, 1e-5f);
            EXPECT_NEAR(a.y, 0.5f, 1e-5f);
            EXPECT_NEAR(a.z, 0.8f, 1e-5f);
            EXPECT_NEAR(n.y, 1.0f, 1e-5f);
        } else {  // the mirror: what it shows, the floor (normal up) or the background (0)
            ++mirrorPixels;
            EXPECT_LT(std::abs(n.z), 1e-5f) << "the mirror's own normal at pixel " << x << "," << y;
            EXPECT_GE(n.y, -1e-5f);
            EXPECT_TRUE(std::abs(a.x - 0.2f) < 1e-5f || a.x > 0.2f) << a.x;
        }
    }
    EXPECT_GT(floorPixels, 100u);
    EXPECT_GT(mirrorPixels, 100u);
    EXPECT_GT(skyPixels, 10u);
}

// A width x height image of colour `color` (with the given variance), albedo and normal.
DenoiseImages constantImages(int w, int h, glm::vec3 color, glm::vec3 variance, glm::vec3 albedo, glm::vec3 normal) {
    DenoiseImages in;
    in.width = w;
    in.height = h;
    const size_t n = size_t(w) * size_t(h);
    in.color.assign(n, color);
    in.variance.assign(n, variance);
    in.albedo.assign(n, albedo);
    in.normal.assign(n, normal);
    in.depth.assign(n, 4.0f);
    return in;
}

// Both backends' output, which agree within float tolerance.
std::vector<glm::vec3> denoiseBoth(const DenoiseImages& in, const std::string& what, DenoiseStats* stats = nullptr) {
    const std::vector<glm::vec3> gl = denoise(Backend::Gl, in, 0, stats);
    const std::vector<glm::vec3> cpu = denoise(Backend::Cpu, in);
    EXPECT_EQ(gl.size(), cpu.size()) << what;
    for (size_t i = 0; i < gl.size() && i < cpu.size(); ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(gl[i][c], cpu[i][c], 1e-4f * (1.0f + std::abs(cpu[i][c]))) << what << ", pixel " << i;
    return gl;
}

// The filter is the identity on a constant colour over constant features, and black stays black.
TEST_F(Denoise, ConstantImagesStayAndBlackStaysBlack) {
    const DenoiseImages grey = constantImages(40, 30, glm::vec3(0.3f, 0.2f, 0.1f), glm::vec3(0.01f), glm::vec3(0.5f),
                                              glm::vec3(0, 0, 1));
    for (const glm::vec3& c : denoiseBoth(grey, "constant")) {
        EXPECT_NEAR(c.x, 0.3f, 1e-6f);
        EXPECT_NEAR(c.y, 0.2f, 1e-6f);
        EXPECT_NEAR(c.z, 0.1f, 1e-6f);
    }
    const DenoiseImages black = constantImages(40, 30, glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.5f), glm::vec3(0, 0, 1));
    for (const glm::vec3& c : denoiseBoth(black, "black")) EXPECT_EQ(c, glm::vec3(0.0f));
}

// Noise of the given variance on each pixel (Gaussian, fixed seed).
void addNoise(DenoiseImages& in, float variance, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> gauss(0.0f, std::sqrt(variance));
    for (glm::vec3& c : in.color) c += glm::vec3(gauss(rng), gauss(rng), gauss(rng));
}

// A step in the albedo under a constant light stays a step (the filter works on the irradiance);
// a step in the normal stays a step in the light: the pixels beside each edge keep their side's
// value within a few of the filtered noise's standard deviations, where blurring across would
// move them half the step.
TEST_F(Denoise, StepsInTheFeaturesStaySteps) {
    const int w = 48, h = 32;
    const float variance = 1e-4f;
    DenoiseImages albedoStep = constantImages(w, h, glm::vec3(0.0f), glm::vec3(variance), glm::vec3(0.0f), glm::vec3(0, 0, 1));
    DenoiseImages normalStep = albedoStep;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y * w + x);
            const bool right = x >= w / 2;
            albedoStep.albedo[i] = glm::vec3(right ? 0.8f : 0.2f);
            albedoStep.color[i] = albedoStep.albedo[i] * 0.5f;  // irradiance 0.5
            normalStep.albedo[i] = glm::vec3(0.5f);
            normalStep.normal[i] = right ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1);
            normalStep.color[i] = glm::vec3(right ? 0.45f : 0.15f);
        }
    addNoise(albedoStep, variance, 1);
    addNoise(normalStep, variance, 2);
    const std::vector<glm::vec3> a = denoiseBoth(albedoStep, "albedo step");
    const std::vector<glm::vec3> n = denoiseBoth(normalStep, "normal step");
    const float sigma = std::sqrt(variance);
    for (int y = 2; y < h - 2; ++y) {
        const size_t left = size_t(y * w + w / 2 - 1), right = left + 1;
        EXPECT_NEAR(a[left].x, 0.1f, 4.0f * sigma) << "row " << y;
        EXPECT_NEAR(a[right].x, 0.4f, 4.0f * sigma) << "row " << y;
        EXPECT_NEAR(n[left].x, 0.15f, 4.0f * sigma) << "row " << y;
        EXPECT_NEAR(n[right].x, 0.45f, 4.0f * sigma) << "row " << y;
    }
}

// A converged image (a smooth gradient with a tiny variance) passes changed by less than its
// noise; a pixel that is not finite is refused (counted) and takes its neighbours' light, and
// nothing of it spreads.
TEST_F(Denoise, ConvergedImagesStayAndNonFinitePixelsAreRefused) {
    const int w = 40, h = 30;
    const float variance = 1e-8f;
    DenoiseImages in = constantImages(w, h, glm::vec3(0.0f), glm::vec3(variance), glm::vec3(0.7f), glm::vec3(0, 1, 0));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) in.color[size_t(y * w + x)] = glm::vec3(0.1f + 0.02f * float(x), 0.3f, 0.2f);
    const std::vector<glm::vec3> same = denoiseBoth(in, "converged");
    for (size_t i = 0; i < same.size(); ++i)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(same[i][c], in.color[i][c], 3.0f * std::sqrt(variance) + 1e-6f) << i;
    DenoiseImages bad = constantImages(w, h, glm::vec3(0.25f), glm::vec3(1e-4f), glm::vec3(0.7f), glm::vec3(0, 1, 0));
    bad.color[size_t(10 * w + 10)] = glm::vec3(std::numeric_limits<float>::quiet_NaN());
    bad.color[size_t(20 * w + 30)] = glm::vec3(std::numeric_limits<float>::infinity());
    DenoiseStats stats;
    const std::vector<glm::vec3> out = denoiseBoth(bad, "not finite", &stats);
    EXPECT_EQ(stats.refused, 2u);
    for (const glm::vec3& c : out)
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], 0.25f, 1e-5f);
}

double relMse(const std::vector<glm::vec3>& x, const std::vector<glm::vec3>& ref) {
    double sum = 0.0;
    for (size_t i = 0; i < ref.size(); ++i)
        for (int c = 0; c < 3; ++c) sum += double(x[i][c] - ref[i][c]) * (x[i][c] - ref[i][c]) / (ref[i][c] * ref[i][c] + 0.01);
    return sum / double(3 * ref.size());
}

// The Cornell blocks at 16 samples, denoised on both backends (their own features), against 1024
// samples of another seed: the error falls by at least a quarter of what the first iteration's
// 5 x 5 kernel alone takes off independent noise on a flat region (1 / sum of its squared
// weights, 13.4): the pixels on edges and on the light's boundary, whose features match few
// neighbours, keep most of their noise (docs/PERFORMANCE.md, "The denoiser").
TEST_F(Denoise, SixteenSamplesComeCloserToTheReference) {
    const LoadedScene loaded = loadScene("scenes/cornell_blocks.json");
    const UniformGrid grid = buildGrid(loaded.scene, GridOptions{});
    const CameraBasis camera = makeCamera(*loaded.scene.camera, 64, 64);
    RenderSettings settings = pathSettings(16);
    settings.maxBounces = kDefaultPathBounces;
    GpuTracer gpu(loaded.scene, grid);
    const RenderOutput raw = gpu.render(camera, settings);
    RenderSettings long_ = settings;
    long_.samples = 1024;
    long_.seed = 7;
    long_.features = long_.variance = long_.aovs = false;
    const RenderOutput reference = gpu.render(camera, long_);
    const std::vector<glm::vec3> denoised = denoiseBoth(denoiseImages(raw), "cornell blocks");
    const RenderOutput rawCpu = CpuTracer(loaded.scene, grid).render(camera, settings);
    const std::vector<glm::vec3> denoisedCpu = denoise(Backend::Cpu, denoiseImages(rawCpu));
    double taps = 0.0;  // the B3 spline's squared weights in one dimension: (1, 4, 6, 4, 1) / 16
    for (double t : {1.0, 4.0, 6.0, 4.0, 1.0}) taps += t * t / 256.0;
    const double footprint = 1.0 / (taps * taps);
    const double before = relMse(raw.color, reference.color), after = relMse(denoised, reference.color);
    const double afterCpu = relMse(denoisedCpu, reference.color);
    EXPECT_LT(after, before * 4.0 / footprint) << "raw " << before << ", denoised " << after;
    EXPECT_LT(afterCpu, relMse(rawCpu.color, reference.color) * 4.0 / footprint) << afterCpu;
}

}  // namespace
}  // namespace gpurt::test
