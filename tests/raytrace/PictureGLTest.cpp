// The pictures' features on both backends (the GL chain and the CPU backend, the same samples):
// against closed forms (the irradiance of polygon emitters by Lambert's formula, the coverage of
// an anti-aliased edge, the transmission of a glass slab), and against each other on the Cornell
// box (area light, glass, mirror) and the smooth-shaded bunny. Statistical tolerances come from
// the sample count.
#include "../common/GLTest.h"
#include "TestScenes.h"

#include "raytrace/camera/Camera.h"
#include "image/Colour.h"
#include "raytrace/render/CpuTracer.h"
#include "raytrace/render/GpuTracer.h"
#include "image/ImageIO.h"
#include "scene/ObjLoader.h"
#include "raytrace/scene/SceneLoader.h"
#include "scene/SmoothNormals.h"
#include "raytrace/accel/grid/UniformGrid.h"
#include "../../glsl/common/scene_layout.h"

#include <cmath>
#include <set>
#include <tuple>

namespace gpurt::test {
namespace {

class Pictures : public GLTest {};

// Irradiance at p (normal n) from a polygon of radiance le (Lambert 1760): le / 2 times the sum
// over its edges of the angle each subtends times the cosine of that edge's plane with n.
double lambertIrradiance(glm::dvec3 p, glm::dvec3 n, const std::vector<glm::vec3>& corners, double le) {
    double sum = 0.0;
    for (size_t i = 0; i < corners.size(); ++i) {
        const glm::dvec3 a = glm::normalize(glm::dvec3(corners[i]) - p);
        const glm::dvec3 b = glm::normalize(glm::dvec3(corners[(i + 1) % corners.size()]) - p);
        sum += std::acos(glm::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(n, glm::normalize(glm::cross(a, b)));
    }
    return 0.5 * le * std::fabs(sum);
}

// One pixel looking at the origin of a white floor (y = 0) lit by an emitter above it: the
// radiance is the ambient term plus kd / pi times the irradiance of Lambert's formula. Each of the
// N samples estimates the irradiance with one point of the emitter, an estimate between the
// emitter seen from its farthest and from its nearest point; the tolerance is 4 standard
// deviations of N such estimates, at most half that range each.
TEST_F(Pictures, PolygonEmittersGiveLambertsIrradiance) {
    const double kd = 0.5, le = 3.0, h = 1.0;
    const uint32_t samples = 1024;
    std::vector<std::vector<glm::vec3>> emitters;
    emitters.push_back({{-0.25f, 1.0f, -0.25f}, {0.25f, 1.0f, -0.25f}, {0.25f, 1.0f, 0.25f}, {-0.25f, 1.0f, 0.25f}});
    std::vector<glm::vec3> disk;  // a 16-gon of radius 0.3
    for (int k = 0; k < 16; ++k)
        disk.push_back({0.3f * std::cos(2.0f * float(M_PI) * float(k) / 16.0f), 1.0f,
                        0.3f * std::sin(2.0f * float(M_PI) * float(k) / 16.0f)});
    emitters.push_back(disk);
    for (const std::vector<glm::vec3>& emitter : emitters) {
        SCOPED_TRACE(std::to_string(emitter.size()) + "-gon");
        Scene scene;
        scene.background = glm::vec3(0.0f);
        addPolygon(scene, {{-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}}, addMaterial(scene, glm::vec3(float(kd))));
        addPolygon(scene, emitter, addMaterial(scene, glm::vec3(0.0f), glm::vec3(float(le))));
        CameraSpec spec;
        spec.eye = {3.0f, 1.0f, 0.0f};  // beside the emitter, which does not hide the origin
        spec.target = {0.0f, 0.0f, 0.0f};
        spec.fovy = 0.01f;
        const Both both = renderBoth(scene, spec, 1, 1, samples);
        const double e = lambertIrradiance({0, 0, 0}, {0, 1, 0}, emitter, le);
        const double expected = 0.1 * kd + kd / M_PI * e;
        double area = 0.0, farthest2 = 0.0;
        for (size_t i = 1; i + 1 < emitter.size(); ++i)
            area += 0.5 * glm::length(glm::cross(glm::dvec3(emitter[i] - emitter[0]), glm::dvec3(emitter[i + 1] - emitter[0])));
        for (const glm::vec3& c : emitter) farthest2 = std::max(farthest2, glm::dot(glm::dvec3(c), glm::dvec3(c)));
        const double nearest = le * area / (h * h), farthest = le * area * h * h / (farthest2 * farthest2);
        const double tolerance = kd / M_PI * 4.0 * 0.5 * (nearest - farthest) / std::sqrt(double(samples));
        for (const RenderOutput* out : {&both.gl, &both.cpu})
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(out->color[0][c], expected, tolerance) << (out == &both.gl ? "gl" : "cpu");
        EXPECT_NEAR(both.gl.color[0].x, both.cpu.color[0].x, 1e-4 * expected);  // the same samples
    }
}

// An emitting quad seen against black, its edge through a pixel at a known fraction: with N
// stratified samples the pixel's value approaches the radiance times the fraction it covers.
// Tolerance: 4 standard deviations of the fraction of N independent samples.
TEST_F(Pictures, AntiAliasedEdgePixelApproachesItsCoverage) {
    const int size = 16;
    const uint32_t samples = 256;
    const float le = 0.5f;
    CameraSpec spec;
    spec.eye = {0.0f, 0.0f, 5.0f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.fovy = 30.0f;
    const CameraBasis camera = makeCamera(spec, size, size);
    // The quad's edge at image column x = 8.3 (in pixels from the left), in the plane z = 0.
    const double edgeColumn = 8.3, coverage = 9.0 - edgeColumn;
    const float edgeX = float(5.0 * (edgeColumn / size * 2.0 - 1.0) * camera.tanHalf * camera.aspect);
    Scene scene;
    scene.background = glm::vec3(0.0f);
    addPolygon(scene, {{edgeX, -10, 0}, {10, -10, 0}, {10, 10, 0}, {edgeX, 10, 0}},
               addMaterial(scene, glm::vec3(0.0f), glm::vec3(le)));
    const Both both = renderBoth(scene, spec, size, size, samples);
    const double tolerance = 4.0 * std::sqrt(coverage * (1.0 - coverage) / double(samples)) * le;
    for (const RenderOutput* out : {&both.gl, &both.cpu}) {
        const std::string backend = out == &both.gl ? "gl" : "cpu";
        for (int row = 0; row < size; ++row) {
            const size_t at = size_t(row) * size_t(size);
            EXPECT_NEAR(out->color[at + 8].x, coverage * le, tolerance) << backend << " row " << row;
            EXPECT_EQ(out->color[at + 7].x, 0.0f) << backend << " row " << row;
            EXPECT_EQ(out->color[at + 9].x, le) << backend << " row " << row;
            // The AOVs stay the pixel centre's: the centre of column 8 (x = 8.5) is on the quad.
            EXPECT_GE(out->prim[at + 8], 0.0f) << backend << " row " << row;
            EXPECT_EQ(out->prim[at + 7], -1.0f) << backend << " row " << row;
        }
    }
}

// A pixel seen through a parallel slab of glass (index n, filter tf) at normal incidence in front
// of an emitter of radiance 1 on black: each pass through an interface transmits 1 - F of it,
// F = ((n - 1) / (n + 1))^2, so the light that reaches the eye after 2k internal reflections is
// (1 - F)^2 tf^2 F^2k, summed over the k the ray tree reaches (depths up to --bounces, children
// of weight at least GPURT_MIN_WEIGHT = 1e-4: shading.h).
TEST_F(Pictures, GlassSlabTransmitsAsTheFresnelSeriesSays) {
    const double n = 2.4, tf = 0.9;
    const int bounces = 8;
    Scene scene;
    scene.background = glm::vec3(0.0f);
    addBox(scene, {-5, -5, -0.5f}, {5, 5, 0.5f}, addMaterial(scene, glm::vec3(0.0f), glm::vec3(0.0f), float(n), glm::vec3(float(tf))));
    addPolygon(scene, {{-20, -20, -2}, {20, -20, -2}, {20, 20, -2}, {-20, 20, -2}},
               addMaterial(scene, glm::vec3(0.0f), glm::vec3(1.0f)));
    CameraSpec spec;
    spec.eye = {0.0f, 0.0f, 5.0f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.fovy = 0.01f;
    const Both both = renderBoth(scene, spec, 1, 1, 1, bounces);
    const double f = std::pow((n - 1.0) / (n + 1.0), 2.0);
    // The chain of rays inside the slab: weight (1 - F) tf F^j at depth j + 1; the one leaving
    // towards the emitter after it has weight (1 - F)^2 tf^2 F^2k, at depth 2k + 2.
    double expected = 0.0;
    for (int k = 0; 2 * k + 1 < bounces; ++k) {  // the back-face hit that sends term k out: depth 2k + 1
        const double inside = (1.0 - f) * tf * std::pow(f, 2 * k);  // the ray reaching the back face
        const double front = k == 0 ? 1.0 : (1.0 - f) * tf * std::pow(f, 2 * k - 1);  // the one before it
        const double out = inside * (1.0 - f) * tf;
        if (front < 1e-4 || inside < 1e-4 || out < 1e-4) break;
        expected += out;
    }
    ASSERT_GT(expected, 0.5);
    for (const RenderOutput* out : {&both.gl, &both.cpu})
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(out->color[0][c], expected, 1e-5) << (out == &both.gl ? "gl" : "cpu");
    // The whole series: (1 - F)^2 tf^2 / (1 - F^2); the tree stops short of it by less than 1e-3.
    EXPECT_NEAR(expected, (1.0 - f) * (1.0 - f) * tf * tf / (1.0 - f * f), 1e-3);
}

TEST_F(Pictures, CornellBoxWithLightGlassAndMirrorAgreesAcrossBackends) {
    const LoadedScene loaded = loadScene("scenes/cornell.json");
    const Both both = renderBoth(loaded.scene, *loaded.scene.camera, 96, 96, 2, loaded.scene.maxBounces);
    expectSamePictures(both.gl, both.cpu, "cornell");
    EXPECT_GT(both.gl.stats.secondaryRays, 96u * 96u / 10);  // glass and mirror rays were traced
}

TEST_F(Pictures, SmoothBunnyWithSamplesAgreesAcrossBackends) {
    Scene scene = loadObj("../shared/models/bunny.obj");
    smoothNormals(scene, kDefaultCreaseDegrees);
    const Bounds b = scene.bounds();
    CameraSpec spec = defaultCamera(b, 80, 64);
    const Both both = renderBoth(scene, spec, 80, 64, 4);
    expectSamePictures(both.gl, both.cpu, "bunny");
    // The AOVs are the pixel centres' whatever the sample count.
    const Both single = renderBoth(scene, spec, 80, 64, 1);
    for (const Both* r : {&both, &single}) {
        EXPECT_EQ(r->gl.prim, single.cpu.prim);
        EXPECT_EQ(r->cpu.depth, single.cpu.depth);
        EXPECT_EQ(r->cpu.normal, single.cpu.normal);
        EXPECT_EQ(r->gl.steps, single.cpu.steps);
    }
    // Smooth shading changes the picture, not the hits.
    Scene faceted = loadObj("../shared/models/bunny.obj");
    const Both flat = renderBoth(faceted, spec, 80, 64, 1);
    EXPECT_EQ(flat.cpu.prim, single.cpu.prim);
    EXPECT_NE(flat.cpu.color, single.cpu.color);
}

}  // namespace
}  // namespace gpurt::test

namespace gpurt::test {
namespace {

// The toy material model GPURT_MODEL_DEBUG_NORMAL (glsl/common/materials/debug_normal.h), added as
// docs/ARCHITECTURE.md says a model is added: an icosphere of it beside a classic floor under a
// light shows 0.5 n + 0.5 of its facet normals (the normal AOV: no vertex normals), on both
// backends and under both integrators, whatever the light; the floor agrees across backends.
TEST_F(Pictures, DebugNormalModelShowsItsNormalsUnderBothIntegrators) {
    Scene scene;
    scene.background = glm::vec3(0.0f);
    const uint32_t debug = addMaterial(scene, glm::vec3(0.8f));
    scene.materials[debug].model = GPURT_MODEL_DEBUG_NORMAL;
    addIcosphere(scene, {0.0f, 0.6f, 0.0f}, 0.5f, 1, debug);
    addPolygon(scene, {{-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}}, addMaterial(scene, glm::vec3(0.5f)));
    scene.lights.push_back({{0.0f, 3.0f, 2.0f}, glm::vec3(1.0f), 4.0f});
    CameraSpec spec;
    spec.eye = {0.3f, 1.2f, 2.5f};
    spec.target = {0.0f, 0.4f, 0.0f};
    for (const Integrator integrator : {Integrator::Whitted, Integrator::Path}) {
        SCOPED_TRACE(integrator == Integrator::Path ? "path" : "whitted");
        const Both both = renderBoth(scene, spec, 40, 30, 1, 3, integrator);
        size_t sphere = 0, floor = 0;
        for (size_t i = 0; i < both.gl.color.size(); ++i) {
            ASSERT_EQ(both.gl.prim[i], both.cpu.prim[i]) << i;
            if (both.gl.prim[i] < 0.0f) continue;
            const uint32_t material = scene.materialIds[size_t(both.gl.prim[i])];
            if (material == debug) {
                for (const RenderOutput* out : {&both.gl, &both.cpu})
                    for (int c = 0; c < 3; ++c) ASSERT_NEAR(out->color[i][c], 0.5f * out->normal[i][c] + 0.5f, 1e-6f) << i;
            } else {  // the floor, lit as the backends light it (the sphere's shadow included)
                for (int c = 0; c < 3; ++c) ASSERT_NEAR(both.gl.color[i][c], both.cpu.color[i][c], 1e-4f) << i;
            }
            (material == debug ? sphere : floor) += 1;
        }
        EXPECT_GT(sphere, 100u);
        EXPECT_GT(floor, 100u);
    }
}

// The materials texture wraps after GPURT_MATERIALS_PER_ROW materials (glsl/common/scene_layout.h):
// a 40 x 30 grid of quads, each of its own material (1200, three rows' worth) glowing its own
// colour, seen head-on by Whitted on both backends. The cpu backend reads the scene's materials,
// not the texture: the pictures agree, and over a thousand colours show.
TEST_F(Pictures, MaterialsPastTheFirstRowOfTheTextureKeepTheirOwn) {
    Scene scene;
    const int columns = 40, rows = 30;
    for (int k = 0; k < columns * rows; ++k) {
        const int i = k % columns, j = k / columns;
        const glm::vec3 glow(float(i + 1) / float(columns), float(j + 1) / float(rows), 0.5f);
        const uint32_t m = addMaterial(scene, glm::vec3(0.0f), glow);
        scene.materials[m].specular = glm::vec3(0.0f);
        scene.materials[m].emissionIsLight = false;  // a glow: no emitter table, no shadow rays
        const float x = float(i) - 0.5f * float(columns), y = float(j) - 0.5f * float(rows);
        addPolygon(scene, {{x, y, 0.0f}, {x + 1.0f, y, 0.0f}, {x + 1.0f, y + 1.0f, 0.0f}, {x, y + 1.0f, 0.0f}}, m);
    }
    ASSERT_GT(scene.materials.size(), size_t(2 * GPURT_MATERIALS_PER_ROW));
    CameraSpec spec;
    spec.eye = {0.0f, 0.0f, 40.0f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.fovy = 45.0f;
    const Both both = renderBoth(scene, spec, 160, 120, 1, 0);
    // The pictures only: the default light's shadow rays from the quads' shared edges differ in
    // number between the backends (rounding at the seams; a 20 x 20 grid in one row does the same).
    expectSamePictures(both.gl, both.cpu, "1200 materials", false);
    std::set<std::tuple<float, float, float>> colours;
    for (const glm::vec3& c : both.gl.color) colours.insert({c.x, c.y, c.z});
    EXPECT_GT(colours.size(), size_t(1000));
}

}  // namespace
}  // namespace gpurt::test
