// Image files: PFM round trip with the contract's bottom-to-top scanlines (checked on the raw
// bytes), a big-endian PFM, PNG read back with libpng, and atomic writes.
#include "image/ImageIO.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include "image/InputError.h"

namespace gpurt {
namespace {

namespace fs = std::filesystem;

class ImageIOTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("gpurt-img-" + std::string(info->name()) + "-" + std::to_string(getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    // Only the named files are left in the folder (no temporary files).
    void expectOnlyFiles(std::initializer_list<std::string> names) {
        size_t count = 0;
        for (const auto& entry : fs::directory_iterator(dir_)) {
            ++count;
            EXPECT_NE(std::find(names.begin(), names.end(), entry.path().filename().string()),
                      names.end())
                << "unexpected file " << entry.path();
        }
        EXPECT_EQ(count, names.size());
    }

    fs::path dir_;
};

std::string readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

float floatAt(const std::string& bytes, size_t offset) {
    float f;
    std::memcpy(&f, bytes.data() + offset, 4);  // the test machine is little-endian, like the file
    return f;
}

TEST_F(ImageIOTest, PfmOneChannelIsBottomRowFirst) {
    // 3 x 2, top row 1 2 3, bottom row 4 5 6.
    const std::vector<float> topFirst = {1, 2, 3, 4, 5, std::numeric_limits<float>::infinity()};
    const fs::path path = dir_ / "depth.pfm";
    writePfm(path, 3, 2, 1, topFirst);
    const std::string bytes = readBytes(path);
    const std::string header = "Pf\n3 2\n-1.0\n";
    ASSERT_EQ(bytes.size(), header.size() + 6 * 4);
    EXPECT_EQ(bytes.substr(0, header.size()), header);
    EXPECT_EQ(floatAt(bytes, header.size()), 4.0f);       // first scanline = bottom row
    EXPECT_EQ(floatAt(bytes, header.size() + 12), 1.0f);  // then the top row
    int w = 0, h = 0, c = 0;
    EXPECT_EQ(readPfm(path, w, h, c), topFirst);
    EXPECT_EQ(w, 3);
    EXPECT_EQ(h, 2);
    EXPECT_EQ(c, 1);
    expectOnlyFiles({"depth.pfm"});
}

TEST_F(ImageIOTest, PfmThreeChannelsRoundTrip) {
    std::vector<float> topFirst;
    for (int k = 0; k < 4 * 3 * 3; ++k) topFirst.push_back(float(k) * 0.5f - 3.0f);
    const fs::path path = dir_ / "normal.pfm";
    writePfm(path, 4, 3, 3, topFirst);
    const std::string bytes = readBytes(path);
    const std::string header = "PF\n4 3\n-1.0\n";
    ASSERT_EQ(bytes.size(), header.size() + topFirst.size() * 4);
    EXPECT_EQ(bytes.substr(0, header.size()), header);
    EXPECT_EQ(floatAt(bytes, header.size()), topFirst[2 * 4 * 3]);  // bottom row's first red
    int w = 0, h = 0, c = 0;
    EXPECT_EQ(readPfm(path, w, h, c), topFirst);
    EXPECT_EQ(c, 3);
}

TEST_F(ImageIOTest, ReadsBigEndianPfm) {
    std::string bytes = "Pf\n2 1\n1.0\n";
    for (float f : {1.5f, -2.0f}) {
        uint32_t bits;
        std::memcpy(&bits, &f, 4);
        for (int shift = 24; shift >= 0; shift -= 8)
            bytes += static_cast<char>((bits >> shift) & 0xff);
    }
    std::ofstream(dir_ / "be.pfm", std::ios::binary) << bytes;
    int w = 0, h = 0, c = 0;
    EXPECT_EQ(readPfm(dir_ / "be.pfm", w, h, c), (std::vector<float>{1.5f, -2.0f}));
}

TEST_F(ImageIOTest, RejectsMalformedPfm) {
    std::ofstream(dir_ / "bad.pfm", std::ios::binary) << "P6\n2 2\n255\n";
    int w, h, c;
    EXPECT_THROW(readPfm(dir_ / "bad.pfm", w, h, c), InputError);
    std::ofstream(dir_ / "short.pfm", std::ios::binary) << "Pf\n2 2\n-1.0\n1234";
    EXPECT_THROW(readPfm(dir_ / "short.pfm", w, h, c), InputError);
}

// The sRGB transfer written out independently, in double.
int srgb8(double linear) {
    const double c = std::clamp(linear, 0.0, 1.0);
    const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
    return int(std::lround(s * 255.0));
}

TEST_F(ImageIOTest, PngIsValidAndSrgbEncoded) {
    const int w = 4, h = 2;
    const std::vector<glm::vec3> linear = {{0, 0, 0},
                                           {1, 1, 1},
                                           {0.5f, 0.25f, 0.001f},
                                           {2.0f, -1.0f, 0.2f},
                                           {0.8f, 0.04f, 0.6f},
                                           {0.0031308f, 0.01f, 0.9f},
                                           {0.3f, 0.7f, 0.1f},
                                           {1e-6f, 0.999f, 0.5f}};
    const fs::path path = dir_ / "image.png";
    writePng(path, w, h, linear);
    expectOnlyFiles({"image.png"});

    png_image image;
    std::memset(&image, 0, sizeof image);
    image.version = PNG_IMAGE_VERSION;
    ASSERT_TRUE(png_image_begin_read_from_file(&image, path.c_str())) << image.message;
    EXPECT_EQ(image.width, png_uint_32(w));
    EXPECT_EQ(image.height, png_uint_32(h));
    image.format = PNG_FORMAT_RGB;
    std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(image));
    ASSERT_TRUE(png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr)) << image.message;
    ASSERT_EQ(pixels.size(), size_t(w * h * 3));
    for (size_t k = 0; k < linear.size(); ++k)
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(int(pixels[3 * k + size_t(c)]), srgb8(linear[k][c]))
                << "pixel " << k << " channel " << c;
    EXPECT_EQ(srgb8(0.5), 188);  // the textbook value
}

TEST_F(ImageIOTest, FailedWritesLeaveNothingBehind) {
    const fs::path missing = dir_ / "no" / "such" / "folder" / "out.png";
    try {
        writePng(missing, 1, 1, {glm::vec3(0.5f)});
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(missing.string() + ": ", 0), 0u) << e.what();
    }
    EXPECT_THROW(writePfm(dir_ / "x.pfm", 2, 2, 1, {1, 2, 3}), InputError);  // wrong size
    EXPECT_THROW(writePng(dir_ / "x.png", 2, 2, {glm::vec3(0.5f)}), InputError);
    expectOnlyFiles({});
}

TEST_F(ImageIOTest, ReplacesAnExistingFileWhole) {
    const fs::path path = dir_ / "out.pfm";
    std::ofstream(path) << "old contents that are longer than the new file will be, to be sure";
    writePfm(path, 1, 1, 1, {7.0f});
    int w, h, c;
    EXPECT_EQ(readPfm(path, w, h, c), std::vector<float>{7.0f});
    expectOnlyFiles({"out.pfm"});
}

}  // namespace
}  // namespace gpurt
