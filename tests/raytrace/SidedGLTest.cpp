// Back-face culling (glTF doubleSided false) on both backends and both accelerators: a horizontal
// quad y = 1, x and z in [-1, 1], its front up (counter-clockwise seen from above), with a
// backdrop behind it as the camera sees it. Where a pixel's centre ray meets the quad (computed
// here in double: the contract's camera, written out), a single-sided quad seen from its front
// and a double-sided one from either side are hit; a single-sided one seen from behind is not:
// the ray goes on to the backdrop, exactly as if the quad were not there. Shadow rays likewise, by
// the direction they are traced in (surface to light): a single-sided quad between a point light
// and a floor shadows the floor only when the floor sees its front. A transmissive (glass) single-sided quad is never culled.
#include "../common/GLTest.h"
#include "TestScenes.h"

#include "raytrace/materials/AlphaCoverage.h"
#include "raytrace/render/Renderer.h"
#include "raytrace/accel/Acceleration.h"

#include <cmath>
#include <string>

namespace gpurt::test {
namespace {

class BackFaceCullingGL : public GLTest {};

constexpr double kQuadHeight = 1.0;
const glm::vec3 kBackground(0.2f, 0.5f, 0.9f);

// The quad (triangles 0 and 1), its front up (facing +y) or down, of material `quad`.
void addQuad(Scene& scene, bool frontUp, uint32_t quad) {
    const float y = float(kQuadHeight);
    if (frontUp)  // cross(e1, e2) = (0, 4, 0)
        addPolygon(scene, {{-1, y, -1}, {-1, y, 1}, {1, y, 1}, {1, y, -1}}, quad);
    else
        addPolygon(scene, {{-1, y, -1}, {1, y, -1}, {1, y, 1}, {-1, y, 1}}, quad);
}

// The quad, front up, of a single-sided (or double-sided) material (glass with `ior` > 0), and a
// double-sided backdrop at y = backdropY (x and z in [-3, 3]; triangles 2 and 3), without the quad
// when `withQuad` is false (the backdrop is then triangles 0 and 1).
Scene quadScene(bool doubleSided, float backdropY, bool withQuad = true, float ior = 0.0f) {
    Scene scene;
    scene.background = kBackground;
    const uint32_t quad = addMaterial(scene, glm::vec3(0.8f, 0.3f, 0.2f), glm::vec3(0.0f), ior);
    scene.materials[quad].doubleSided = doubleSided;
    const uint32_t grey = addMaterial(scene, glm::vec3(0.7f), glm::vec3(0.3f));  // emits: visible without lights
    if (withQuad) addQuad(scene, true, quad);
    const float b = backdropY;
    addPolygon(scene, {{-3, b, -3}, {-3, b, 3}, {3, b, 3}, {3, b, -3}}, grey);
    return scene;
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

// Whether (x, z) lies inside the quad more than `margin` from its edges (`clear`), or outside
// it by more than `margin`; false for both near the edges (no expectation there).
bool insideQuad(double x, double z, double margin, bool& clear) {
    const double edge = std::max(std::abs(x), std::abs(z));
    clear = std::abs(edge - 1.0) > margin;
    return edge < 1.0;
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
                    Integrator integrator = Integrator::Whitted) {
    const CameraBasis camera = makeCamera(spec, size, size);
    const Acceleration accel = chooseAcceleration(scene, v.accel, nullptr, {}, camera);
    RenderSettings settings;
    settings.width = settings.height = size;
    settings.samples = 1;
    settings.integrator = integrator;
    settings.maxBounces = 3;
    GpuTracerOptions options;
    options.kernel = v.kernel;
    return makeRenderer(RendererConfig{v.backend, integrator, options}, scene, accel)->render(camera, settings);
}

// A camera above the quad (fromAbove: it sees the quad's front) or below it (its back), looking
// at it; the backdrop is behind the quad as this camera sees it.
CameraSpec viewOf(bool fromAbove) {
    CameraSpec spec;
    spec.eye = {0.05f, fromAbove ? 4.0f : -2.0f, 0.03f};
    spec.target = {0.0f, 1.0f, 0.0f};
    spec.up = {0.0f, 0.0f, -1.0f};
    spec.fovy = 60.0f;
    return spec;
}
float backdropFor(bool fromAbove) { return fromAbove ? -1.0f : 2.5f; }

// Per pixel whose centre ray crosses the quad clear of its edges: the quad's triangles (0, 1)
// where `seen`, else the backdrop's (2, 3) with the colour of the render without the quad
// (Whitted). Returns the pixels checked.
size_t expectQuadSeen(const Scene& scene, const Scene& withoutQuad, bool fromAbove, bool seen, const Variant& v,
                      Integrator integrator) {
    constexpr int kSize = 40;
    const CameraSpec spec = viewOf(fromAbove);
    const RenderOutput out = render(scene, spec, kSize, v, integrator);
    const RenderOutput bare = render(withoutQuad, spec, kSize, v, integrator);
    size_t checked = 0;
    for (int j = 0; j < kSize; ++j)
        for (int i = 0; i < kSize; ++i) {
            const glm::dvec3 d = centreRay(spec, kSize, i, j);
            const double t = (kQuadHeight - double(spec.eye.y)) / d.y;
            bool clear = false;
            const bool inside = insideQuad(double(spec.eye.x) + t * d.x, double(spec.eye.z) + t * d.z, 0.02, clear);
            if (!clear || !inside) continue;
            const size_t at = size_t(j) * kSize + size_t(i);
            if (seen) {
                EXPECT_TRUE(out.prim[at] == 0.0f || out.prim[at] == 1.0f) << "pixel " << i << ", " << j << ": " << out.prim[at];
            } else {
                EXPECT_TRUE(out.prim[at] == 2.0f || out.prim[at] == 3.0f) << "pixel " << i << ", " << j << ": " << out.prim[at];
                if (integrator == Integrator::Whitted) {
                    for (int c = 0; c < 3; ++c)
                        EXPECT_NEAR(out.color[at][c], bare.color[at][c], 1e-6f + 1e-6f * bare.color[at][c])
                            << "pixel " << i << ", " << j;
                }
            }
            if (testing::Test::HasFailure()) return checked;
            ++checked;
        }
    return checked;
}

TEST_F(BackFaceCullingGL, SingleSidedQuadIsInvisibleFromBehind) {
    for (const Variant& v : kVariants)
        for (Integrator integrator : {Integrator::Whitted, Integrator::Path})
            for (bool fromAbove : {true, false})
                for (bool doubleSided : {false, true}) {
                    SCOPED_TRACE(std::string(v.name) + (integrator == Integrator::Path ? " path" : " whitted") +
                                 (fromAbove ? ", front" : ", back") + (doubleSided ? ", double-sided" : ", single-sided"));
                    const float b = backdropFor(fromAbove);
                    const bool seen = fromAbove || doubleSided;
                    EXPECT_GT(expectQuadSeen(quadScene(doubleSided, b), quadScene(doubleSided, b, false), fromAbove, seen, v,
                                             integrator),
                              400u);
                    if (HasFailure()) return;
                }
}

// Glass (ior > 0, as glTF KHR_materials_transmission loads) is never culled: rays inside a solid
// meet its back faces.
TEST_F(BackFaceCullingGL, TransmissiveSingleSidedQuadIsNotCulled) {
    for (const Variant& v : kVariants)
        for (Integrator integrator : {Integrator::Whitted, Integrator::Path}) {
            SCOPED_TRACE(std::string(v.name) + (integrator == Integrator::Path ? " path" : " whitted"));
            const Scene glass = quadScene(false, backdropFor(false), true, 1.5f);
            EXPECT_FALSE(glass.materials[0].cullsBackFaces());
            EXPECT_GT(expectQuadSeen(glass, quadScene(false, backdropFor(false), false), false, true, v, integrator), 400u);
            if (HasFailure()) return;
        }
}

// A floor (y = 0) under the quad, a point light high above, the camera between them looking
// down. Shadow rays are culled as every other ray is, by the direction they are traced in: from
// the floor point p up to the light. So the floor is in the quad's shadow where that ray crosses
// the quad (at p (1 - 1 / 50)) and meets its front, i.e. with the quad's front down (facing the
// floor, the light seeing its back); with the quad's front up the shadow ray meets its back and
// the floor is as lit as without the quad. (The path integrator's bounce rays from the floor
// see the quad the same way, so its next-event estimation and its bounces agree.) Expectations:
// the renders with a double-sided quad (dark) and without a quad (lit).
TEST_F(BackFaceCullingGL, SingleSidedQuadShadowsOnlyWhereShadowRaysMeetItsFront) {
    auto floorScene = [](int quad) {  // quad: 0 none, 1 single-sided front up, 2 front down, 3 double-sided
        Scene scene;
        scene.background = kBackground;
        const uint32_t grey = addMaterial(scene, glm::vec3(0.7f));
        addPolygon(scene, {{-3, 0, -3}, {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}}, grey);
        const uint32_t q = addMaterial(scene, glm::vec3(0.8f, 0.3f, 0.2f));
        scene.materials[q].doubleSided = quad == 3;
        if (quad > 0) addQuad(scene, quad != 2, q);
        scene.lights.push_back({glm::vec3(0.0f, 50.0f, 0.0f), glm::vec3(1.0f), 2500.0f});
        return scene;
    };
    CameraSpec spec;
    spec.eye = {0.02f, 0.9f, 0.01f};  // sees the floor out to |x|, |z| = 1.5: in and out of the shadow
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.up = {0.0f, 0.0f, -1.0f};
    spec.fovy = 120.0f;
    constexpr int kSize = 40;
    for (const Variant& v : kVariants) {
        SCOPED_TRACE(v.name);
        const RenderOutput lit = render(floorScene(0), spec, kSize, v);
        const RenderOutput dark = render(floorScene(3), spec, kSize, v);
        const RenderOutput frontUp = render(floorScene(1), spec, kSize, v);
        const RenderOutput frontDown = render(floorScene(2), spec, kSize, v);
        size_t shadowed = 0, open = 0;
        for (int j = 0; j < kSize; ++j)
            for (int i = 0; i < kSize; ++i) {
                const glm::dvec3 d = centreRay(spec, kSize, i, j);
                const glm::dvec3 p = glm::dvec3(spec.eye) + (-double(spec.eye.y) / d.y) * d;  // on the floor
                const double f = kQuadHeight / 50.0;
                bool clear = false;
                const bool blocked = insideQuad(p.x * (1.0 - f), p.z * (1.0 - f), 0.02, clear);
                if (!clear) continue;
                const size_t at = size_t(j) * kSize + size_t(i);
                ASSERT_TRUE(frontDown.prim[at] == 0.0f || frontDown.prim[at] == 1.0f) << "the floor, pixel " << i << ", " << j;
                if (blocked) {
                    ASSERT_GT(lit.color[at].x, dark.color[at].x * 1.5f) << "pixel " << i << ", " << j;
                }
                const glm::vec3 down = blocked ? dark.color[at] : lit.color[at];
                for (int c = 0; c < 3; ++c) {
                    ASSERT_NEAR(frontDown.color[at][c], down[c], 1e-5f + 1e-5f * down[c])
                        << (blocked ? "shadow" : "lit") << " at pixel " << i << ", " << j;
                    ASSERT_NEAR(frontUp.color[at][c], lit.color[at][c], 1e-5f + 1e-5f * lit.color[at][c])
                        << "lit through the quad's back at pixel " << i << ", " << j;
                }
                ++(blocked ? shadowed : open);
            }
        EXPECT_GT(shadowed, 300u);
        EXPECT_GT(open, 100u);
    }
}

// Only materials that triangles use count, and glass never culls.
TEST(BackFaceCulling, OnlyMaterialsInUseCullAndGlassNever) {
    Scene scene = quadScene(true, 2.0f);
    EXPECT_FALSE(sceneCullsBackFaces(scene)) << "double-sided";
    EXPECT_EQ(AlphaCoverage::of(scene), nullptr);
    scene.materials[0].doubleSided = false;
    EXPECT_TRUE(sceneCullsBackFaces(scene));
    EXPECT_FALSE(sceneUsesAlpha(scene));
    EXPECT_NE(AlphaCoverage::of(scene), nullptr);
    scene.materials[0].ior = 1.5f;  // glass
    EXPECT_FALSE(sceneCullsBackFaces(scene));
    scene.materials[0].ior = 0.0f;
    scene.materialIds.assign(scene.triangles.size(), 1);  // the single-sided material unused
    EXPECT_FALSE(sceneCullsBackFaces(scene));
}

}  // namespace
}  // namespace gpurt::test
