// The environment light through the program (CONTRACT.md, "Environment light and the default
// light"): --env with hostile maps (truncated .hdr and .exr, zero-size and huge maps, NaN and
// infinite texels: refused with exit 1 and one line naming the file; negative texels: clamped to
// 0, channels above 1e30 to 1e30, with a warning), a missing file, the JSON scene's "environment", --env-rotate and
// --env-strength, and the default light: every model without a light of its own comes out well
// exposed under both integrators (over the object's pixels, the mean of each pixel's largest PNG
// channel in 0.25..0.75, under 2% with a channel at 255), and --env none turns it off.
#include "CliRunner.h"
#include "PngPixels.h"
#include "../raytrace/EnvironmentTestMaps.h"

#include "image/ImageIO.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>

namespace gpurt::test {
namespace {

const std::string kTriangle = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n";

class EnvironmentMaps : public GpurtTest {
  protected:
    std::string render(const std::string& map, const std::string& options = "") const {
        return "render " + quoted("tri.obj") + " -o " + quoted("out.png") + " --size 16x16 --env " + quoted(map) + " " +
               options;
    }
    void SetUp() override {
        GpurtTest::SetUp();
        write("tri.obj", kTriangle);
    }
    // A small valid map file NAME (its extension chooses the format).
    void writeMap(const std::string& name, const EnvironmentImage& image) const {
        if (name.size() > 4 && name.substr(name.size() - 4) == ".exr") writeExrMap(dir / name, image);
        else writeHdr(dir / name, image);
    }
    EnvironmentImage sky() const {
        return makeMap(32, 16, [](glm::vec3 d) { return glm::vec3(0.5f + 0.4f * d.y, 0.5f, 0.3f); });
    }
    // The first `keep` bytes of the valid map NAME as BROKEN.
    void truncate(const std::string& name, const std::string& broken, size_t keep) const {
        const std::string bytes = readFile(dir / name);
        ASSERT_GT(bytes.size(), keep);
        write(broken, bytes.substr(0, keep));
        std::filesystem::remove(dir / name);
    }
};

TEST_F(EnvironmentMaps, ValidMapsRender) {
    for (const char* name : {"sky.hdr", "sky.exr"}) {
        writeMap(name, sky());
        const GpurtRun run = gpurt(render(name));
        EXPECT_EQ(run.code, 0) << name << ": " << run.err;
        EXPECT_TRUE(run.err.empty()) << run.err;
    }
}

TEST_F(EnvironmentMaps, MissingFileIsRefusedByName) {
    expectRefused(render("nosuch.hdr"), {path("nosuch.hdr"), "no such file"});
    expectRefused(render("nosuch.exr"), {path("nosuch.exr")});
}

TEST_F(EnvironmentMaps, OtherFormatsAreRefused) {
    write("sky.png", "not a map");
    expectRefused(render("sky.png"), {path("sky.png"), ".hdr or .exr"});
    write("garbage.hdr", "garbage, not a Radiance file");
    expectRefused(render("garbage.hdr"), {path("garbage.hdr"), "Radiance"});
    write("garbage.exr", "garbage, not an EXR file");
    expectRefused(render("garbage.exr"), {path("garbage.exr"), "EXR"});
}

TEST_F(EnvironmentMaps, TruncatedFilesAreRefused) {
    writeMap("whole.hdr", sky());
    truncate("whole.hdr", "cut.hdr", readFile(dir / "whole.hdr").size() / 2);
    expectRefused(render("cut.hdr"), {path("cut.hdr")});
    writeMap("whole.hdr", sky());
    truncate("whole.hdr", "header.hdr", 20);  // inside the header
    expectRefused(render("header.hdr"), {path("header.hdr")});
    writeMap("whole.exr", sky());
    truncate("whole.exr", "cut.exr", readFile(dir / "whole.exr").size() / 2);
    expectRefused(render("cut.exr"), {path("cut.exr"), "EXR"});
    writeMap("whole.exr", sky());
    truncate("whole.exr", "header.exr", 40);
    expectRefused(render("header.exr"), {path("header.exr"), "EXR"});
}

TEST_F(EnvironmentMaps, ZeroSizeAndHugeMapsAreRefused) {
    write("zero.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 0\n");
    expectRefused(render("zero.hdr"), {path("zero.hdr")});
    write("wide.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 100000\n" + std::string(64, '\x01'));
    expectRefused(render("wide.hdr"), {path("wide.hdr")});
    // Within stb's limits but beyond gpurt's (16384 x 8192), and with no pixels: refused by size first.
    write("tall.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16000 +X 16000\n" + std::string(64, '\x01'));
    expectRefused(render("tall.hdr"), {path("tall.hdr"), "16000x16000"});
}

TEST_F(EnvironmentMaps, NonFiniteTexelsAreRefusedAndNegativeOnesClamped) {
    for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        EnvironmentImage image = sky();
        image.texels[5 * 32 + 7].y = bad;
        writeMap("bad.exr", image);
        expectRefused(render("bad.exr"), {path("bad.exr"), "(7, 5)", std::isnan(bad) ? "NaN" : "infinite"});
        std::filesystem::remove(dir / "bad.exr");
    }
    EnvironmentImage image = sky();
    image.texels[3].x = -2.0f;
    writeMap("negative.exr", image);
    const GpurtRun run = gpurt(render("negative.exr", "--aov color=" + quoted("c.pfm")));
    EXPECT_EQ(run.code, 0) << run.err;
    EXPECT_NE(run.err.find("negative"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find(path("negative.exr")), std::string::npos) << run.err;
    // RGBE reaches 1.7e38; above 1e30 a channel is clamped (the map's sums stay finite).
    image = sky();
    image.texels[9].z = 1e35f;
    writeMap("huge.exr", image);
    const GpurtRun huge = gpurt(render("huge.exr"));
    EXPECT_EQ(huge.code, 0) << huge.err;
    EXPECT_NE(huge.err.find("above 1e30"), std::string::npos) << huge.err;
}

TEST_F(EnvironmentMaps, BadOptionsAreRefused) {
    writeMap("sky.hdr", sky());
    expectRefused(render("sky.hdr", "--env-strength -1"), {"--env-strength"});
    expectRefused(render("sky.hdr", "--env-strength nan"), {"--env-strength"});
    expectRefused(render("sky.hdr", "--env-rotate abc"), {"--env-rotate"});
    expectRefused(render("sky.hdr", "--env-sampling some"), {"--env-sampling"});
}

// The JSON scene's environment: read relative to the scene's folder; a missing file is named by
// its JSON pointer; the unlit triangle under it shows the environment's light, twice as bright
// at strength 2.
TEST_F(EnvironmentMaps, JsonSceneEnvironment) {
    writeMap("sky.hdr", makeMap(32, 16, [](glm::vec3) { return glm::vec3(0.25f); }));
    auto scene = [&](const std::string& env) {
        return "{\"meshes\": [{\"file\": \"tri.obj\"}], \"environment\": " + env +
               ", \"camera\": {\"eye\": [0, 0, 3], \"target\": [0, 0, 0], \"fovy\": 30}}";
    };
    write("one.json", scene("{\"file\": \"sky.hdr\"}"));
    write("two.json", scene("{\"file\": \"sky.hdr\", \"strength\": 2, \"rotation\": 45}"));
    write("missing.json", scene("{\"file\": \"nosuch.hdr\"}"));
    write("unknown.json", scene("{\"file\": \"sky.hdr\", \"brightness\": 2}"));
    expectRefused("render " + quoted("missing.json") + " -o " + quoted("x.png"), {path("missing.json"), "/environment/file", "nosuch.hdr"});
    expectRefused("render " + quoted("unknown.json") + " -o " + quoted("x.png"), {path("unknown.json"), "/environment/brightness"});
    double centre[2];
    for (int k = 0; k < 2; ++k) {
        const std::string name = k == 0 ? "one" : "two";
        const GpurtRun run = gpurt("render " + quoted(name + ".json") + " -o " + quoted(name + ".png") + " --size 8x8 --aov color=" +
                                   quoted(name + ".pfm"));
        ASSERT_EQ(run.code, 0) << run.err;
        int w = 0, h = 0, c = 0;
        const std::vector<float> color = readPfm(dir / (name + ".pfm"), w, h, c);
        centre[k] = color[size_t((4 * w + 4) * c)];
    }
    // Whitted: the triangle (albedo 0.8) shows 0.8 x 0.25 under the constant sky.
    EXPECT_NEAR(centre[0], 0.8 * 0.25, 2e-3);
    EXPECT_NEAR(centre[1], 2.0 * centre[0], 1e-5);
}

// --env-rotate through the command line: a patch at +x lights a triangle facing +x and not one
// facing -x; turned by 90 degrees (counter-clockwise seen from above) it is at -z: it lights one
// facing -z and not one facing +z.
TEST_F(EnvironmentMaps, RotateOptionTurnsTheMap) {
    writeMap("patch.hdr", makeMap(64, 32, [](glm::vec3 d) { return d.x > 0.95f ? glm::vec3(20.0f) : glm::vec3(0.0f); }));
    write("tx.obj", "v 0 -1 -1\nv 0 -1 1\nv 0 1 0\nf 1 3 2\n");  // in the x = 0 plane (lit on the side it is seen from)
    write("tz.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");   // in the z = 0 plane
    auto centre = [&](const std::string& obj, const std::string& eye, const std::string& rotate) {
        const GpurtRun run = gpurt("render " + quoted(obj) + " -o " + quoted("r.png") + " --size 8x8 --integrator path --spp 16 --eye " +
                                   eye + " --target 0,0,0 --env " + quoted("patch.hdr") + " --env-rotate " + rotate +
                                   " --aov color=" + quoted("r.pfm"));
        EXPECT_EQ(run.code, 0) << run.err;
        int w = 0, h = 0, c = 0;
        const std::vector<float> color = readPfm(dir / "r.pfm", w, h, c);
        return double(color[size_t((4 * w + 4) * c)]);
    };
    EXPECT_GT(centre("tx.obj", "3,0,0", "0"), 0.1);
    EXPECT_EQ(centre("tx.obj", "-3,0,0", "0"), 0.0);
    EXPECT_GT(centre("tz.obj", "0,0,-3", "90"), 0.1);
    EXPECT_EQ(centre("tz.obj", "0,0,3", "90"), 0.0);
}

// The default light (docs/SCENE_FORMAT.md): over the pixels that show the model (the prim AOV),
// the mean of each PNG pixel's largest channel is in 0.25..0.75 and under 2% have a channel at
// 255, under both integrators.
// Not tests/assets/gltf/cornell_box.glb: it is single-sided (glTF's default) with its walls
// facing inwards, and the default camera is behind its back wall, so the picture is the inside of
// the box seen through the culled wall, lit only through the box's open side (Cli,
// SingleSidedCornellBoxFromBehindShowsItsInside); the same box as OBJ and PLY is here.
class DefaultLight : public GpurtTest, public ::testing::WithParamInterface<std::tuple<std::string, std::string>> {};

TEST_P(DefaultLight, ShowsTheModelWellExposed) {
    const auto& [scene, integrator] = GetParam();
    const GpurtRun run = gpurt("render " + shellQuote(scene) + " -o " + quoted("out.png") + " --size 96x96 --integrator " +
                               integrator + (integrator == "path" ? " --spp 4" : "") + " --aov prim=" + quoted("prim.pfm"));
    ASSERT_EQ(run.code, 0) << run.err;
    int width = 0, height = 0, channels = 0;
    const std::vector<unsigned char> pixels = pngPixels(readFile(path("out.png")), width, height);
    const std::vector<float> prim = readPfm(dir / "prim.pfm", width, height, channels);
    ASSERT_EQ(pixels.size(), size_t(96 * 96 * 3));
    size_t object = 0, clipped = 0;
    double sum = 0.0;
    for (size_t p = 0; p < size_t(96 * 96); ++p) {
        if (prim[p * size_t(channels)] < 0.0f) continue;
        ++object;
        const unsigned char* c = &pixels[3 * p];
        const int largest = std::max(c[0], std::max(c[1], c[2]));
        clipped += largest == 255;
        sum += largest / 255.0;
    }
    ASSERT_GT(object, 200u) << scene;
    const double mean = sum / double(object);
    EXPECT_GE(mean, 0.25) << scene;
    EXPECT_LE(mean, 0.75) << scene;
    EXPECT_LT(double(clipped) / double(object), 0.02) << scene;
    std::cout << "[ exposure ] " << scene << " " << integrator << ": mean " << mean << ", clipped "
              << double(clipped) / double(object) << "\n";
}

INSTANTIATE_TEST_SUITE_P(
    Models, DefaultLight,
    ::testing::Combine(::testing::Values("scenes/cube.obj", "scenes/torus.obj", "scenes/octahedron.obj",
                                         "scenes/tetrahedron.obj", "scenes/boxes.obj", "scenes/room.obj",
                                         "../shared/models/bunny.obj",
                                         "../shared/models/bunny_lo.obj", "../shared/models/teapot.obj",
                                         "../shared/models/cornell_box.obj", "tests/assets/gltf/teapot.gltf",
                                         "tests/assets/ply/teapot_binary.ply",
                                         "tests/assets/ply/cornell_box_be.ply", "tests/assets/textures/globe.glb",
                                         "tests/assets/textures/quad.obj"),
                       ::testing::Values("whitted", "path")),
    [](const auto& info) {
        std::string name = std::get<0>(info.param).substr(std::get<0>(info.param).rfind('/') + 1) + "_" + std::get<1>(info.param);
        for (char& c : name)
            if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
        return name;
    });

// --env none: no default light; the scene is lit as before it existed (the headlight).
TEST_F(EnvironmentMaps, EnvNoneTurnsTheDefaultLightOff) {
    auto render = [&](const std::string& options, const std::string& out) {
        const GpurtRun run = gpurt("render " + quoted("tri.obj") + " -o " + quoted(out) + " --size 16x16 " + options);
        EXPECT_EQ(run.code, 0) << run.err;
        return readFile(dir / out);
    };
    const std::string lit = render("", "a.png"), none = render("--env none", "b.png");
    EXPECT_NE(lit, none);
}

}  // namespace
}  // namespace gpurt::test
