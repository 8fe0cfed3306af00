// Whole images: the GL kernel chain against the CPU backend (same grid, same algorithm) on the
// shared models, with oblique, close-up, inside-the-box and non-square cameras; every masking
// mode and traversal step count gives the same first hits.
#include "../common/GLTest.h"

#include "raytrace/camera/Camera.h"
#include "raytrace/render/CpuTracer.h"
#include "raytrace/render/GpuTracer.h"
#include "scene/ObjLoader.h"
#include "raytrace/accel/grid/UniformGrid.h"

#include <cmath>

namespace gpurt::test {
namespace {

class TraceImage : public GLTest {};

struct Agreement {
    double prim = 0, depth = 0, color = 0;
    size_t nans = 0;
};

Agreement compare(const RenderOutput& gl, const RenderOutput& cpu) {
    Agreement a;
    const size_t n = gl.prim.size();
    size_t prim = 0, depth = 0, color = 0;
    for (size_t i = 0; i < n; ++i) {
        prim += gl.prim[i] == cpu.prim[i];
        const float d0 = gl.depth[i], d1 = cpu.depth[i];
        depth += (std::isinf(d0) && std::isinf(d1)) || std::abs(d0 - d1) <= 1e-4f * std::abs(d1);
        const glm::vec3 diff = glm::abs(gl.color[i] - cpu.color[i]);
        color += std::max(diff.x, std::max(diff.y, diff.z)) <= 1e-3f;
        a.nans += std::isnan(d0) || std::isnan(gl.color[i].x) || std::isnan(gl.color[i].y) ||
                  std::isnan(gl.color[i].z) || std::isnan(gl.normal[i].x);
    }
    a.prim = double(prim) / double(n);
    a.depth = double(depth) / double(n);
    a.color = double(color) / double(n);
    return a;
}

struct Case {
    const char* model;
    glm::vec3 eye, target;
    float fovy;
    int width, height;
};

void renderBoth(const Case& c, RenderOutput& gl, RenderOutput& cpu, GpuTracerOptions options = {}) {
    const Scene scene = loadObj(std::string("../shared/models/") + c.model);
    const UniformGrid grid = buildGrid(scene, GridOptions{});
    CameraSpec spec;
    spec.eye = c.eye;
    spec.target = c.target;
    spec.fovy = c.fovy;
    const CameraBasis camera = makeCamera(spec, c.width, c.height);
    RenderSettings settings;
    settings.width = c.width;
    settings.height = c.height;
    GpuTracer tracer(scene, grid, options);
    gl = tracer.render(camera, settings);
    cpu = CpuTracer(scene, grid).render(camera, settings);
}

class TraceImageCases : public GLTest, public ::testing::WithParamInterface<Case> {};

TEST_P(TraceImageCases, GlMatchesCpuBackend) {
    RenderOutput gl, cpu;
    renderBoth(GetParam(), gl, cpu);
    const Agreement a = compare(gl, cpu);
    EXPECT_GE(a.prim, 0.999);
    EXPECT_GE(a.depth, 0.995);
    EXPECT_GE(a.color, 0.99);
    EXPECT_EQ(a.nans, 0u);
    EXPECT_EQ(gl.stats.primaryRays, cpu.stats.primaryRays);
    EXPECT_EQ(gl.stats.overflowRays, 0u);
}

INSTANTIATE_TEST_SUITE_P(
    Models, TraceImageCases,
    ::testing::Values(Case{"teapot.obj", {0, 0, 52.68f}, {0, 0, 0}, 45, 96, 96},
                      Case{"teapot.obj", {30, 25, 20}, {2, 1, 0}, 30, 120, 70},     // oblique, non-square
                      Case{"teapot.obj", {3, 2, 4}, {0, 0, 0}, 70, 64, 80},         // inside the box
                      Case{"cornell_box.obj", {278, 273, -800}, {278, 273, 0}, 39.3077f, 80, 80},
                      Case{"cornell_box.obj", {300, 250, 200}, {100, 300, 500}, 60, 90, 60},  // inside
                      Case{"bunny_lo.obj", {0, 4.83f, 16.97f}, {0, 4.83f, 0.04f}, 45, 100, 100},
                      Case{"bunny.obj", {0, 0, 3.43f}, {0, 0, 0}, 45, 128, 128},
                      Case{"bunny.obj", {0.3f, 0.2f, 0.9f}, {0, 0, 0}, 40, 96, 64}),  // close-up
    [](const ::testing::TestParamInfo<Case>& info) {
        std::string name = info.param.model;
        name = name.substr(0, name.find('.'));
        return name + "_" + std::to_string(info.index);
    });

TEST_F(TraceImage, EveryKernelMaskModeAndStepCountGivesTheSameHits) {
    const Case c{"bunny_lo.obj", {3, 6, 12}, {0, 4.8f, 0}, 45, 64, 48};
    RenderOutput reference, cpu;
    renderBoth(c, reference, cpu, GpuTracerOptions{MaskMode::EarlyExit, 1, 0.0f, TraceKernel::Split});
    EXPECT_EQ(reference.steps, cpu.steps);
    for (TraceKernel kernel : {TraceKernel::Split, TraceKernel::Fused})
        for (MaskMode mode : {MaskMode::EarlyZ, MaskMode::Stencil, MaskMode::EarlyExit})
            for (int steps : {0, 1, 3, 64}) {
                RenderOutput gl;
                renderBoth(c, gl, cpu, GpuTracerOptions{mode, steps, 0.0f, kernel});
                const std::string what = std::string(traceKernelName(kernel)) + " " + maskModeName(mode) + " " +
                                         std::to_string(steps);
                EXPECT_EQ(gl.prim, reference.prim) << what;
                EXPECT_EQ(gl.steps, reference.steps) << what;
                EXPECT_EQ(gl.color, reference.color) << what;
            }
}

}  // namespace
}  // namespace gpurt::test
