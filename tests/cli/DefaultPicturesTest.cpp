// The pictures a new user gets: every scene in scenes/ and ../shared/models rendered by the
// program with its default camera, lights, tone map and exposure has fewer than 2% of its pixels
// clipped (a channel at 255) and a mean brightness between 0.15 and 0.8 of white.
#include "CliRunner.h"
#include "PngPixels.h"

#include <gtest/gtest.h>

namespace gpurt::test {
namespace {

class DefaultPictures : public GpurtTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(DefaultPictures, AreNeitherClippedNorDark) {
    const std::string scene = GetParam();
    const GpurtRun run = gpurt("render " + shellQuote(scene) + " -o " + quoted("out.png") + " --size 96x96");
    ASSERT_EQ(run.code, 0) << run.err;
    int width = 0, height = 0;
    const std::vector<unsigned char> pixels = pngPixels(readFile(path("out.png")), width, height);
    ASSERT_EQ(pixels.size(), size_t(96 * 96 * 3));
    size_t clipped = 0;
    double sum = 0.0;
    for (size_t i = 0; i < pixels.size(); i += 3) {
        clipped += pixels[i] == 255 || pixels[i + 1] == 255 || pixels[i + 2] == 255;
        sum += double(pixels[i]) + pixels[i + 1] + pixels[i + 2];
    }
    const double mean = sum / double(pixels.size()) / 255.0;
    EXPECT_LT(double(clipped) / double(96 * 96), 0.02) << scene;
    EXPECT_GT(mean, 0.15) << scene;
    EXPECT_LT(mean, 0.8) << scene;
}

INSTANTIATE_TEST_SUITE_P(Scenes, DefaultPictures,
                         ::testing::Values("scenes/boxes.json", "scenes/room.json", "scenes/highlow.json",
                                           "scenes/cornell.json", "../shared/models/bunny.obj",
                                           "../shared/models/bunny_lo.obj", "../shared/models/teapot.obj",
                                           "../shared/models/cornell_box.obj"),
                         [](const auto& info) {
                             std::string name = info.param.substr(info.param.rfind('/') + 1);
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

}  // namespace
}  // namespace gpurt::test
