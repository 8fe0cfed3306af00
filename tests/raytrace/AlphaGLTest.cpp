// Alpha coverage (glTF alphaMode MASK / BLEND, MTL d) on both backends and both accelerators: a
// horizontal quad with a 4 x 4 checkerboard alpha texture in MASK mode. Where a pixel's centre ray
// meets the quad, the test computes the texture cell here in double (the contract's camera,
// written out): the ray shows the background where the cell's alpha (0 or 1, filtered: it crosses
// the cutoff 0.5 on the cells' borders) is below the cutoff and the quad where it is not. The
// quad's shadow on a floor below has holes exactly where a floor point's shadow ray to the light
// crosses the quad in a cell of alpha 0: such a point is as lit as with a quad that covers
// nothing, the others as dark as under an opaque quad. BLEND with alpha 0.3 (and MTL d 0.5): the
// fraction of samples that see an emitting quad is the alpha within five standard deviations of
// the binomial count.
#include "../common/GLTest.h"
#include "TestScenes.h"

#include "raytrace/materials/AlphaCoverage.h"
#include "raytrace/render/Renderer.h"
#include "raytrace/accel/Acceleration.h"
#include "scene/ObjLoader.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

namespace gpurt::test {
namespace {

class AlphaCoverageGL : public GLTest {};

constexpr int kCells = 4;            // the checkerboard's texels a side
constexpr double kQuadHeight = 1.0;  // the quad: y = 1, x and z in [-1, 1]
const glm::vec3 kBackground(0.2f, 0.5f, 0.9f);

// Scene: an optional floor (triangles 0, 1; y = 0, x and z in [-3, 3]), then the quad with the
// checkerboard alpha texture (cell (0, 0) alpha 1) in MASK mode, cutoff 0.5.
Scene checkerScene(bool floor) {
    Scene scene;
    scene.background = kBackground;
    if (floor) {
        const uint32_t grey = addMaterial(scene, glm::vec3(0.7f));
        addPolygon(scene, {{-3, 0, -3}, {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}}, grey);
    }
    Material quad;
    quad.diffuse = glm::vec3(0.8f, 0.3f, 0.2f);
    quad.alphaMode = 1;  // GPURT_ALPHA_MASK
    quad.alphaCutoff = 0.5f;
    quad.alphaTexture = {0, 3};
    scene.materials.push_back(quad);
    const uint32_t q = uint32_t(scene.materials.size() - 1);
    const float y = float(kQuadHeight);
    addPolygon(scene, {{-1, y, -1}, {1, y, -1}, {1, y, 1}, {-1, y, 1}}, q);
    Texture checker;
    checker.name = "checker";
    checker.wrapS = checker.wrapT = kWrapClamp;
    checker.image.width = checker.image.height = kCells;
    for (int row = 0; row < kCells; ++row)
        for (int column = 0; column < kCells; ++column)
            checker.image.texels.push_back(0x00c8c8c8u |
                                           ((row + column) % 2 == 0 ? 0xff000000u : 0u));
    scene.textures.push_back(checker);
    // Image coordinates ((x + 1) / 2, (z + 1) / 2) on the quad; zeros on the floor.
    auto uv = [](glm::vec3 p) { return glm::vec2((p.x + 1.0f) / 2.0f, (p.z + 1.0f) / 2.0f); };
    for (const Triangle& t : scene.triangles)
        scene.texcoords.push_back(scene.materialIds[scene.texcoords.size()] == q
                                      ? TriangleTexcoords{uv(t.v0), uv(t.v1), uv(t.v2)}
                                      : TriangleTexcoords{});
    return scene;
}

// Whether the quad covers its point (x, z): the cell's alpha is 1; false with `clear` false when
// the point lies within `margin` cells of a cell border or outside the quad (no expectation).
bool coveredAt(double x, double z, double margin, bool& clear) {
    const double s = (x + 1.0) / 2.0 * kCells, t = (z + 1.0) / 2.0 * kCells;
    clear = s > margin && t > margin && s < kCells - margin && t < kCells - margin &&
            std::abs(s - std::round(s)) > margin && std::abs(t - std::round(t)) > margin;
    return (int(std::floor(s)) + int(std::floor(t))) % 2 == 0;
}

// The centre ray of pixel (i, j) of a size x size image of `spec` (CONTRACT.md's camera).
glm::dvec3 centreRay(const CameraSpec& spec, int size, int i, int j) {
    const glm::dvec3 eye(spec.eye), forward = glm::normalize(glm::dvec3(spec.target) - eye);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(spec.up)));
    const glm::dvec3 up = glm::cross(right, forward);
    const double tanHalf = std::tan(double(spec.fovy) * 3.14159265358979323846 / 360.0);
    const double u = ((i + 0.5) / size * 2.0 - 1.0) * tanHalf,
                 v = (1.0 - (j + 0.5) / size * 2.0) * tanHalf;
    return forward + u * right + v * up;
}

struct Variant {
    const char* accel;
    Backend backend;
    TraceKernel kernel;
    const char* name;
};
const Variant kVariants[] = {{"grid", Backend::Cpu, TraceKernel::Fused, "grid cpu"},
                             {"grid", Backend::Gl, TraceKernel::Fused, "grid gl"},
                             {"grid", Backend::Gl, TraceKernel::Split, "grid gl split"},
                             {"bvh", Backend::Cpu, TraceKernel::Fused, "bvh cpu"},
                             {"bvh", Backend::Gl, TraceKernel::Fused, "bvh gl"}};

RenderOutput render(const Scene& scene, const CameraSpec& spec, int size, const Variant& v,
                    Integrator integrator = Integrator::Whitted, uint32_t samples = 1) {
    const CameraBasis camera = makeCamera(spec, size, size);
    const Acceleration accel =
        chooseAcceleration(scene, v.accel, nullptr, {}, camera);
    RenderSettings settings;
    settings.width = settings.height = size;
    settings.samples = samples;
    settings.integrator = integrator;
    settings.maxBounces = 3;
    GpuTracerOptions options;
    options.kernel = v.kernel;
    return makeRenderer(RendererConfig{v.backend, integrator, options}, scene, accel)
        ->render(camera, settings);
}

TEST_F(AlphaCoverageGL, MaskShowsTheBackgroundWhereAlphaIsBelowTheCutoff) {
    const Scene scene = checkerScene(false);
    CameraSpec spec;
    spec.eye = {0.05f, 4.0f, 0.03f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.up = {0.0f, 0.0f, -1.0f};
    spec.fovy = 40.0f;
    constexpr int kSize = 48;
    for (const Variant& v : kVariants)
        for (Integrator integrator : {Integrator::Whitted, Integrator::Path}) {
            SCOPED_TRACE(std::string(v.name) +
                         (integrator == Integrator::Path ? " path" : " whitted"));
            const RenderOutput out = render(scene, spec, kSize, v, integrator);
            size_t covered = 0, holes = 0;
            for (int j = 0; j < kSize; ++j)
                for (int i = 0; i < kSize; ++i) {
                    const glm::dvec3 d = centreRay(spec, kSize, i, j);
                    const double t = (kQuadHeight - double(spec.eye.y)) / d.y;
                    bool clear = false;
                    const bool expectCovered = coveredAt(double(spec.eye.x) + t * d.x,
                                                         double(spec.eye.z) + t * d.z, 0.05, clear);
                    if (!clear) continue;
                    const size_t at = size_t(j) * kSize + size_t(i);
                    if (expectCovered) {
                        ASSERT_GE(out.prim[at], 0.0f) << "pixel " << i << ", " << j;
                        ++covered;
                    } else {
                        ASSERT_EQ(out.prim[at], -1.0f) << "pixel " << i << ", " << j;
                        if (integrator == Integrator::Whitted) {
                            ASSERT_EQ(out.color[at], kBackground) << "pixel " << i << ", " << j;
                        }
                        ++holes;
                    }
                }
            EXPECT_GT(covered, 600u);
            EXPECT_GT(holes, 600u);
        }
}

TEST_F(AlphaCoverageGL, MaskShadowHasHolesWhereAlphaIsBelowTheCutoff) {
    Scene scene = checkerScene(true);
    scene.lights.push_back({glm::vec3(0.0f, 50.0f, 0.0f), glm::vec3(1.0f), 2500.0f});
    Scene opaque = scene, clear = scene;
    opaque.materials[1].alphaMode = 0;
    clear.materials[1].alphaMode = 2;  // BLEND with alpha 0: covers nothing
    clear.materials[1].alphaFactor = 0.0f;
    CameraSpec spec;  // between the quad and the floor, looking down
    spec.eye = {0.02f, 0.5f, 0.01f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.up = {0.0f, 0.0f, -1.0f};
    spec.fovy = 120.0f;
    constexpr int kSize = 40;
    for (const Variant& v : kVariants) {
        SCOPED_TRACE(v.name);
        const RenderOutput out = render(scene, spec, kSize, v);
        const RenderOutput dark = render(opaque, spec, kSize, v);
        const RenderOutput lit = render(clear, spec, kSize, v);
        size_t shadowed = 0, holes = 0;
        for (int j = 0; j < kSize; ++j)
            for (int i = 0; i < kSize; ++i) {
                const glm::dvec3 d = centreRay(spec, kSize, i, j);
                const glm::dvec3 p =
                    glm::dvec3(spec.eye) + (-double(spec.eye.y) / d.y) * d;  // on the floor
                // The shadow ray from p to the light crosses y = 1 at p + (light - p) / 50.
                const double f = kQuadHeight / 50.0;
                bool clearCell = false;
                const bool blocked = coveredAt(p.x * (1.0 - f), p.z * (1.0 - f), 0.05, clearCell);
                if (!clearCell) continue;
                const size_t at = size_t(j) * kSize + size_t(i);
                ASSERT_TRUE(out.prim[at] == 0.0f || out.prim[at] == 1.0f)
                    << "the floor, pixel " << i << ", " << j;
                ASSERT_GT(lit.color[at].x, dark.color[at].x * 1.5f) << "pixel " << i << ", " << j;
                const glm::vec3 expected = blocked ? dark.color[at] : lit.color[at];
                for (int c = 0; c < 3; ++c)
                    ASSERT_NEAR(out.color[at][c], expected[c], 1e-5f + 1e-5f * expected[c])
                        << (blocked ? "shadow" : "hole") << " at pixel " << i << ", " << j;
                ++(blocked ? shadowed : holes);
            }
        EXPECT_GT(shadowed, 300u);
        EXPECT_GT(holes, 300u);
    }
}

// The mean colour of an emitting quad of radiance 1 over a black background: the covered fraction.
double meanCoverage(const Scene& scene, const Variant& v, uint32_t samples, int size) {
    CameraSpec spec;  // the image lies inside the quad (y = 1, [-1, 1]^2)
    spec.eye = {0.0f, 4.0f, 0.0f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.up = {0.0f, 0.0f, -1.0f};
    spec.fovy = 20.0f;
    const RenderOutput out = render(scene, spec, size, v, Integrator::Whitted, samples);
    double sum = 0.0;
    for (const glm::vec3& c : out.color) sum += double(c.x);
    return sum / double(out.color.size());
}

Scene emittingQuad(float alpha) {
    Scene scene;
    scene.background = glm::vec3(0.0f);
    const uint32_t m = addMaterial(scene, glm::vec3(0.0f), glm::vec3(1.0f));
    scene.materials[m].alphaMode = 2;  // GPURT_ALPHA_BLEND
    scene.materials[m].alphaFactor = alpha;
    addPolygon(scene, {{-1, 1, -1}, {1, 1, -1}, {1, 1, 1}, {-1, 1, 1}}, m);
    return scene;
}

// BLEND: each (pixel, sample) sees the quad with probability alpha; the mean over n = pixels x
// samples draws is alpha within five standard deviations sqrt(alpha (1 - alpha) / n).
TEST_F(AlphaCoverageGL, BlendCoverageIsTheAlphaOnAverage) {
    constexpr int kSize = 32;
    constexpr uint32_t kSamples = 16;
    const double n = double(kSize * kSize) * kSamples;
    const float alpha = 0.3f;
    const Scene scene = emittingQuad(alpha);
    double gl = -1.0;
    for (const Variant& v : kVariants) {
        if (v.kernel == TraceKernel::Split) continue;
        SCOPED_TRACE(v.name);
        const double mean = meanCoverage(scene, v, kSamples, kSize);
        EXPECT_NEAR(mean, alpha, 5.0 * std::sqrt(alpha * (1.0 - alpha) / n));
        if (v.backend == Backend::Gl) {
            if (gl >= 0.0) {
                EXPECT_DOUBLE_EQ(mean, gl) << "the accelerators agree";
            }
            gl = mean;
        } else {
            if (gl >= 0.0) {
                EXPECT_NEAR(mean, gl, 1e-6) << "the backends agree";
            }
        }
    }
}

// The path integrator packs its paths after the first round: a ray's coverage key is still its
// pixel's sample, so both backends make the same choices at every depth and give the same
// picture (a BLEND quad over a floor, seen obliquely, under a uniform sky); so do Whitted's
// reflected rays off a mirror floor.
TEST_F(AlphaCoverageGL, BlendPathsAndRayTreesAgreeOnBothBackends) {
    Scene scene = checkerScene(true);
    scene.background = glm::vec3(1.0f);
    Material& quad = scene.materials[1];
    quad.alphaMode = 2;  // GPURT_ALPHA_BLEND, alpha 0.5 times the checkerboard
    quad.alphaFactor = 0.5f;
    CameraSpec spec;
    spec.eye = {2.5f, 2.5f, 3.0f};
    spec.target = {0.0f, 0.3f, 0.0f};
    spec.fovy = 45.0f;
    constexpr int kSize = 40;
    for (const Variant& v : {kVariants[1], kVariants[4]}) {
        SCOPED_TRACE(v.name);
        const Variant cpu{v.accel, Backend::Cpu, v.kernel, "cpu"};
        const RenderOutput gl = render(scene, spec, kSize, v, Integrator::Path, 4);
        const RenderOutput reference = render(scene, spec, kSize, cpu, Integrator::Path, 4);
        expectSamePictures(gl, reference, v.name);
    }
    // Whitted's secondary rays: a mirror floor sees the quad's reflection through its holes.
    scene.materials[0].reflectivity = glm::vec3(0.6f);
    for (const Variant& v : {kVariants[1], kVariants[4]}) {
        SCOPED_TRACE(std::string(v.name) + " whitted");
        const Variant cpu{v.accel, Backend::Cpu, v.kernel, "cpu"};
        const RenderOutput gl = render(scene, spec, kSize, v, Integrator::Whitted, 4);
        const RenderOutput reference = render(scene, spec, kSize, cpu, Integrator::Whitted, 4);
        expectSamePictures(gl, reference, v.name);
        EXPECT_GT(reference.stats.secondaryRays, 0u);
    }
}

// Tiles (--tile): BLEND's choices depend on the image pixel, not on the stream element, so a
// tile's rows are exactly those rows of the whole image on both backends and integrators.
TEST_F(AlphaCoverageGL, BlendTilesAreTheirRowsOfTheWholeImage) {
    Scene scene = checkerScene(true);
    scene.background = glm::vec3(1.0f);
    scene.materials[1].alphaMode = 2;
    scene.materials[1].alphaFactor = 0.5f;
    CameraSpec spec;
    spec.eye = {2.5f, 2.5f, 3.0f};
    spec.target = {0.0f, 0.3f, 0.0f};
    spec.fovy = 45.0f;
    const int width = 20, height = 23;
    const UniformGrid grid = buildGrid(scene, GridOptions{});
    const CameraBasis whole = makeCamera(spec, width, height);
    for (Integrator integrator : {Integrator::Whitted, Integrator::Path}) {
        RenderSettings settings;
        settings.integrator = integrator;
        settings.samples = 3;
        CpuTracer cpu(scene, grid);
        GpuTracer gl(scene, grid);
        const RenderOutput fullCpu = cpu.render(whole, settings),
                           fullGl = gl.render(whole, settings);
        CameraBasis tile = whole;
        tile.rowBegin = 9;
        tile.rowCount = 7;
        for (bool onGl : {false, true}) {
            SCOPED_TRACE(std::string(onGl ? "gl" : "cpu") +
                         (integrator == Integrator::Path ? " path" : " whitted"));
            const RenderOutput& full = onGl ? fullGl : fullCpu;
            const RenderOutput part = onGl ? gl.render(tile, settings) : cpu.render(tile, settings);
            ASSERT_EQ(part.color.size(), size_t(width) * size_t(tile.rowCount));
            for (size_t k = 0; k < part.color.size(); ++k)
                ASSERT_EQ(part.color[k], full.color[size_t(tile.rowBegin) * size_t(width) + k])
                    << "element " << k;
        }
    }
}

// Only materials that triangles use turn the coverage test on (an MTL library's unused ones do not).
TEST(AlphaCoverage, OnlyMaterialsInUseCount) {
    Scene scene = emittingQuad(0.5f);  // material 0, BLEND, on both triangles
    EXPECT_TRUE(sceneUsesAlpha(scene));
    EXPECT_NE(AlphaCoverage::of(scene), nullptr);
    const uint32_t plain = addMaterial(scene, glm::vec3(0.5f));
    Material late;  // a second alpha material after an opaque one
    late.alphaMode = 1;
    scene.materials.push_back(late);
    scene.materialIds.assign(scene.triangles.size(), plain);
    EXPECT_FALSE(sceneUsesAlpha(scene));
    EXPECT_EQ(AlphaCoverage::of(scene), nullptr);
    scene.materialIds[1] = uint32_t(scene.materials.size() - 1);
    EXPECT_TRUE(sceneUsesAlpha(scene));
}

// MTL d 0.5 without map_d: BLEND coverage of one half.
TEST_F(AlphaCoverageGL, MtlDissolveIsBlendCoverage) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("gpurt-alpha-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "half.mtl") << "newmtl half\nKd 0 0 0\nKe 1 1 1\nd 0.5\n";
    std::ofstream(dir / "half.obj")
        << "mtllib half.mtl\nv -1 1 -1\nv 1 1 -1\nv 1 1 1\nv -1 1 1\nusemtl half\nf 1 2 3 4\n";
    Scene scene = loadObj(dir / "half.obj");
    std::filesystem::remove_all(dir);
    scene.background = glm::vec3(0.0f);
    ASSERT_EQ(scene.materials[scene.materialIds[0]].alphaMode, 2);
    constexpr int kSize = 32;
    constexpr uint32_t kSamples = 16;
    const double n = double(kSize * kSize) * kSamples;
    for (const Variant& v : {kVariants[1], kVariants[3]}) {
        SCOPED_TRACE(v.name);
        EXPECT_NEAR(meanCoverage(scene, v, kSamples, kSize), 0.5, 5.0 * std::sqrt(0.25 / n));
    }
}

}  // namespace
}  // namespace gpurt::test
