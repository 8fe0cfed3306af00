// Texture images for materials (glTF base colour textures, MTL map_Kd): PNG (libpng), JPEG
// (libjpeg-turbo), BMP and TGA (stb_image: the Maya-era OBJ files use BMP), chosen by their
// signature (TGA, which has none, by stb's test of its header), decoded to 8-bit sRGB RGBA.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace gpurt {

// Larger images than these are refused (a texture of 16384 x 4096 is 256 MiB decoded). The fuzz
// targets build with a smaller limit (GPURT_FUZZ_TEXTURE_TEXELS): a few hundred bytes can claim a
// 16384 x 4096 JPEG, which the reader rightly allocates for before it finds the data missing,
// beyond the fuzzer's memory limit under the sanitizers.
constexpr int kMaxTextureSide = 16384;
#ifdef GPURT_FUZZ_TEXTURE_TEXELS
constexpr uint64_t kMaxTextureTexels = GPURT_FUZZ_TEXTURE_TEXELS;
#else
constexpr uint64_t kMaxTextureTexels = uint64_t(1) << 26;
#endif

struct Rgba8Image {
    int width = 0, height = 0;
    // Top row first; each texel r | g << 8 | b << 16 | a << 24, sRGB-encoded as stored in the file
    // (greyscale and palette images expanded; alpha 255 where the file has none).
    std::vector<uint32_t> texels;
};

// Decodes a PNG, JPEG, BMP or TGA held in memory. Throws InputError("<name>: ...") when it is
// none of them, is damaged or truncated, or is larger than the limits above, which is checked from
// the header before anything is allocated for the pixels (for BMP and TGA also against the bytes
// the file has: an uncompressed image needs all its pixels, a run-length TGA one byte and a pixel
// for every 128).
Rgba8Image decodeImage(const unsigned char* bytes, size_t size, const std::string& name);

// The same for a file.
Rgba8Image readImage(const std::filesystem::path& path);

}  // namespace gpurt
