#include "image/TextureImage.h"

#include <algorithm>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

#include <jpeglib.h>
#include <jerror.h>
#include <png.h>

#include "image/InputError.h"

// stb_image, only its BMP and TGA readers, compiled into this file with static linkage (as
// EnvironmentImage.cpp compiles its Radiance reader: tinygltf's prebuilt library carries its own
// copy; the fuzz build instruments this one).
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_BMP
#define STBI_ONLY_TGA
#define STBI_NO_STDIO
#define STBI_MAX_DIMENSIONS 16384
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#include <stb/stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace gpurt {
namespace {

bool fits(uint64_t width, uint64_t height, uint64_t maxTexels) {
    return width > 0 && height > 0 && width <= uint64_t(kMaxTextureSide) && height <= uint64_t(kMaxTextureSide) &&
           width * height <= maxTexels;
}

void checkSize(uint64_t width, uint64_t height, uint64_t maxTexels, const std::string& name) {
    if (width == 0 || height == 0) throw InputError(name + ": an image of no pixels");
    if (!fits(width, height, maxTexels))
        throw InputError(name + ": a " + std::to_string(width) + " x " + std::to_string(height) +
                         " image is larger than a texture may be (" + std::to_string(kMaxTextureSide) +
                         " a side, " + std::to_string(maxTexels) + " texels)");
}

Rgba8Image decodePng(const unsigned char* bytes, size_t size, uint64_t maxTexels, const std::string& name) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&image, bytes, size))
        throw InputError(name + ": not a readable PNG (" + image.message + ")");
    try {
        checkSize(image.width, image.height, maxTexels, name);
    } catch (...) {
        png_image_free(&image);
        throw;
    }
    image.format = PNG_FORMAT_RGBA;  // 8 bits a channel, sRGB
    Rgba8Image out;
    out.width = int(image.width);
    out.height = int(image.height);
    std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(image));
    if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr)) {
        png_image_free(&image);
        throw InputError(name + ": not a readable PNG (" + image.message + ")");
    }
    out.texels.resize(size_t(out.width) * size_t(out.height));
    for (size_t k = 0; k < out.texels.size(); ++k) {
        const unsigned char* p = pixels.data() + 4 * k;
        out.texels[k] = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
    }
    return out;
}

// libjpeg reports errors through a callback that must not return: it jumps back to decodeJpeg.
struct JpegError {
    jpeg_error_mgr manager;
    std::jmp_buf back;
    char message[JMSG_LENGTH_MAX];
};

void jpegFail(j_common_ptr info) {
    JpegError* error = reinterpret_cast<JpegError*>(info->err);
    (*info->err->format_message)(info, error->message);
    std::longjmp(error->back, 1);
}

// Warnings (recoverable damage, as extraneous bytes) are not printed; but data that ends early,
// which libjpeg would fill with grey, is a truncated file and fails.
void jpegWarning(j_common_ptr info, int level) {
    if (level == -1 && info->err->msg_code == JWRN_JPEG_EOF) jpegFail(info);
}

// The libjpeg idiom: only `info` and the caller's objects live across the setjmp, so that the
// jump skips no destructor. false: libjpeg failed (error.message says why). The size is checked
// from the header, before libjpeg allocates for the image (a progressive JPEG's coefficients)
// and before the pixels are.
bool runJpeg(const unsigned char* bytes, size_t size, uint64_t maxTexels, JpegError& error,
             std::vector<unsigned char>& pixels, size_t& width, size_t& height) {
    jpeg_decompress_struct info{};
    info.err = jpeg_std_error(&error.manager);
    error.manager.error_exit = jpegFail;
    error.manager.emit_message = jpegWarning;
    if (setjmp(error.back)) {
        jpeg_destroy_decompress(&info);
        return false;
    }
    jpeg_create_decompress(&info);
    jpeg_mem_src(&info, bytes, static_cast<unsigned long>(size));
    jpeg_read_header(&info, TRUE);
    width = info.image_width;
    height = info.image_height;
    if (fits(width, height, maxTexels)) {
        info.out_color_space = JCS_EXT_RGBA;  // libjpeg-turbo: greyscale and YCbCr to RGBA; CMYK fails
        jpeg_start_decompress(&info);
        width = info.output_width;  // the same: no scaling asked
        height = info.output_height;
        pixels.assign(width * height * 4, 0);
        while (info.output_scanline < info.output_height) {
            JSAMPROW row = pixels.data() + size_t(info.output_scanline) * width * 4;
            jpeg_read_scanlines(&info, &row, 1);
        }
        jpeg_finish_decompress(&info);
    }
    jpeg_destroy_decompress(&info);
    return true;
}

Rgba8Image decodeJpeg(const unsigned char* bytes, size_t size, uint64_t maxTexels, const std::string& name) {
    JpegError error{};
    std::vector<unsigned char> pixels;
    size_t width = 0, height = 0;
    if (!runJpeg(bytes, size, maxTexels, error, pixels, width, height))
        throw InputError(name + ": not a readable JPEG (" + error.message + ")");
    checkSize(width, height, maxTexels, name);
    Rgba8Image out;
    out.width = int(width);
    out.height = int(height);
    out.texels.resize(width * height);
    for (size_t k = 0; k < out.texels.size(); ++k) {
        const unsigned char* p = pixels.data() + 4 * k;
        out.texels[k] = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | 0xff000000u;
    }
    return out;
}

// BMP and TGA through stb_image. stb reads zeros past the end of a memory buffer, so it reads
// through these callbacks instead, which note when it asks for bytes the file does not have (a
// truncated file): they then give none, and stb fills in zeros and returns.
struct StbSource {
    const unsigned char* bytes;
    size_t size;
    size_t pos = 0;
    bool overrun = false;
};
int stbRead(void* user, char* data, int size) {
    auto* s = static_cast<StbSource*>(user);
    if (size <= 0) return 0;
    const size_t n = std::min(size_t(size), s->size - s->pos);
    if (n == 0) s->overrun = true;
    std::memcpy(data, s->bytes + s->pos, n);
    s->pos += n;
    return int(n);
}
void stbSkip(void* user, int n) {
    auto* s = static_cast<StbSource*>(user);
    if (n > 0 && size_t(n) > s->size - s->pos) s->overrun = true;
    s->pos = n < 0 ? s->pos - std::min(s->pos, size_t(-int64_t(n))) : std::min(s->size, s->pos + size_t(n));
}
int stbEof(void* user) {
    auto* s = static_cast<StbSource*>(user);
    return s->pos >= s->size ? 1 : 0;
}
const stbi_io_callbacks kStbCallbacks = {stbRead, stbSkip, stbEof};

uint32_t littleEndian(const unsigned char* p, int bytes) {
    uint32_t v = 0;
    for (int k = bytes - 1; k >= 0; --k) v = v << 8 | p[k];
    return v;
}

// The fewest bytes of pixel data a BMP or TGA of its header's size and depth needs (all of the
// file for an uncompressed one; a TGA's run-length packets hold at most 128 pixels each), so that
// a few hundred bytes cannot make stb allocate for a 16384 x 4096 image. 0 when the header is too
// short to say (stb then refuses it).
uint64_t leastPixelBytes(const unsigned char* bytes, size_t size, bool bmp, uint64_t width, uint64_t height) {
    if (bmp) {
        if (size < 30) return 0;
        const uint32_t headerSize = littleEndian(bytes + 14, 4);
        const uint64_t bits = littleEndian(bytes + (headerSize == 12 ? 24 : 28), 2);
        const uint64_t row = (width * bits + 31) / 32 * 4;
        return row * (height - 1) + (width * bits + 7) / 8;  // the last row's padding may be missing
    }
    if (size < 18) return 0;
    const uint64_t pixel = (uint64_t(bytes[16]) + 7) / 8;
    const uint64_t pixels = width * height;
    return bytes[2] >= 9 ? (pixels + 127) / 128 * (1 + pixel) : pixels * pixel;
}

Rgba8Image decodeStb(const unsigned char* bytes, size_t size, bool bmp, uint64_t maxTexels, const std::string& name) {
    const std::string kind = bmp ? "BMP" : "TGA";
    if (size > size_t(INT32_MAX)) throw InputError(name + ": file too large");
    int w = 0, h = 0, comp = 0;
    StbSource info{bytes, size};
    if (!stbi_info_from_callbacks(&kStbCallbacks, &info, &w, &h, &comp))
        throw InputError(name + ": not a readable " + kind + " (" + stbi_failure_reason() + ")");
    checkSize(uint64_t(w), uint64_t(h), maxTexels, name);
    const uint64_t least = leastPixelBytes(bytes, size, bmp, uint64_t(w), uint64_t(h));
    if (least > size)
        throw InputError(name + ": truncated " + kind + " (a " + std::to_string(w) + " x " + std::to_string(h) +
                         " image needs at least " + std::to_string(least) + " bytes of pixels; the file has " +
                         std::to_string(size) + " bytes)");
    StbSource source{bytes, size};
    stbi_uc* pixels = stbi_load_from_callbacks(&kStbCallbacks, &source, &w, &h, &comp, 4);  // RGBA, 8 bits
    if (!pixels) throw InputError(name + ": not a readable " + kind + " (" + stbi_failure_reason() + ")");
    if (source.overrun) {
        stbi_image_free(pixels);
        throw InputError(name + ": truncated " + kind + " (its " + std::to_string(w) + " x " + std::to_string(h) +
                         " pixels end early)");
    }
    Rgba8Image out;
    out.width = w;
    out.height = h;
    out.texels.resize(size_t(w) * size_t(h));
    for (size_t k = 0; k < out.texels.size(); ++k) {
        const stbi_uc* p = pixels + 4 * k;
        out.texels[k] = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
    }
    stbi_image_free(pixels);
    return out;
}

}  // namespace

Rgba8Image decodeImage(const unsigned char* bytes, size_t size, const std::string& name) {
    const uint64_t maxTexels = kMaxTextureTexels;
    static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (size >= 8 && std::memcmp(bytes, kPng, 8) == 0) return decodePng(bytes, size, maxTexels, name);
    if (size >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff) return decodeJpeg(bytes, size, maxTexels, name);
    if (size >= 2 && bytes[0] == 'B' && bytes[1] == 'M') return decodeStb(bytes, size, true, maxTexels, name);
    // TGA has no signature: stb's test of its header (colour map and image types, sizes, depths).
    int w = 0, h = 0, comp = 0;
    StbSource test{bytes, size};
    if (size >= 18 && size <= size_t(INT32_MAX) && stbi_info_from_callbacks(&kStbCallbacks, &test, &w, &h, &comp))
        return decodeStb(bytes, size, false, maxTexels, name);
    throw InputError(name + ": not a PNG, JPEG, BMP or TGA image");
}

Rgba8Image readImage(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path.string() + ": cannot open image file");
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw InputError(path.string() + ": cannot read image file");
    return decodeImage(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), path.string());
}

}  // namespace gpurt
