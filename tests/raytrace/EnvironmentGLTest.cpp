// The environment light (CONTRACT.md, "Environment light and the default light") on both backends
// and both integrators, each map made by the test and read back from a file: closed forms (a white
// Lambert sphere under L = a + b d.y has radiance albedo (a + 2/3 b n.y) at normal n, and under a
// constant sky shows its albedo), the direction convention and --env-rotate (a small bright patch
// lights the plane facing it and leaves the plane facing away black), and importance sampling (a
// small sun: far less variance than BSDF sampling alone at equal samples, the same mean).
// Statistical tolerances come from the samples' spread: the standard error of their mean.
#include "../common/GLTest.h"
#include "EnvironmentTestMaps.h"
#include "TestScenes.h"

#include <cmath>
#include <functional>

namespace gpurt::test {
namespace {

class Environments : public GLTest {};

struct Estimate {
    double mean = 0.0, error = 0.0;  // error: the standard error of the mean
    double variance = 0.0;           // of one value
    size_t count = 0;
    void add(double x) {
        sum_ += x;
        sum2_ += x * x;
        ++count;
        const double n = double(count);
        mean = sum_ / n;
        variance = std::max(0.0, sum2_ / n - mean * mean);
        error = n > 1.0 ? std::sqrt(variance / (n - 1.0)) : 0.0;
    }

  private:
    double sum_ = 0.0, sum2_ = 0.0;
};

// `seeds` renders of one sample a pixel (the pixel centre, so that the normal AOV is the normal
// of every sample) on each backend, with the tracers built once.
struct Renders {
    std::vector<RenderOutput> gl, cpu;
};
Renders renderSeeds(const Scene& scene, const CameraSpec& spec, int size, int seeds, Integrator integrator,
                    int bounces = 8, uint32_t spp = 1) {
    const UniformGrid grid = buildGrid(scene, GridOptions{});
    const CameraBasis camera = makeCamera(spec, size, size);
    RenderSettings settings;
    settings.width = settings.height = size;
    settings.samples = spp;
    settings.maxBounces = bounces;
    settings.integrator = integrator;
    CpuTracer cpu(scene, grid);
    GpuTracer gl(scene, grid);
    Renders r;
    for (int s = 0; s < seeds; ++s) {
        settings.seed = uint32_t(s);
        r.cpu.push_back(cpu.render(camera, settings));
        r.gl.push_back(gl.render(camera, settings));
    }
    return r;
}

Scene sphereScene(glm::vec3 albedo) {
    Scene scene;
    addIcosphere(scene, glm::vec3(0.0f), 1.0f, 3, addMaterial(scene, albedo));
    return scene;
}

CameraSpec frontCamera() {
    CameraSpec spec;
    spec.eye = {0.0f, 0.0f, 3.0f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.fovy = 45.0f;
    return spec;
}

// L = a + b d.y: the irradiance at normal n is pi a + 2 pi / 3 b n.y, so a Lambert surface of
// albedo k shows k (a + 2/3 b n.y). Whitted's ambient term (the first 9 spherical harmonics) is
// exact for it; the path integrator converges to it. The sphere is convex: nothing else is seen.
TEST_F(Environments, LambertSphereUnderALinearSkyMatchesTheClosedForm) {
    const float a = 0.6f, b = 0.5f, albedo = 0.7f;
    Scene scene = sphereScene(glm::vec3(albedo));
    scene.environment = environmentThroughFile(makeMap(256, 128, [&](glm::vec3 d) { return glm::vec3(a + b * d.y); }),
                                               "linear.exr");
    auto expected = [&](glm::vec3 n) { return double(albedo) * (a + 2.0 / 3.0 * b * n.y); };
    for (Integrator integrator : {Integrator::Whitted, Integrator::Path}) {
        const bool path = integrator == Integrator::Path;
        SCOPED_TRACE(path ? "path" : "whitted");
        const Renders r = renderSeeds(scene, frontCamera(), 40, path ? 8 : 1, integrator);
        for (const std::vector<RenderOutput>* outs : {&r.gl, &r.cpu}) {
            SCOPED_TRACE(outs == &r.gl ? "gl" : "cpu");
            // The residual over the upper and the lower half of the sphere apart: a wrong slope in
            // n.y cannot cancel out.
            Estimate upper, lower;
            size_t hits = 0;
            for (const RenderOutput& out : *outs)
                for (size_t i = 0; i < out.color.size(); ++i) {
                    if (out.prim[i] < 0.0f) {
                        const double x = out.color[i].x;  // the sky itself, between 0.1 and 1.1
                        ASSERT_GE(x, a - b - 1e-3);
                        ASSERT_LE(x, a + b + 1e-3);
                        continue;
                    }
                    ++hits;
                    const glm::vec3 n = out.normal[i];
                    const double residual = out.color[i].y - expected(n);
                    if (!path) {  // the harmonics are exact: pixel by pixel
                        ASSERT_NEAR(out.color[i].y, expected(n), 2e-3 + 5e-3 * expected(n)) << "normal " << n.x << " " << n.y << " " << n.z;
                        ASSERT_EQ(out.color[i].x, out.color[i].y);
                    }
                    if (n.y > 0.3f) upper.add(residual);
                    if (n.y < -0.3f) lower.add(residual);
                }
            ASSERT_GT(hits, 400u);
            for (const Estimate* e : {&upper, &lower}) {
                ASSERT_GT(e->count, 100u);
                EXPECT_NEAR(e->mean, 0.0, 5.0 * e->error + 4e-3) << (e == &upper ? "upper" : "lower") << " half, standard error " << e->error;
                if (path) {
                    EXPECT_LT(e->error, 0.01) << "enough samples to tell";
                }
            }
        }
    }
}

// Under a constant sky L every convex Lambert object shows albedo x L (a white furnace through a
// Radiance file); the sky's value is the one the file holds (RGBE rounds 0.8).
TEST_F(Environments, LambertSphereUnderAConstantSkyShowsItsAlbedo) {
    const glm::vec3 albedo(0.2f, 0.5f, 0.8f);
    Scene scene = sphereScene(albedo);
    scene.environment = environmentThroughFile(makeMap(64, 32, [](glm::vec3) { return glm::vec3(0.8f); }), "constant.hdr");
    const float sky = scene.environment->image->texels[0].x;
    ASSERT_NEAR(sky, 0.8f, 0.004f);
    for (Integrator integrator : {Integrator::Whitted, Integrator::Path}) {
        const bool path = integrator == Integrator::Path;
        SCOPED_TRACE(path ? "path" : "whitted");
        const Renders r = renderSeeds(scene, frontCamera(), 32, path ? 4 : 1, integrator);
        for (const std::vector<RenderOutput>* outs : {&r.gl, &r.cpu}) {
            SCOPED_TRACE(outs == &r.gl ? "gl" : "cpu");
            for (int c = 0; c < 3; ++c) {
                Estimate e;
                for (const RenderOutput& out : *outs)
                    for (size_t i = 0; i < out.color.size(); ++i) {
                        if (out.prim[i] < 0.0f) {
                            ASSERT_NEAR(out.color[i][c], sky, 1e-6f);
                            continue;
                        }
                        // Whitted: the harmonics of a 64 x 32 map, to a part in a thousand.
                        if (!path) {
                            ASSERT_NEAR(out.color[i][c], albedo[c] * sky, 1e-3f * albedo[c] * sky) << i;
                        }
                        e.add(out.color[i][c]);
                    }
                EXPECT_NEAR(e.mean, albedo[c] * sky, 5.0 * e.error + 1e-3 * albedo[c] * sky)
                    << "channel " << c << ", standard error " << e.error;
            }
        }
    }
}

// A bright patch of 10 degrees' radius about `towards` and nothing else.
Environment patchEnvironment(glm::vec3 towards, float rotation, const std::string& name) {
    const glm::vec3 k = glm::normalize(towards);
    const float cosRadius = std::cos(10.0f * 3.14159265f / 180.0f);
    return environmentThroughFile(
        makeMap(128, 64, [&](glm::vec3 d) { return glm::dot(d, k) > cosRadius ? glm::vec3(50.0f) : glm::vec3(0.0f); }),
        name, 1.0f, rotation);
}

// The mean and the largest colour of the pixels that show a 2 x 2 square at the origin facing
// `facing`, path traced, seen from 3 units along `facing`.
struct PlaneLight {
    double meanGl = 0.0, meanCpu = 0.0, largest = 0.0;
};
PlaneLight litPlane(const Environment& env, glm::vec3 facing) {
    const glm::vec3 n = glm::normalize(facing);
    const glm::vec3 helper = std::abs(n.y) > 0.9f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    const glm::vec3 s = glm::normalize(glm::cross(helper, n)), t = glm::cross(n, s);
    Scene scene;
    const uint32_t white = addMaterial(scene, glm::vec3(0.8f));
    addPolygon(scene, {-s - t, s - t, s + t, -s + t}, white);
    scene.environment = env;
    CameraSpec spec;
    spec.eye = 3.0f * n;
    spec.target = glm::vec3(0.0f);
    spec.up = t;
    spec.fovy = 30.0f;
    const Renders r = renderSeeds(scene, spec, 16, 1, Integrator::Path, 2, 16);
    PlaneLight p;
    for (const RenderOutput* out : {&r.gl[0], &r.cpu[0]}) {
        Estimate e;
        for (size_t i = 0; i < out->color.size(); ++i) {
            if (out->prim[i] < 0.0f) continue;
            e.add(out->color[i].x);
            p.largest = std::max(p.largest, double(glm::max(out->color[i].x, glm::max(out->color[i].y, out->color[i].z))));
        }
        EXPECT_GT(e.count, 100u);
        (out == &r.gl[0] ? p.meanGl : p.meanCpu) = e.mean;
    }
    return p;
}

// The patch is where the contract's formula puts it: +x (u = 0.75, v = 0.5), -z (u = 0.5: the
// middle of the map) and +y (the top row) each light the plane facing them (irradiance about
// 50 x 0.095 sr: radiance about 1.2 on a plane of albedo 0.8) and none of the plane facing away.
TEST_F(Environments, ABrightPatchLightsThePlaneFacingItAndNotThePlaneFacingAway) {
    for (glm::vec3 towards : {glm::vec3(1, 0, 0), glm::vec3(0, 0, -1), glm::vec3(0, 1, 0)}) {
        SCOPED_TRACE(testing::Message() << "patch towards " << towards.x << "," << towards.y << "," << towards.z);
        const Environment env = patchEnvironment(towards, 0.0f, "patch.hdr");
        const PlaneLight facing = litPlane(env, towards), away = litPlane(env, -towards);
        EXPECT_GT(facing.meanGl, 0.6);
        EXPECT_GT(facing.meanCpu, 0.6);
        EXPECT_LT(facing.meanGl, 2.0);
        EXPECT_EQ(away.largest, 0.0);
    }
}

// --env-rotate 90 turns the map counter-clockwise seen from above (+Y): what was at +x is then at
// -z, and what was at -z at -x; -90 takes +x to +z.
TEST_F(Environments, RotationTurnsTheMapCounterClockwiseSeenFromAbove) {
    struct Case {
        glm::vec3 patch;
        float degrees;
        glm::vec3 after;
    };
    for (const Case& c : {Case{{1, 0, 0}, 90.0f, {0, 0, -1}}, Case{{0, 0, -1}, 90.0f, {-1, 0, 0}},
                          Case{{1, 0, 0}, -90.0f, {0, 0, 1}}}) {
        SCOPED_TRACE(testing::Message() << "rotation " << c.degrees);
        const Environment env = patchEnvironment(c.patch, c.degrees, "turned.exr");
        const PlaneLight turned = litPlane(env, c.after);
        EXPECT_GT(turned.meanGl, 0.6);
        EXPECT_GT(turned.meanCpu, 0.6);
        EXPECT_EQ(litPlane(env, -c.after).largest, 0.0);
        // The patch's old place is now at right angles: half of it at grazing light at most.
        EXPECT_LT(litPlane(env, c.patch).meanGl, 0.15 * turned.meanGl);
    }
}

// A small bright sun (3 degrees' radius, 400 times brighter than the sky) over a plane: sampling
// the environment by its luminance with MIS gives far less variance than BSDF sampling alone,
// which finds the sun in a few samples of a thousand; both estimate the same radiance.
TEST_F(Environments, ImportanceSamplingASmallSunCutsTheVarianceAndKeepsTheMean) {
    const glm::vec3 sun = glm::normalize(glm::vec3(0.5f, 1.0f, 0.3f));
    const float cosRadius = std::cos(3.0f * 3.14159265f / 180.0f);
    const EnvironmentImage map = makeMap(512, 256, [&](glm::vec3 d) {
        return glm::dot(d, sun) > cosRadius ? glm::vec3(400.0f) : glm::vec3(0.3f);
    });
    Scene scene;
    addPolygon(scene, {{-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, {-2, 0, -2}}, addMaterial(scene, glm::vec3(0.8f)));
    CameraSpec spec;
    spec.eye = {0.0f, 3.0f, 0.0f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.up = {0.0f, 0.0f, -1.0f};
    spec.fovy = 40.0f;
    Estimate estimates[2][2];  // [mis, bsdf][gl, cpu]: the pixels (each the mean of 16 samples)
    for (int bsdf = 0; bsdf < 2; ++bsdf) {
        scene.environment = environmentThroughFile(map, "sun.hdr", 1.0f, 0.0f, bsdf == 0);
        const Renders r = renderSeeds(scene, spec, 48, 1, Integrator::Path, 1, 16);
        for (int backend = 0; backend < 2; ++backend) {
            const RenderOutput& out = backend == 0 ? r.gl[0] : r.cpu[0];
            for (size_t i = 0; i < out.color.size(); ++i) {
                ASSERT_GE(out.prim[i], 0.0f);  // the plane fills the image
                estimates[bsdf][backend].add(out.color[i].x);
            }
        }
    }
    for (int backend = 0; backend < 2; ++backend) {
        SCOPED_TRACE(backend == 0 ? "gl" : "cpu");
        const Estimate& mis = estimates[0][backend];
        const Estimate& bsdf = estimates[1][backend];
        EXPECT_GT(bsdf.variance, 20.0 * mis.variance) << "MIS variance " << mis.variance << ", BSDF-only " << bsdf.variance;
        EXPECT_NEAR(mis.mean, bsdf.mean, 5.0 * std::sqrt(mis.error * mis.error + bsdf.error * bsdf.error))
            << "MIS " << mis.mean << " +- " << mis.error << ", BSDF-only " << bsdf.mean << " +- " << bsdf.error;
        EXPECT_GT(mis.mean, 0.5);  // the sun lights the plane: about 0.8 / pi (3.1 + 0.94)
    }
}

}  // namespace
}  // namespace gpurt::test
