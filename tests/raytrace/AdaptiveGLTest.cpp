// Adaptive sampling (--noise-threshold; glsl/common/adaptive.h) on both backends: the same
// rounds and stopping decisions on gl (masked passes, occlusion-counted convergence passes) and
// cpu; pixels of zero variance stop at --min-spp; noisy regions take more samples than flat
// ones; the active pixels never rise; the image agrees in expectation with uniform sampling.
#include "../common/GLTest.h"
#include "TestScenes.h"

#include "raytrace/scene/SceneLoader.h"

#include <cmath>
#include <numeric>

#include <glm/gtx/component_wise.hpp>

namespace gpurt::test {
namespace {

class Adaptive : public GLTest {};

RenderSettings adaptiveSettings(uint32_t spp, uint32_t minSpp, float threshold) {
    RenderSettings s;
    s.integrator = Integrator::Path;
    s.maxBounces = kDefaultPathBounces;
    s.samples = spp;
    s.minSamples = minSpp;
    s.noiseThreshold = threshold;
    s.aovs = false;
    return s;
}

void expectNeverRising(const std::vector<AdaptiveRound>& rounds, uint64_t pixels, const std::string& what) {
    uint64_t last = pixels;
    uint32_t samples = 0;
    for (const AdaptiveRound& r : rounds) {
        EXPECT_LE(r.active, last) << what << " after " << r.samples;
        EXPECT_GT(r.samples, samples) << what;
        last = r.active;
        samples = r.samples;
    }
}

// The Cornell blocks, adaptive: gl (either kernel form, whichever GPURT_KERNEL picks) and cpu
// take the same rounds and stop the same pixels (an error exactly at the threshold may round to
// either side on one backend: 0.5% of the pixels may differ by a round), and the pictures agree.
TEST_F(Adaptive, BothBackendsStopTheSamePixels) {
    const LoadedScene loaded = loadScene("scenes/cornell_blocks.json");
    const UniformGrid grid = buildGrid(loaded.scene, GridOptions{});
    const CameraBasis camera = makeCamera(*loaded.scene.camera, 48, 40);
    const RenderSettings settings = adaptiveSettings(96, 16, 0.05f);
    const RenderOutput gl = GpuTracer(loaded.scene, grid).render(camera, settings);
    const RenderOutput cpu = CpuTracer(loaded.scene, grid).render(camera, settings);
    ASSERT_EQ(gl.spp.size(), size_t(48 * 40));
    ASSERT_EQ(cpu.spp.size(), gl.spp.size());
    size_t same = 0;
    for (size_t i = 0; i < gl.spp.size(); ++i) same += gl.spp[i] == cpu.spp[i];
    EXPECT_GE(double(same) / double(gl.spp.size()), 0.995);
    // Rounds at 16 (--min-spp), 32, 48, 64 and 80: the same on both, each no more active pixels.
    ASSERT_EQ(gl.stats.adaptive.size(), cpu.stats.adaptive.size());
    for (size_t r = 0; r < gl.stats.adaptive.size(); ++r) {
        EXPECT_EQ(gl.stats.adaptive[r].samples, 16u * uint32_t(r + 1));
        EXPECT_EQ(gl.stats.adaptive[r].samples, cpu.stats.adaptive[r].samples);
        EXPECT_NEAR(double(gl.stats.adaptive[r].active), double(cpu.stats.adaptive[r].active),
                    0.005 * 48 * 40 + 1.0);
    }
    expectNeverRising(gl.stats.adaptive, 48 * 40, "gl");
    expectNeverRising(cpu.stats.adaptive, 48 * 40, "cpu");
    // Some pixels stopped early and some went on: the test decides something.
    const float fewest = *std::min_element(gl.spp.begin(), gl.spp.end());
    const float most = *std::max_element(gl.spp.begin(), gl.spp.end());
    EXPECT_EQ(fewest, 16.0f);
    EXPECT_GT(most, 16.0f);
    // Each pixel's sample count is one of the rounds' ends, and the stats count them all.
    const double total = std::accumulate(gl.spp.begin(), gl.spp.end(), 0.0);
    EXPECT_EQ(double(gl.stats.samples), total);
    for (float n : gl.spp) EXPECT_TRUE(n == 96.0f || std::fmod(n, 16.0f) == 0.0f) << n;
    // The stopped pixels are masked out of the later sample passes: they trace no camera ray.
    EXPECT_EQ(gl.stats.primaryRays, gl.stats.samples);
    EXPECT_EQ(cpu.stats.primaryRays, cpu.stats.samples);
    expectSamePictures(gl, cpu, "cornell blocks, adaptive", false);
}

// A white Lambert plane under a uniform sky (no other light): every path leaves after its first
// hit with throughput 1, so every sample of every pixel is exactly 1, each pixel's error 0, and
// every pixel stops at the first convergence pass, --min-spp.
TEST_F(Adaptive, PixelsWithoutNoiseStopAtTheMinimum) {
    Scene scene;
    scene.background = glm::vec3(1.0f);
    const uint32_t white = addMaterial(scene, glm::vec3(1.0f));
    addPolygon(scene, {{-4, 0, -4}, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}}, white);
    CameraSpec spec;
    spec.eye = {0.0f, 3.0f, 3.0f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.fovy = 50.0f;
    const UniformGrid grid = buildGrid(scene, GridOptions{});
    const CameraBasis camera = makeCamera(spec, 32, 24);
    for (uint32_t minSpp : {4u, 8u, 24u}) {
        const RenderSettings settings = adaptiveSettings(64, minSpp, 0.01f);
        const RenderOutput gl = GpuTracer(scene, grid).render(camera, settings);
        const RenderOutput cpu = CpuTracer(scene, grid).render(camera, settings);
        for (const RenderOutput* out : {&gl, &cpu}) {
            ASSERT_EQ(out->stats.adaptive.size(), 1u) << minSpp;
            EXPECT_EQ(out->stats.adaptive[0].samples, minSpp);
            EXPECT_EQ(out->stats.adaptive[0].active, 0u);
            for (float n : out->spp) ASSERT_EQ(n, float(minSpp));
            for (const glm::vec3& c : out->color) ASSERT_NEAR(c.x, 1.0f, 1e-5f);
        }
    }
}

// A floor under a uniform sky, its right half under a low grey roof: the left half's pixels have
// (nearly) no noise, the right half's paths find the sky or the roof at random. The right half
// takes more samples a pixel than the left, on both backends.
TEST_F(Adaptive, NoisyRegionsTakeMoreSamples) {
    Scene scene;
    scene.background = glm::vec3(1.0f);
    const uint32_t white = addMaterial(scene, glm::vec3(0.8f));
    const uint32_t grey = addMaterial(scene, glm::vec3(0.1f));
    addPolygon(scene, {{-4, 0, -4}, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}}, white);
    addBox(scene, {0.2f, 0.3f, -4.0f}, {4.0f, 0.35f, 4.0f}, grey);
    CameraSpec spec;
    spec.eye = {0.0f, 0.25f, 0.0f};  // between floor and roof on the left, looking down
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.up = {0.0f, 0.0f, -1.0f};
    spec.fovy = 120.0f;
    const UniformGrid grid = buildGrid(scene, GridOptions{});
    const CameraBasis camera = makeCamera(spec, 32, 16);
    const RenderSettings settings = adaptiveSettings(128, 16, 0.02f);
    for (const RenderOutput& out :
         {GpuTracer(scene, grid).render(camera, settings), CpuTracer(scene, grid).render(camera, settings)}) {
        double left = 0.0, right = 0.0;
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 32; ++x) (x < 16 ? left : right) += out.spp[size_t(y * 32 + x)];
        EXPECT_GT(right, 1.5 * left) << "left " << left / 256 << ", right " << right / 256;
        expectNeverRising(out.stats.adaptive, 32 * 16, "roof");
    }
}

// Stopping a pixel early leaves its mean unbiased: the adaptive Cornell blocks agree with a
// uniform render of as many samples (another seed, so its noise is independent) in every region,
// within 5 standard errors of their difference, estimated from the pixels' spread.
TEST_F(Adaptive, AgreesWithUniformSamplingInExpectation) {
    const LoadedScene loaded = loadScene("scenes/cornell_blocks.json");
    const UniformGrid grid = buildGrid(loaded.scene, GridOptions{});
    const CameraBasis camera = makeCamera(*loaded.scene.camera, 32, 32);
    RenderSettings settings = adaptiveSettings(128, 16, 0.05f);
    const RenderOutput adaptive = GpuTracer(loaded.scene, grid).render(camera, settings);
    settings.noiseThreshold = 0.0f;
    settings.seed = 7;
    const RenderOutput uniform = GpuTracer(loaded.scene, grid).render(camera, settings);
    // Four quadrants and the whole image.
    for (int quadrant = -1; quadrant < 4; ++quadrant) {
        double sum = 0.0, sum2 = 0.0;
        size_t n = 0;
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                if (quadrant >= 0 && (x / 16) + 2 * (y / 16) != quadrant) continue;
                const size_t i = size_t(y * 32 + x);
                const glm::vec3 d = adaptive.color[i] - uniform.color[i];
                const double v = double(d.x + d.y + d.z) / 3.0;
                sum += v, sum2 += v * v, ++n;
            }
        const double mean = sum / double(n);
        const double error = std::sqrt((sum2 / double(n) - mean * mean) / double(n - 1));
        EXPECT_LT(std::abs(mean), 5.0 * error + 1e-6) << "quadrant " << quadrant;
    }
    EXPECT_LT(double(adaptive.stats.samples), 0.9 * double(uniform.stats.samples));  // it did stop pixels
}

}  // namespace
}  // namespace gpurt::test

namespace gpurt::test {
namespace {

// Clamping (--clamp-direct, --clamp-indirect): the Cornell box's light, its glass and mirror
// spheres' caustics (fireflies: rare BSDF paths of great weight). With one sample a pixel, a path
// adds at most two direct contributions at its first hit (emission, next-event estimation), each
// at most the direct limit, and two indirect ones at each later depth, so no pixel exceeds
// 2 direct + 2 bounces x indirect; without clamping some do (the light itself is Ke 34 26 16). Clamping only removes
// light, and both backends clamp alike.
TEST_F(Adaptive, ClampingBoundsEachSamplesContribution) {
    const LoadedScene loaded = loadScene("scenes/cornell.json");
    const UniformGrid grid = buildGrid(loaded.scene, GridOptions{});
    const CameraBasis camera = makeCamera(*loaded.scene.camera, 48, 48);
    RenderSettings settings;
    settings.integrator = Integrator::Path;
    settings.maxBounces = 6;
    settings.samples = 1;
    settings.aovs = false;
    const RenderOutput plain = CpuTracer(loaded.scene, grid).render(camera, settings);
    settings.clampDirect = 2.0f;
    settings.clampIndirect = 0.5f;
    // Each depth adds two contributions (emission, next-event estimation), each clamped.
    const float bound = 2.0f * settings.clampDirect + 2.0f * float(settings.maxBounces) * settings.clampIndirect;
    const RenderOutput cpu = CpuTracer(loaded.scene, grid).render(camera, settings);
    const RenderOutput gl = GpuTracer(loaded.scene, grid).render(camera, settings);
    size_t above = 0;
    double plainSum = 0.0, clampedSum = 0.0;
    for (size_t i = 0; i < plain.color.size(); ++i) {
        above += glm::compMax(plain.color[i]) > bound;
        for (const RenderOutput* out : {&cpu, &gl}) ASSERT_LE(glm::compMax(out->color[i]), bound * (1.0f + 1e-5f)) << i;
        for (int c = 0; c < 3; ++c) {
            EXPECT_LE(cpu.color[i][c], plain.color[i][c] * (1.0f + 1e-5f) + 1e-6f) << i;
            plainSum += plain.color[i][c];
            clampedSum += cpu.color[i][c];
        }
    }
    EXPECT_GT(above, 0u);
    EXPECT_LT(clampedSum, plainSum);
    // The pictures (at one sample a pixel a few of 4800 glass-bent shadow rays differ in existence
    // between the backends, more than the 0.1% expectSamePictures allows a count this small).
    expectSamePictures(gl, cpu, "cornell, clamped", false);
}

}  // namespace
}  // namespace gpurt::test

namespace gpurt::test {
namespace {

// The variance AOV: the variance of each pixel's mean. Two renders (random sampler) of other seeds differ by
// E[(a - b)^2] = 2 var(mean) in each pixel, so over the image the mean squared difference of two
// renders is twice the mean of the AOV (within 10%: 1920 pixels x 3 channels of a chi-square of
// one degree, plus the estimates' own spread), on both backends; the backends' AOVs agree.
TEST_F(Adaptive, VarianceAovPredictsTheSpreadBetweenSeeds) {
    const LoadedScene loaded = loadScene("scenes/cornell_blocks.json");
    const UniformGrid grid = buildGrid(loaded.scene, GridOptions{});
    const CameraBasis camera = makeCamera(*loaded.scene.camera, 48, 40);
    RenderSettings settings = adaptiveSettings(32, 0, 0.0f);
    settings.variance = true;
    settings.clampIndirect = 2.0f;  // no fireflies: their variance is estimated only once one is drawn
    // Independent samples: the AOV is the samples' variance over their count, which is the mean's
    // for independent samples; sobol's means vary about 10x less between seeds than that here.
    settings.sampler = SamplerKind::Random;
    GpuTracer gl(loaded.scene, grid);
    const RenderOutput a = gl.render(camera, settings);
    const RenderOutput cpu = CpuTracer(loaded.scene, grid).render(camera, settings);
    settings.seed = 1;
    const RenderOutput b = gl.render(camera, settings);
    ASSERT_EQ(a.variance.size(), a.color.size());
    double predicted = 0.0, observed = 0.0, worst = 0.0;
    for (size_t i = 0; i < a.color.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            // The light and its edge (above 1) are left out: a few pixels of great variance there
            // would decide the whole sum.
            if (glm::compMax(a.color[i]) > 1.0f || glm::compMax(b.color[i]) > 1.0f) continue;
            predicted += a.variance[i][c] + b.variance[i][c];
            observed += std::pow(double(a.color[i][c]) - double(b.color[i][c]), 2.0);
            worst = std::max(worst, std::abs(double(a.variance[i][c]) - double(cpu.variance[i][c])) /
                                        (1e-6 + double(cpu.variance[i][c])));
        }
    EXPECT_GT(observed / predicted, 0.9);
    EXPECT_LT(observed / predicted, 1.1);
    EXPECT_LT(worst, 1e-2);
}

}  // namespace
}  // namespace gpurt::test

namespace gpurt::test {
namespace {

// The samplers' numbers are pure functions of (pixel, sample, seed, dimension) and the same on
// both backends, bit for bit: a kernel of glsl/common/sampling.h against the C++ of the same file.
TEST_F(Adaptive, SamplersGiveTheSameNumbersOnBothBackends) {
    const int w = 24, h = 16;
    GPUFloatArray first(w, h, 4, "first"), second(w, h, 4, "second");
    GPUKernel kernel("samples", "test/samples.frag");
    kernel.addOutput(first).addOutput(second);
    for (uint32_t s : {0u, 1u, 5u, 63u, 1000u})
        for (uint32_t dimension : {0u, 1u, 1030u, 3077u}) {
            kernel.setUniform("sampleIndex", s).setUniform("sampleCount", 64u).setUniform("seed", 7u);
            kernel.setUniform("dimension", dimension).execute();
            const std::vector<float> a = first.download(), b = second.download();
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const size_t i = size_t(y * w + x) * 4;
                    const auto px = [&](uint32_t sampler) {
                        return raymath::sample2D(sampler, uint32_t(x), uint32_t(y), s, 64u, 7u, dimension);
                    };
                    const glm::vec2 sobol = px(GPURT_SAMPLER_SOBOL), stratified = px(GPURT_SAMPLER_STRATIFIED),
                                    random = px(GPURT_SAMPLER_RANDOM);
                    const glm::vec2 choice =
                        raymath::sampleChoice(GPURT_SAMPLER_SOBOL, uint32_t(x), uint32_t(y), s, 64u, 7u, dimension + 1u);
                    ASSERT_EQ(glm::vec4(a[i], a[i + 1], a[i + 2], a[i + 3]), glm::vec4(sobol, stratified))
                        << x << "," << y << " sample " << s << " dimension " << dimension;
                    ASSERT_EQ(glm::vec4(b[i], b[i + 1], b[i + 2], b[i + 3]), glm::vec4(random, choice))
                        << x << "," << y << " sample " << s << " dimension " << dimension;
                }
        }
}

}  // namespace
}  // namespace gpurt::test
