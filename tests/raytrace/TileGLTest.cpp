// Tiles (--tile I/N): the rows of tile i of n, rendered alone with the whole image's camera and
// samples, are exactly those rows of the whole render, for every output, on both backends and
// both integrators, for n that do and do not divide the height.
#include "../common/GLTest.h"
#include "TestScenes.h"

#include "image/InputError.h"
#include "raytrace/scene/SceneLoader.h"
#include "image/Tiles.h"

#include <cstdio>

namespace gpurt::test {
namespace {

class Tiles : public GLTest {};

// How many elements of the tile differ from rows [begin, begin + count) of the whole image's
// values, and the first of them ("" when none does).
template <typename T>
std::string differences(const std::vector<T>& tile, const std::vector<T>& whole, int width, int begin, int count) {
    if (tile.size() != size_t(width) * size_t(count)) return "tile of " + std::to_string(tile.size()) + " values";
    size_t n = 0, first = 0;
    for (size_t k = 0; k < tile.size(); ++k)
        if (!(tile[k] == whole[size_t(begin) * size_t(width) + k]) && n++ == 0) first = k;
    return n == 0 ? std::string() : std::to_string(n) + " differ, first at element " + std::to_string(first);
}

TEST_F(Tiles, EachTileIsItsRowsOfTheWholeRender) {
    const LoadedScene loaded = loadScene("scenes/cornell.json");
    const UniformGrid grid = buildGrid(loaded.scene, GridOptions{});
    const int width = 24, height = 37;
    const CameraBasis whole = makeCamera(*loaded.scene.camera, width, height);
    for (Integrator integrator : {Integrator::Whitted, Integrator::Path}) {
        RenderSettings settings;
        settings.integrator = integrator;
        settings.samples = 4;
        settings.maxBounces = integrator == Integrator::Path ? 5 : 6;
        CpuTracer cpu(loaded.scene, grid);
        GpuTracer gl(loaded.scene, grid);
        const RenderOutput fullCpu = cpu.render(whole, settings), fullGl = gl.render(whole, settings);
        for (int n : {1, 3, 7, 37}) {
            for (int i = 0; i < n; ++i) {
                CameraBasis tile = whole;
                tileRows(height, i, n, tile.rowBegin, tile.rowCount);
                SCOPED_TRACE("tile " + std::to_string(i) + "/" + std::to_string(n) +
                             (integrator == Integrator::Path ? ", path" : ", whitted"));
                for (bool onGl : {false, true}) {
                    const RenderOutput& full = onGl ? fullGl : fullCpu;
                    const RenderOutput part = onGl ? gl.render(tile, settings) : cpu.render(tile, settings);
                    ASSERT_EQ(part.width, width);
                    ASSERT_EQ(part.height, tile.rowCount);
                    const int b = tile.rowBegin, c = tile.rowCount;
                    const char* backend = onGl ? "gl" : "cpu";
                    EXPECT_EQ(differences(part.color, full.color, width, b, c), "") << backend << " color";
                    EXPECT_EQ(differences(part.depth, full.depth, width, b, c), "") << backend << " depth";
                    EXPECT_EQ(differences(part.prim, full.prim, width, b, c), "") << backend << " prim";
                    EXPECT_EQ(differences(part.normal, full.normal, width, b, c), "") << backend << " normal";
                    EXPECT_EQ(differences(part.steps, full.steps, width, b, c), "") << backend << " steps";
                }
            }
        }
    }
}

TEST(TileRows, TilesCoverTheImageInBalancedBands) {
    for (int height : {1, 7, 37, 512})
        for (int n = 1; n <= height && n <= 40; ++n) {
            int next = 0;
            for (int i = 0; i < n; ++i) {
                int begin = 0, count = 0;
                tileRows(height, i, n, begin, count);
                EXPECT_EQ(begin, next);
                EXPECT_GE(count, height / n);
                EXPECT_LE(count, height / n + 1);
                next = begin + count;
            }
            EXPECT_EQ(next, height);
        }
}

// Frame file names (--frames): the number as printf's %0Nd and %d would write it (checked against
// snprintf), %% a percent sign, anything else with a '%' refused.
TEST(FramePatterns, NameEachFrameAsPrintfWould) {
    char expected[64];
    for (int frame : {0, 7, 42, 12345, 999999}) {
        std::snprintf(expected, sizeof expected, "out/f%04d.png", frame);
        EXPECT_EQ(frameFileName("out/f%04d.png", frame), expected);
        std::snprintf(expected, sizeof expected, "%d_100%%.pfm", frame);
        EXPECT_EQ(frameFileName("%d_100%%.pfm", frame), expected);
        std::snprintf(expected, sizeof expected, "a%%b%09d", frame);
        EXPECT_EQ(frameFileName("a%%b%09d", frame), expected);
    }
    for (const char* bad : {"f.png", "f%04d_%04d.png", "f%s.png", "f%5d.png", "f%0d.png", "f%.png", "100%", "%%d"}) {
        try {
            checkFramePattern("-o", bad);
            ADD_FAILURE() << bad << " accepted";
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()).rfind(std::string("-o: '") + bad + "'", 0), 0u) << e.what();
        }
    }
    int first = 0, last = 0;
    parseFrames("3:17", first, last);
    EXPECT_EQ(first, 3);
    EXPECT_EQ(last, 17);
    for (const char* bad : {"3", "5:4", "-1:2", "a:b", "1:", ":2", "0:1000000", "1.5:2"})
        EXPECT_THROW(parseFrames(bad, first, last), InputError) << bad;
}

}  // namespace
}  // namespace gpurt::test
