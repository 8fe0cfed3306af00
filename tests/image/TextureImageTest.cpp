// Texture images (image/TextureImage: PNG and JPEG to sRGB RGBA8) and their filtering on the CPU
// (raytrace/SurfaceTexture, the code the kernels share), against the colours the files were made
// with and the bilinear formula.
#include <gtest/gtest.h>
#include <png.h>
#include <zlib.h>

#include <cmath>
#include <fstream>
#include <iterator>

#include "../common/ImageFiles.h"
#include "../common/Refusal.h"
#include "image/TextureImage.h"
#include "raytrace/materials/SurfaceTexture.h"

namespace gpurt::test {
namespace {

const std::string kAssets = "tests/assets/textures/";

std::string bytesOf(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

Rgba8Image decode(const std::string& bytes, const std::string& name = "image") {
    return decodeImage(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), name);
}

std::string refusal(const std::string& bytes) {
    return refusalOf([&] { decode(bytes, "t.img"); }, "t.img");
}

uint32_t rgba(uint32_t r, uint32_t g, uint32_t b, uint32_t a = 255) { return r | g << 8 | b << 16 | a << 24; }

// A PNG that libpng writes from `pixels` in `format` (the simplified API).
std::string pngOf(int width, int height, uint32_t format, const std::vector<unsigned char>& pixels) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    image.width = uint32_t(width);
    image.height = uint32_t(height);
    image.format = format;
    png_alloc_size_t size = 0;
    EXPECT_TRUE(png_image_write_to_memory(&image, nullptr, &size, 0, pixels.data(), 0, nullptr));
    std::string out(size, '\0');
    EXPECT_TRUE(png_image_write_to_memory(&image, out.data(), &size, 0, pixels.data(), 0, nullptr));
    out.resize(size);
    return out;
}

// quadrants.png is ImageMagick's 4 x 4 palette image (2 bits a texel) of red, lime, blue and
// white quadrants.
TEST(TextureImageTest, APaletteImageExpandsToItsColours) {
    const Rgba8Image image = decode(bytesOf(kAssets + "quadrants.png"));
    ASSERT_EQ(image.width, 4);
    ASSERT_EQ(image.height, 4);
    const uint32_t quadrant[2][2] = {{rgba(255, 0, 0), rgba(0, 255, 0)}, {rgba(0, 0, 255), rgba(255, 255, 255)}};
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) EXPECT_EQ(image.texels[size_t(4 * y + x)], quadrant[y / 2][x / 2]) << x << "," << y;
}

// Grey and grey-alpha images become RGB(A) with the grey in each channel; alpha is kept.
TEST(TextureImageTest, GreyAndAlphaPngs) {
    const Rgba8Image grey = decode(pngOf(3, 1, PNG_FORMAT_GRAY, {0, 128, 255}));
    EXPECT_EQ(grey.texels, (std::vector<uint32_t>{rgba(0, 0, 0), rgba(128, 128, 128), rgba(255, 255, 255)}));
    const Rgba8Image alpha = decode(pngOf(2, 1, PNG_FORMAT_RGBA, {10, 20, 30, 40, 50, 60, 70, 255}));
    EXPECT_EQ(alpha.texels, (std::vector<uint32_t>{rgba(10, 20, 30, 40), rgba(50, 60, 70, 255)}));
}

// checker.jpg is ImageMagick's JPEG (quality 92) of checker.png: libjpeg-turbo's decoding is that
// image but for the JPEG's own loss (a few levels on average, more along the squares' edges).
TEST(TextureImageTest, AJpegDecodesCloseToItsLosslessImage) {
    const Rgba8Image jpeg = decode(bytesOf(kAssets + "checker.jpg"));
    const Rgba8Image png = decode(bytesOf(kAssets + "checker.png"));
    ASSERT_EQ(jpeg.width, 256);
    ASSERT_EQ(jpeg.height, 128);
    ASSERT_EQ(jpeg.texels.size(), png.texels.size());
    double sum = 0.0;
    int largest = 0;
    for (size_t k = 0; k < png.texels.size(); ++k)
        for (int c = 0; c < 3; ++c) {
            const int d = std::abs(int((jpeg.texels[k] >> (8 * c)) & 0xffu) - int((png.texels[k] >> (8 * c)) & 0xffu));
            sum += d;
            largest = std::max(largest, d);
        }
    EXPECT_LT(sum / double(3 * png.texels.size()), 3.0);
    EXPECT_LT(largest, 64);
    EXPECT_EQ(jpeg.texels[0] >> 24, 255u);
}

TEST(TextureImageTest, WhatIsNotAWholeImageIsRefused) {
    const std::string png = bytesOf(kAssets + "quadrants.png");
    const std::string jpeg = bytesOf(kAssets + "checker.jpg");
    EXPECT_REFUSED("", "not a PNG, JPEG, BMP or TGA");
    EXPECT_REFUSED("GIF89a\x01\x00\x01\x00", "not a PNG, JPEG, BMP or TGA");
    EXPECT_REFUSED(png.substr(0, 40), "not a readable PNG");
    EXPECT_REFUSED(png.substr(0, png.find("IDAT") + 10), "not a readable PNG");  // pixel data cut short
    EXPECT_REFUSED(jpeg.substr(0, 100), "not a readable JPEG");
    EXPECT_REFUSED(jpeg.substr(0, jpeg.size() / 2), "not a readable JPEG");
    // A header that claims more texels than a texture may have is refused before any is read.
    std::string huge = png;
    const unsigned char width[4] = {0, 0, 0x4e, 0x20};  // 20000, big endian, in IHDR (at byte 16)
    huge.replace(16, 4, reinterpret_cast<const char*>(width), 4);
    const uint32_t crc = uint32_t(crc32(0, reinterpret_cast<const Bytef*>(huge.data() + 12), 17));
    const unsigned char crcBytes[4] = {uint8_t(crc >> 24), uint8_t(crc >> 16), uint8_t(crc >> 8), uint8_t(crc)};
    huge.replace(29, 4, reinterpret_cast<const char*>(crcBytes), 4);
    EXPECT_REFUSED(huge, "larger than a texture may be");
    EXPECT_THROW(readImage("tests/assets/textures/no-such-image.png"), InputError);
}

// A 5 x 3 image (odd width: BMP rows are padded) with runs and single pixels, alpha varying.
std::vector<unsigned char> testRgba() {
    std::vector<unsigned char> rgba;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x) {
            const bool run = y == 1 && x < 4;  // four equal pixels: a TGA run packet
            rgba.insert(rgba.end(), {static_cast<unsigned char>(run ? 7 : 40 * x + 3), static_cast<unsigned char>(run ? 99 : 60 * y),
                                     static_cast<unsigned char>(run ? 250 : 13 * x * y), static_cast<unsigned char>(run ? 255 : 255 - 20 * x)});
        }
    return rgba;
}

// BMP and TGA (stb_image) decode to the texels libpng gives for the same image as a PNG: every
// layout the writers of ImageFiles.h make (BMP 24 and 32 bits; TGA 24 and 32 bits, top or bottom
// row first, raw or run-length encoded). 24-bit files have no alpha: 255.
TEST(TextureImageTest, BmpAndTgaDecodeAsTheSameImageAsPng) {
    const std::vector<unsigned char> rgba = testRgba();
    std::vector<unsigned char> opaque = rgba;
    for (size_t k = 3; k < opaque.size(); k += 4) opaque[k] = 255;
    const Rgba8Image png = decode(pngOf(5, 3, PNG_FORMAT_RGBA, rgba)), opaquePng = decode(pngOf(5, 3, PNG_FORMAT_RGBA, opaque));
    ASSERT_EQ(png.texels.size(), 15u);
    for (int bits : {24, 32}) {
        SCOPED_TRACE(bits);
        const std::vector<uint32_t>& expected = bits == 32 ? png.texels : opaquePng.texels;
        const Rgba8Image bmp = decode(bmpOf(5, 3, bits, rgba));
        EXPECT_EQ(bmp.width, 5);
        EXPECT_EQ(bmp.height, 3);
        EXPECT_EQ(bmp.texels, expected);
        for (bool top : {false, true})
            for (bool rle : {false, true}) {
                SCOPED_TRACE(std::string(top ? "top first" : "bottom first") + (rle ? " rle" : " raw"));
                const Rgba8Image tga = decode(tgaOf(5, 3, bits, top, rle, rgba));
                EXPECT_EQ(tga.width, 5);
                EXPECT_EQ(tga.texels, expected);
            }
    }
}

// A BMP or TGA header is checked against the bytes the file has before stb allocates for the
// pixels: 400 bytes claiming 16384 x 4096 (2^26 texels, as many as a texture may have) are
// refused as truncated; so is a file whose pixels (or run-length packets) end early.
TEST(TextureImageTest, BmpAndTgaThatClaimMoreThanTheyHoldAreRefused) {
    const std::vector<unsigned char> rgba = testRgba();
    std::string bmp = bmpOf(5, 3, 24, rgba);
    std::string huge = bmp;
    huge.replace(18, 8, std::string("\x00\x40\x00\x00\x00\x10\x00\x00", 8));  // 16384 x 4096
    huge.resize(400, '\0');
    EXPECT_REFUSED(huge, "t.img: truncated BMP (a 16384 x 4096 image needs at least");
    EXPECT_REFUSED(bmp.substr(0, bmp.size() - 20), "truncated BMP");
    std::string rle = bmp;
    rle[30] = 1;  // BI_RLE8: stb does not read it
    EXPECT_REFUSED(rle, "not a readable BMP");
    std::string tga = tgaOf(5, 3, 32, true, true, rgba);
    std::string hugeTga = tga;
    hugeTga.replace(12, 4, std::string("\x00\x40\x00\x10", 4));  // 16384 x 4096
    hugeTga.resize(400, '\0');
    EXPECT_REFUSED(hugeTga, "truncated TGA");
    EXPECT_REFUSED(tga.substr(0, tga.size() - 3), "truncated TGA");
    const std::string raw = tgaOf(5, 3, 24, false, false, rgba);
    EXPECT_REFUSED(raw.substr(0, raw.size() - 1), "truncated TGA");
}

// IEC 61966-2-1 in double.
double linear(uint32_t code) {
    const double c = code / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// A 2 x 2 texture of distinct grey levels (red = green = blue), filtered at points whose weights
// the bilinear formula gives, for each wrap mode.
TEST(SurfaceTextureTest, BilinearFilteringAndWrapping) {
    Texture texture;
    texture.image.width = 2;
    texture.image.height = 2;
    const uint32_t codes[4] = {0, 60, 140, 255};  // (0, 0), (1, 0), (0, 1), (1, 1)
    for (uint32_t c : codes) texture.image.texels.push_back(rgba(c, c, c));
    auto grey = [&](float x, float y) { return double(sampleTexture(texture, {x, y}).y); };
    auto texel = [&](int x, int y) { return linear(codes[2 * y + x]); };
    for (uint32_t wrap : {kWrapRepeat, kWrapClamp, kWrapMirror}) {
        SCOPED_TRACE(wrap);
        texture.wrapS = texture.wrapT = wrap;
        // Texel centres are the texels; between them the weights are linear.
        EXPECT_NEAR(grey(0.25f, 0.25f), texel(0, 0), 1e-6);
        EXPECT_NEAR(grey(0.75f, 0.75f), texel(1, 1), 1e-6);
        EXPECT_NEAR(grey(0.5f, 0.25f), 0.5 * (texel(0, 0) + texel(1, 0)), 1e-6);
        EXPECT_NEAR(grey(0.375f, 0.625f),
                    0.75 * 0.25 * texel(0, 0) + 0.25 * 0.25 * texel(1, 0) + 0.75 * 0.75 * texel(0, 1) + 0.25 * 0.75 * texel(1, 1),
                    1e-6);
    }
    // Outside a texel centre's reach: repeat blends with the other side; clamp keeps the edge.
    texture.wrapS = texture.wrapT = kWrapRepeat;
    EXPECT_NEAR(grey(0.0f, 0.25f), 0.5 * (texel(0, 0) + texel(1, 0)), 1e-6);
    EXPECT_NEAR(grey(0.25f + 3.0f, 0.25f - 2.0f), texel(0, 0), 1e-6);
    EXPECT_NEAR(grey(-0.25f, 0.75f), texel(1, 1), 1e-6);
    texture.wrapS = texture.wrapT = kWrapClamp;
    EXPECT_NEAR(grey(0.0f, 0.25f), texel(0, 0), 1e-6);
    EXPECT_NEAR(grey(-7.0f, 9.0f), texel(0, 1), 1e-6);
    texture.wrapS = texture.wrapT = kWrapMirror;
    EXPECT_NEAR(grey(-0.25f, 0.25f), texel(0, 0), 1e-6);  // mirrored about 0
    EXPECT_NEAR(grey(1.25f, 0.25f), texel(1, 0), 1e-6);   // about 1
    EXPECT_NEAR(grey(2.25f, 0.25f), texel(0, 0), 1e-6);   // period 2
    // Coordinates that are not finite sample at 0 rather than anywhere.
    texture.wrapS = texture.wrapT = kWrapRepeat;
    EXPECT_NEAR(grey(std::nanf(""), 0.25f), grey(0.0f, 0.25f), 1e-6);
    EXPECT_NEAR(grey(INFINITY, 0.25f), grey(0.0f, 0.25f), 1e-6);
}

// The material's colour times the texture's at the interpolated coordinates; without a texture
// (or texture coordinates) the colour alone.
TEST(SurfaceTextureTest, DiffuseIsTheColourTimesTheTexture) {
    Scene scene;
    scene.triangles.push_back({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    scene.materialIds.push_back(0);
    Material m;
    m.diffuse = {0.5f, 1.0f, 0.25f};
    Texture texture;
    texture.image.width = 2;
    texture.image.height = 1;
    texture.image.texels = {rgba(255, 0, 128), rgba(0, 255, 255)};
    scene.textures.push_back(texture);
    EXPECT_EQ(diffuseAt(scene, m, 0, 0.2f, 0.3f), m.diffuse);  // no texture
    m.diffuseTexture = 0;
    EXPECT_EQ(diffuseAt(scene, m, 0, 0.2f, 0.3f), m.diffuse);  // no texture coordinates
    // Corner 0 at the first texel's centre, corner 1 at the second's.
    scene.texcoords.push_back({{0.25f, 0.5f}, {0.75f, 0.5f}, {0.25f, 0.5f}});
    const glm::vec3 first = diffuseAt(scene, m, 0, 0.0f, 0.0f);
    EXPECT_NEAR(first.x, 0.5 * 1.0, 1e-6);
    EXPECT_NEAR(first.y, 0.0, 1e-6);
    EXPECT_NEAR(first.z, 0.25 * linear(128), 1e-6);
    const glm::vec3 half = diffuseAt(scene, m, 0, 0.5f, 0.0f);
    EXPECT_NEAR(half.y, 0.5 * 1.0, 1e-6);
    EXPECT_NEAR(half.z, 0.25 * 0.5 * (linear(128) + 1.0), 1e-6);
}

}  // namespace
}  // namespace gpurt::test
