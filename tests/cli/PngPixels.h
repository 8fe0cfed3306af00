// Reading back the PNGs the program writes, for tests.
#pragma once

#include <png.h>

#include <string>
#include <vector>

namespace gpurt::test {

// Pixels of an 8-bit RGB PNG (libpng's simplified API); empty when it cannot be read.
inline std::vector<unsigned char> pngPixels(const std::string& bytes, int& width, int& height) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) return {};
    image.format = PNG_FORMAT_RGB;
    std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(image));
    if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr)) return {};
    width = int(image.width);
    height = int(image.height);
    return pixels;
}

}  // namespace gpurt::test
