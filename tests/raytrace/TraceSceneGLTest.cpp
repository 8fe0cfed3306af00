// The shipped demo scenes: the GL chain against the CPU backend, and golden images for scenes A
// and B (tests/golden/, rendered by `gpurt render scenes/NAME.json`; tolerance below). On a
// golden mismatch the actual image and a diff image are written next to the build's tests.
#include "../common/GLTest.h"

#include "raytrace/camera/Camera.h"
#include "raytrace/render/CpuTracer.h"
#include "raytrace/render/GpuTracer.h"
#include "image/ImageIO.h"
#include "raytrace/scene/SceneLoader.h"
#include "raytrace/accel/grid/UniformGrid.h"

#include <png.h>

#include <cmath>
#include <filesystem>

namespace gpurt::test {
namespace {

struct SceneRender {
    RenderOutput gl, cpu;
};

SceneRender renderScene(const std::string& name) {
    const LoadedScene loaded = loadScene("scenes/" + name + ".json");
    const glm::ivec2 size = loaded.size.value_or(glm::ivec2(256, 256));
    const CameraBasis camera = makeCamera(*loaded.scene.camera, size.x, size.y);
    const UniformGrid grid = buildGrid(loaded.scene, GridOptions{});
    RenderSettings settings;
    settings.width = size.x;
    settings.height = size.y;
    settings.maxBounces = loaded.scene.maxBounces;
    SceneRender r;
    r.gl = GpuTracer(loaded.scene, grid).render(camera, settings);
    r.cpu = CpuTracer(loaded.scene, grid).render(camera, settings);
    return r;
}

std::vector<unsigned char> readPngRgb(const std::string& path, int& w, int& h) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&image, path.c_str())) return {};
    image.format = PNG_FORMAT_RGB;
    std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(image));
    if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr)) return {};
    w = int(image.width);
    h = int(image.height);
    return pixels;
}

class TraceScenes : public GLTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(TraceScenes, GlMatchesCpuBackend) {
    const SceneRender r = renderScene(GetParam());
    size_t prim = 0, color = 0, nans = 0;
    for (size_t i = 0; i < r.gl.prim.size(); ++i) {
        prim += r.gl.prim[i] == r.cpu.prim[i];
        const glm::vec3 d = glm::abs(r.gl.color[i] - r.cpu.color[i]);
        color += std::max(d.x, std::max(d.y, d.z)) <= 2e-3f;
        nans += std::isnan(r.gl.color[i].x + r.gl.color[i].y + r.gl.color[i].z + r.gl.depth[i]);
    }
    const double n = double(r.gl.prim.size());
    EXPECT_GE(double(prim) / n, 0.999);
    EXPECT_GE(double(color) / n, 0.99);
    EXPECT_EQ(nans, 0u);
    EXPECT_EQ(r.gl.stats.shadowRays, r.cpu.stats.shadowRays);
    EXPECT_GT(r.gl.stats.secondaryRays, 0u);  // every demo scene has mirrors
}

INSTANTIATE_TEST_SUITE_P(Demo, TraceScenes, ::testing::Values("boxes", "room", "highlow"));

// Golden images: 8-bit sRGB PNGs; a pixel matches when every channel is within 2 levels, and
// 99.5% of pixels must match (float differences between drivers move a few edge pixels).
class GoldenImages : public GLTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(GoldenImages, GlRenderMatchesGolden) {
    const std::string name = GetParam();
    const SceneRender r = renderScene(name);
    int w = 0, h = 0;
    const auto golden = readPngRgb("tests/golden/" + name + ".png", w, h);
    ASSERT_FALSE(golden.empty()) << "tests/golden/" << name << ".png is missing or unreadable";
    ASSERT_EQ(w, r.gl.width);
    ASSERT_EQ(h, r.gl.height);
    // Both backends against the same golden (it was rendered by the GL backend).
    for (const RenderOutput* out : {&r.gl, &r.cpu}) {
        const std::string backend = out == &r.gl ? "gl" : "cpu";
        size_t matching = 0;
        std::vector<glm::vec3> diff(out->color.size());
        for (size_t i = 0; i < out->color.size(); ++i) {
            int worst = 0;
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, std::abs(int(linearToSrgb8(out->color[i][c])) - int(golden[i * 3 + size_t(c)])));
            matching += worst <= 2;
            diff[i] = glm::vec3(worst > 2 ? 1.0f : 0.0f, std::min(1.0f, float(worst) / 16.0f), 0.0f);
        }
        const double fraction = double(matching) / double(out->color.size());
        const std::string stem = "golden-" + name + "-" + backend;
        if (fraction < 0.995) {
            writePng(stem + "-actual.png", out->width, out->height, out->color);
            writePng(stem + "-diff.png", out->width, out->height, diff);
        }
        EXPECT_GE(fraction, 0.995) << backend << ": see " << stem << "-actual.png and -diff.png in "
                                   << std::filesystem::current_path();
    }
}

INSTANTIATE_TEST_SUITE_P(SceneAB, GoldenImages, ::testing::Values("boxes", "room"));

}  // namespace
}  // namespace gpurt::test
