// The GL tracer's per-ray cell limit (RAY_OVERFLOW): no ray of a real scene reaches it, and rays
// that do (the limit lowered for the test) are counted in RenderStats::overflowRays and end as
// misses, on the fused and the split kernels alike.
#include "../common/GLTest.h"

#include "raytrace/camera/Camera.h"
#include "raytrace/render/CpuTracer.h"
#include "raytrace/render/GpuTracer.h"
#include "scene/ObjLoader.h"
#include "raytrace/accel/grid/UniformGrid.h"

namespace gpurt::test {
namespace {

class TraceLimits : public GLTest {};

TEST_F(TraceLimits, RaysStoppedByTheCellLimitAreCountedAsOverflow) {
    const Scene scene = loadObj("../shared/models/bunny_lo.obj");
    const UniformGrid grid = buildGrid(scene, GridOptions{});
    const CameraBasis camera = makeCamera({{3, 6, 12}, {0, 4.8f, 0}, {0, 1, 0}, 45.0f}, 64, 48);
    RenderSettings settings;
    settings.maxBounces = 0;
    // The CPU backend's cell counts: a ray that needs more cells than the limit overflows. The
    // count is of rays whose cell count reached the limit, which includes those that end in
    // exactly the last cell allowed (with the grid's own limit, no ray can).
    const RenderOutput cpu = CpuTracer(scene, grid).render(camera, settings);
    const int limit = 4;
    size_t expected = 0;
    for (float steps : cpu.steps) expected += steps >= float(limit);
    ASSERT_GT(expected, cpu.steps.size() / 10);
    ASSERT_LT(expected, cpu.steps.size());
    for (TraceKernel kernel : {TraceKernel::Fused, TraceKernel::Split}) {
        SCOPED_TRACE(traceKernelName(kernel));
        GpuTracerOptions options;
        options.kernel = kernel;
        EXPECT_EQ(GpuTracer(scene, grid, options).render(camera, settings).stats.overflowRays, 0u);
        options.maxCellSteps = limit;
        const RenderOutput gl = GpuTracer(scene, grid, options).render(camera, settings);
        EXPECT_EQ(gl.stats.overflowRays, expected);
        for (size_t i = 0; i < gl.prim.size(); ++i) {
            if (cpu.steps[i] > float(limit))
                EXPECT_EQ(gl.prim[i], -1.0f) << "pixel " << i << " went on past the limit";
            else
                EXPECT_EQ(gl.prim[i], cpu.prim[i]) << "pixel " << i;
        }
    }
}

}  // namespace
}  // namespace gpurt::test
