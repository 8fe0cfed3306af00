// The BVH on the gl backend: the same hits and pictures as the cpu backend over the same tree,
// the same images as the grid on each backend (the same hits: identical, Whitted and path, whole
// and in tiles, masked or not), and the node limit reported as the grid's cell limit is.
#include "../common/GLTest.h"
#include "TestScenes.h"

#include "raytrace/render/Renderer.h"
#include "raytrace/scene/SceneLoader.h"
#include "scene/ObjLoader.h"

#include <cmath>

namespace gpurt::test {
namespace {

class BvhGL : public GLTest {};

struct View {
    LoadedScene loaded;
    CameraBasis camera;
};

View view(const std::string& path, int width, int height) {
    View v{loadScene(path), {}};
    const Scene& scene = v.loaded.scene;
    v.camera = makeCamera(scene.camera ? *scene.camera : defaultCamera(scene.bounds(), width, height), width, height);
    return v;
}

Acceleration accelerate(const View& v, const char* choice) {
    return chooseAcceleration(v.loaded.scene, choice, nullptr, {}, v.camera);
}

RenderOutput render(const View& v, const Acceleration& accel, Backend backend, Integrator integrator, uint32_t samples,
                    GpuTracerOptions options = {}, const CameraBasis* camera = nullptr) {
    RenderSettings settings;
    settings.width = v.camera.width;
    settings.height = v.camera.height;
    settings.samples = samples;
    settings.integrator = integrator;
    settings.maxBounces = integrator == Integrator::Path ? kDefaultPathBounces : 3;
    return makeRenderer(RendererConfig{backend, integrator, options}, v.loaded.scene, accel)
        ->render(camera ? *camera : v.camera, settings);
}

size_t samePrims(const RenderOutput& a, const RenderOutput& b) {
    size_t same = 0;
    for (size_t i = 0; i < a.prim.size(); ++i) same += a.prim[i] == b.prim[i];
    return same;
}

TEST_F(BvhGL, BothBackendsFindTheSameHitsAndPictures) {
    for (const char* path : {"scenes/room.json", "scenes/highlow.json", "scenes/cornell_blocks.json",
                             "../shared/models/bunny_lo.obj"}) {
        const View v = view(path, 96, 96);
        const Acceleration bvh = accelerate(v, "bvh");
        const RenderOutput gl = render(v, bvh, Backend::Gl, Integrator::Whitted, 1);
        const RenderOutput cpu = render(v, bvh, Backend::Cpu, Integrator::Whitted, 1);
        // As the grid's backends: equal but where the kernels' float rounding differs from C++'s
        // on a ray through an edge.
        EXPECT_GE(double(samePrims(gl, cpu)) / double(gl.prim.size()), 0.999) << path;
        EXPECT_EQ(gl.stats.overflowRays, 0u) << path;
        // The shadow rays within expectSamePictures's 0.1%, not equal: the kernels' t differs from
        // C++'s in the last bits on about a tenth of the pixels (with Moller-Trumbore as with the
        // watertight test: room.json at 96x96, 885 and 855 of 9216 depths), so a shadow ray whose
        // light lies almost in the surface's plane can exist on one backend only (cornell_blocks:
        // 6051 and 6052 with the watertight test).
        expectSamePictures(gl, cpu, path);
    }
}

TEST_F(BvhGL, EitherAcceleratorGivesTheSameImageOnEachBackend) {
    const View v = view("scenes/cornell_blocks.json", 64, 64);
    const Acceleration grid = accelerate(v, "grid");
    const Acceleration bvh = accelerate(v, "bvh");
    for (Backend backend : {Backend::Gl, Backend::Cpu})
        for (Integrator integrator : {Integrator::Whitted, Integrator::Path}) {
            const uint32_t samples = integrator == Integrator::Path ? 3 : 1;
            const RenderOutput a = render(v, grid, backend, integrator, samples);
            const RenderOutput b = render(v, bvh, backend, integrator, samples);
            const char* what = backend == Backend::Gl ? "gl" : "cpu";
            EXPECT_EQ(samePrims(a, b), a.prim.size()) << what;
            EXPECT_EQ(a.depth, b.depth) << what;
            EXPECT_EQ(a.color, b.color) << what << (integrator == Integrator::Path ? " path" : " whitted");
            EXPECT_EQ(a.stats.shadowRays, b.stats.shadowRays) << what;
        }
    // The path integrator's masked rounds trace under the live paths' mask: the same image.
    GpuTracerOptions masked;
    masked.maskPaths = true;
    EXPECT_EQ(render(v, bvh, Backend::Gl, Integrator::Path, 3, masked).color,
              render(v, bvh, Backend::Gl, Integrator::Path, 3).color);
}

TEST_F(BvhGL, EachTileIsItsRowsOfTheWholeRender) {
    const View v = view("scenes/room.json", 48, 40);
    const Acceleration bvh = accelerate(v, "bvh");
    const RenderOutput whole = render(v, bvh, Backend::Gl, Integrator::Path, 2);
    int row = 0;
    for (int i = 0; i < 3; ++i) {
        CameraBasis tile = v.camera;
        tileRows(v.camera.height, i, 3, tile.rowBegin, tile.rowCount);
        const RenderOutput part = render(v, bvh, Backend::Gl, Integrator::Path, 2, {}, &tile);
        ASSERT_EQ(part.color.size(), size_t(tile.rowCount) * size_t(v.camera.width));
        for (size_t k = 0; k < part.color.size(); ++k)
            EXPECT_EQ(part.color[k], whole.color[size_t(row) * size_t(v.camera.width) + k]) << "tile " << i;
        row += tile.rowCount;
    }
    EXPECT_EQ(row, v.camera.height);
}

TEST_F(BvhGL, RaysPastTheNodeLimitAreCountedAsOverflow) {
    const View v = view("../shared/models/bunny_lo.obj", 48, 48);
    const Acceleration bvh = accelerate(v, "bvh");
    // The cpu backend's node counts say how many primary rays reach 4 visits (as for the grid's
    // cells, the count includes rays that end at the last visit allowed).
    const RenderOutput cpu = render(v, bvh, Backend::Cpu, Integrator::Whitted, 1);
    uint64_t expected = 0;
    for (float steps : cpu.steps) expected += steps >= 4.0f;
    ASSERT_GT(expected, 0u);
    ASSERT_LT(expected, cpu.steps.size());
    GpuTracerOptions limited;
    limited.maxCellSteps = 4;
    RenderSettings settings;
    settings.width = settings.height = 48;
    settings.maxBounces = 0;
    const RenderOutput gl = makeRenderer(RendererConfig{Backend::Gl, Integrator::Whitted, limited}, v.loaded.scene, bvh)
                                ->render(v.camera, settings);
    EXPECT_EQ(gl.stats.overflowRays, expected);
    for (size_t i = 0; i < gl.prim.size(); ++i)
        if (cpu.steps[i] > 4.0f) {
            EXPECT_EQ(gl.prim[i], -1.0f) << "pixel " << i << " went on past the limit";
        }
}

}  // namespace
}  // namespace gpurt::test
