#include "image/TextureImage.h"

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

#include <jpeglib.h>
#include <jerror.h>
#include <png.h>

#include "image/InputError.h"

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

}  // namespace

Rgba8Image decodeImage(const unsigned char* bytes, size_t size, const std::string& name) {
    const uint64_t maxTexels = kMaxTextureTexels;
    static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (size >= 8 && std::memcmp(bytes, kPng, 8) == 0) return decodePng(bytes, size, maxTexels, name);
    if (size >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff) return decodeJpeg(bytes, size, maxTexels, name);
    throw InputError(name + ": not a PNG or JPEG image");
}

Rgba8Image readImage(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path.string() + ": cannot open image file");
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw InputError(path.string() + ": cannot read image file");
    return decodeImage(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), path.string());
}

}  // namespace gpurt
