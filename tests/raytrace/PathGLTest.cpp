// The path integrator (--integrator path) on both backends: against closed forms (white
// furnaces: convex objects under a uniform sky, a camera inside a closed emitter), against the
// Whitted integrator where the two must agree (direct light from point lights), against each other
// (the same samples), and its convergence on the Cornell box. Statistical tolerances come from
// the sample count: the standard error of the mean of the pixels, each the mean of its samples.
#include "../common/GLTest.h"
#include "TestScenes.h"

#include "scene/ObjLoader.h"
#include "raytrace/scene/SceneLoader.h"

#include <cmath>
#include <functional>

#include <glm/gtx/component_wise.hpp>

namespace gpurt::test {
namespace {

class Paths : public GLTest {};

struct Estimate {
    double mean = 0.0, error = 0.0;  // error: the standard error of the mean
    size_t pixels = 0;
};

// The mean of channel c over the pixels `use` selects, and its standard error from their spread.
Estimate pixelMean(const RenderOutput& out, int c, const std::function<bool(size_t)>& use) {
    Estimate e;
    double sum = 0.0, sum2 = 0.0;
    for (size_t i = 0; i < out.color.size(); ++i) {
        if (!use(i)) continue;
        const double x = out.color[i][c];
        sum += x;
        sum2 += x * x;
        ++e.pixels;
    }
    const double n = double(e.pixels);
    e.mean = sum / n;
    e.error = std::sqrt(std::max(0.0, sum2 / n - e.mean * e.mean) / (n - 1.0));
    return e;
}

const char* backendName(const Both& both, const RenderOutput* out) { return out == &both.gl ? "gl" : "cpu"; }

// A convex object under a sky of radiance 1 and no other light: every path leaves the object
// after its first hit, so a diffuse object of albedo a shows exactly a (its estimator has no
// variance: cosine sampling gives the throughput a), a mirror its reflectivity, and glass of
// transmission 1 all of the sky (1, within the standard error of Russian roulette). The sky is the
// only light: no headlight joins it.
TEST_F(Paths, ConvexObjectsUnderAUniformSkyShowTheirAlbedo) {
    const glm::vec3 albedo(0.2f, 0.5f, 0.8f);
    CameraSpec spec;
    spec.eye = {0.0f, 0.0f, 3.0f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.fovy = 45.0f;
    for (int kind = 0; kind < 3; ++kind) {
        const char* names[] = {"diffuse", "mirror", "glass"};
        SCOPED_TRACE(names[kind]);
        Scene scene;
        scene.background = glm::vec3(1.0f);
        Material m;
        m.diffuse = kind == 0 ? albedo : glm::vec3(0.0f);
        m.specular = glm::vec3(0.0f);
        m.reflectivity = kind == 1 ? albedo : glm::vec3(0.0f);
        m.ior = kind == 2 ? 1.5f : 0.0f;
        scene.materials.push_back(m);
        addIcosphere(scene, glm::vec3(0.0f), 1.0f, 3, 0);
        const Both both = renderBoth(scene, spec, 32, 32, 1, 16, Integrator::Path);  // the AOV rays
        for (const RenderOutput* out : {&both.gl, &both.cpu}) {
            SCOPED_TRACE(backendName(both, out));
            size_t hits = 0;
            for (size_t i = 0; i < out->color.size(); ++i) {
                if (out->prim[i] < 0.0f) {
                    EXPECT_EQ(out->color[i], glm::vec3(1.0f)) << i;  // the sky itself
                    continue;
                }
                ++hits;
                if (kind < 2) {
                    for (int c = 0; c < 3; ++c) ASSERT_NEAR(out->color[i][c], albedo[c], 1e-5f) << i;
                }
            }
            ASSERT_GT(hits, 300u);
            if (kind == 2) {
                const Estimate e = pixelMean(*out, 0, [&](size_t i) { return out->prim[i] >= 0.0f; });
                EXPECT_NEAR(e.mean, 1.0, 5.0 * e.error + 1e-4) << "standard error " << e.error;
            }
        }
    }
}

// A camera inside a closed box whose walls are diffuse with albedo a and emit e: the radiance
// everywhere is L = e + a L, e / (1 - a); with paths of at most B hits, the sum of e a^k for
// k = 0..B. Each channel its own albedo, so Russian roulette, next-event estimation and the
// multiple importance weights between the two ways of reaching the walls' emission are all tested.
TEST_F(Paths, InsideAClosedEmitterTheRadianceIsEmissionOverOneMinusAlbedo) {
    const glm::vec3 albedo(0.3f, 0.6f, 0.85f);
    const float e = 0.25f;
    const int bounces = 64;
    Scene scene;
    scene.background = glm::vec3(0.0f);
    addBox(scene, glm::vec3(-1.0f), glm::vec3(1.0f), addMaterial(scene, albedo, glm::vec3(e)));
    CameraSpec spec;
    spec.eye = {0.1f, 0.2f, 0.3f};
    spec.target = {1.0f, 0.5f, -0.7f};
    spec.fovy = 70.0f;
    const Both both = renderBoth(scene, spec, 16, 16, 64, bounces, Integrator::Path);
    for (const RenderOutput* out : {&both.gl, &both.cpu}) {
        SCOPED_TRACE(backendName(both, out));
        for (int c = 0; c < 3; ++c) {
            const double a = albedo[c];
            const double expected = e * (1.0 - std::pow(a, bounces + 1)) / (1.0 - a);
            const Estimate est = pixelMean(*out, c, [](size_t) { return true; });
            EXPECT_NEAR(est.mean, expected, 5.0 * est.error) << "channel " << c << ", standard error " << est.error;
            EXPECT_LT(est.error, 0.02 * expected) << "channel " << c;  // enough samples to tell
        }
    }
}

// With paths of one hit (--bounces 1) and only point lights, the path integrator gathers the
// direct light alone: Whitted's local colour without its ambient term 0.1 kd.
TEST_F(Paths, DirectLightOnlyIsWhittedWithoutItsAmbientTerm) {
    Scene scene = loadObj("../shared/models/teapot.obj");
    scene.background = glm::vec3(0.0f);
    const Bounds b = scene.bounds();
    const float r = glm::length(b.halfExtent());  // intensities that give about 1 at the centre
    scene.lights.push_back({b.center() + glm::vec3(0.0f, 3.0f, 4.0f) * r, {1.0f, 0.9f, 0.7f}, 25.0f * r * r});
    scene.lights.push_back({b.center() + glm::vec3(-4.0f, 1.0f, 1.0f) * r, {0.3f, 0.4f, 1.0f}, 18.0f * r * r});
    const CameraSpec spec = defaultCamera(b, 64, 48);
    const Both whitted = renderBoth(scene, spec, 64, 48, 1, 0, Integrator::Whitted);
    const Both path = renderBoth(scene, spec, 64, 48, 1, 1, Integrator::Path);
    const glm::vec3 ambient = 0.1f * scene.materials[0].diffuse;
    size_t lit = 0;
    for (const RenderOutput* out : {&path.gl, &path.cpu}) {
        const RenderOutput& w = out == &path.gl ? whitted.gl : whitted.cpu;
        for (size_t i = 0; i < out->color.size(); ++i) {
            const glm::vec3 expected = w.prim[i] >= 0.0f ? w.color[i] - ambient : glm::vec3(0.0f);
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(out->color[i][c], expected[c], 1e-5f * (1.0f + expected[c])) << backendName(path, out) << " " << i;
            lit += expected.x > 0.01f;
        }
    }
    EXPECT_GT(lit, 2u * 64u * 48u / 10u);  // the teapot covers about a fifth of the image
}

// The same samples give the same picture on both backends, and the same paths per bounce.
TEST_F(Paths, CornellBoxAgreesAcrossBackends) {
    const LoadedScene loaded = loadScene("scenes/cornell.json");
    const Both both = renderBoth(loaded.scene, *loaded.scene.camera, 96, 96, 2, kDefaultPathBounces, Integrator::Path);
    expectSamePictures(both.gl, both.cpu, "cornell, path");
    const std::vector<uint64_t>& gl = both.gl.stats.livePaths;
    const std::vector<uint64_t>& cpu = both.cpu.stats.livePaths;
    ASSERT_EQ(gl.size(), size_t(kDefaultPathBounces + 1));
    ASSERT_EQ(cpu.size(), gl.size());
    EXPECT_EQ(gl[0], 96u * 96u * 2u);  // every camera ray
    for (size_t b = 1; b < gl.size(); ++b) {
        EXPECT_LE(gl[b], gl[b - 1]) << b;
        EXPECT_NEAR(double(gl[b]), double(cpu[b]), 1e-3 * double(cpu[b]) + 2.0) << b;
    }
    EXPECT_LT(gl.back(), gl[3] / 2);  // Russian roulette from depth 3 on
}

// Masking the rounds' passes to the live paths (--mask-paths), or tracing them with the split
// kernels, changes the cost, not the image: under a grey sky, so that the paths that leave the
// box must end where they miss.
TEST_F(Paths, MaskedRoundsAndSplitKernelsGiveTheSameImage) {
    LoadedScene loaded = loadScene("scenes/cornell_blocks.json");
    loaded.scene.background = glm::vec3(0.3f);
    const UniformGrid grid = buildGrid(loaded.scene, GridOptions{});
    const CameraBasis camera = makeCamera(*loaded.scene.camera, 48, 40);
    RenderSettings settings;
    settings.integrator = Integrator::Path;
    settings.maxBounces = 5;
    settings.samples = 2;
    GpuTracerOptions masked;
    masked.maskPaths = true;
    const RenderOutput a = GpuTracer(loaded.scene, grid).render(camera, settings);
    const RenderOutput b = GpuTracer(loaded.scene, grid, masked).render(camera, settings);
    EXPECT_EQ(a.color, b.color);
    EXPECT_EQ(a.stats.livePaths, b.stats.livePaths);
    EXPECT_EQ(a.stats.shadowRays, b.stats.shadowRays);
    EXPECT_LT(a.stats.livePaths[1], a.stats.livePaths[0]);  // some paths left through the open side
    GpuTracerOptions split;
    split.kernel = TraceKernel::Split;
    const RenderOutput c = GpuTracer(loaded.scene, grid, split).render(camera, settings);
    EXPECT_EQ(a.color, c.color);
    EXPECT_EQ(a.stats.livePaths, c.stats.livePaths);
}

// The megakernels take the same paths as the wavefront chain (the same random numbers, the same
// sums), whether a pass takes every path to its end or packs the live paths after each 1, 2 or 3
// bounces: the path integrator under a grey sky (paths end where they leave the box) and under an
// environment light (its next-event estimation), and Whitted's ray trees through glass and a
// mirror. The counts of rays and live paths agree as well.
TEST_F(Paths, MegakernelsTakeTheSamePathsAsTheWavefrontChain) {
    struct Case {
        const char* scene;
        Integrator integrator;
        int bounces;
    };
    for (const Case& c : {Case{"scenes/cornell_blocks.json", Integrator::Path, 6}, Case{"scenes/sky.json", Integrator::Path, 4},
                          Case{"scenes/cornell.json", Integrator::Whitted, 6}}) {
        SCOPED_TRACE(c.scene);
        LoadedScene loaded = loadScene(c.scene);
        if (std::string(c.scene) == "scenes/cornell_blocks.json") loaded.scene.background = glm::vec3(0.3f);
        const UniformGrid grid = buildGrid(loaded.scene, GridOptions{});
        const CameraBasis camera = makeCamera(*loaded.scene.camera, 40, 32);
        RenderSettings settings;
        settings.integrator = c.integrator;
        settings.maxBounces = c.bounces;
        settings.samples = 3;
        GpuTracerOptions wavefront;
        wavefront.integratorKernel = IntegratorKernel::Wavefront;
        const RenderOutput a = GpuTracer(loaded.scene, grid, wavefront).render(camera, settings);
        for (int perPass : {0, 1, 2, 3}) {
            if (c.integrator == Integrator::Whitted && perPass > 0) break;  // one pass a tree
            SCOPED_TRACE("bounces a pass " + std::to_string(perPass));
            GpuTracerOptions megakernel;
            megakernel.integratorKernel = IntegratorKernel::Megakernel;
            megakernel.megakernelBounces = perPass;
            const RenderOutput b = GpuTracer(loaded.scene, grid, megakernel).render(camera, settings);
            ASSERT_EQ(a.color.size(), b.color.size());
            for (size_t i = 0; i < a.color.size(); ++i)
                ASSERT_LE(glm::compMax(glm::abs(a.color[i] - b.color[i])), 1e-5f * (1.0f + glm::compMax(a.color[i])))
                    << "pixel " << i;
            EXPECT_EQ(a.stats.primaryRays, b.stats.primaryRays);
            EXPECT_EQ(a.stats.secondaryRays, b.stats.secondaryRays);
            // Within 0.1%, as expectSamePictures: with the watertight triangle test one of
            // cornell_blocks' 6229 next-event shadow rays exists in the megakernel only (the primary
            // AOVs, the secondary rays and the colours agree; every value of the triangle test is
            // `precise`, so where the two kernels round differently is not yet found).
            EXPECT_NEAR(double(a.stats.shadowRays), double(b.stats.shadowRays), 1e-3 * double(a.stats.shadowRays));
            EXPECT_EQ(a.stats.livePaths, b.stats.livePaths);
        }
        EXPECT_GT(a.stats.secondaryRays, 0u);
    }
}

// The Cornell box converges: the RMS error against a long render (another seed, so its own noise
// is independent) falls as 1 / sqrt(spp), a factor 2 for each 4 times the samples. Its sphere and
// block are made diffuse here: the caustics of glass and mirror (light reaching the floor through
// them) are found only by rare BSDF paths of large weight, whose fireflies make the error of a few
// samples too erratic to measure a rate on; CornellBoxAgreesAcrossBackends renders them.
TEST_F(Paths, CornellBoxConvergesAsOneOverTheSquareRootOfTheSamples) {
    LoadedScene loaded = loadScene("scenes/cornell.json");
    Scene& scene = loaded.scene;
    for (Material& m : scene.materials)
        if (m.ior > 0.0f || m.reflectivity != glm::vec3(0.0f)) {
            m = Material{};
            m.diffuse = glm::vec3(0.7f);
            m.specular = glm::vec3(0.0f);
        }
    const int size = 32;
    const UniformGrid grid = buildGrid(scene, GridOptions{});
    const CameraBasis camera = makeCamera(*scene.camera, size, size);
    RenderSettings settings;
    settings.integrator = Integrator::Path;
    settings.maxBounces = kDefaultPathBounces;
    settings.samples = 1024;
    settings.seed = 1;
    const RenderOutput reference = CpuTracer(scene, grid).render(camera, settings);
    GpuTracer tracer(scene, grid);
    // Pixels that see the light, wholly or in part (above 1 in the reference), are left out: their
    // error is the light's edge, which the stratified pixel samples resolve faster than
    // 1 / sqrt(spp).
    auto seesLight = [&](size_t i) { return glm::compMax(reference.color[i]) > 1.0f; };
    std::vector<double> errors;
    for (uint32_t spp : {4u, 16u, 64u}) {
        settings.samples = spp;
        settings.seed = 0;
        const RenderOutput out = tracer.render(camera, settings);
        double sum = 0.0;
        size_t n = 0;
        for (size_t i = 0; i < out.color.size(); ++i) {
            if (seesLight(i)) continue;
            for (int c = 0; c < 3; ++c) sum += std::pow(double(out.color[i][c]) - double(reference.color[i][c]), 2.0);
            n += 3;
        }
        errors.push_back(std::sqrt(sum / double(n)));
    }
    // 4 times the samples: half the error; the reference's own error (a quarter of the last one's)
    // makes the last ratio 2 / sqrt(1 + 1/16). Stratification may do a little better.
    const std::string all = "errors at 4, 16, 64 spp: " + std::to_string(errors[0]) + ", " +
                            std::to_string(errors[1]) + ", " + std::to_string(errors[2]);
    for (size_t k = 1; k < errors.size(); ++k) {
        EXPECT_GT(errors[k - 1] / errors[k], 1.5) << all;
        EXPECT_LT(errors[k - 1] / errors[k], 3.0) << all;
    }
}

}  // namespace
}  // namespace gpurt::test
