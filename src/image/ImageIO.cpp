// PNG (libpng) and PFM writing through a temporary file and rename, so that an output file
// appears whole or not at all (CONTRACT.md, exit codes).
#include "image/ImageIO.h"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include <png.h>

#include "image/AtomicFile.h"
#include "image/Colour.h"
#include "image/InputError.h"

namespace gpurt {
namespace {

std::string errnoText() { return std::strerror(errno); }

// libpng reports errors through longjmp; keep the message for the exception.
struct PngErrorState {
    std::jmp_buf jump;
    std::string message;
};

void pngError(png_structp png, png_const_charp message) {
    auto* state = static_cast<PngErrorState*>(png_get_error_ptr(png));
    state->message = message;
    std::longjmp(state->jump, 1);
}

void pngWarning(png_structp, png_const_charp) {}

// Writes the PNG to an open file. Kept free of C++ objects with destructors between setjmp and
// the libpng calls, as longjmp would skip them.
bool writePngRows(FILE* file, int width, int height, unsigned char* const* rows,
                  PngErrorState& state) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, pngError, pngWarning);
    if (!png) {
        state.message = "out of memory";
        return false;
    }
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        state.message = "out of memory";
        return false;
    }
    if (setjmp(state.jump)) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_init_io(png, file);
    png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
                 PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    // Fast over small (docs/PERFORMANCE.md, issue 24): zlib level 2 and two filters to try per row
    // write a rendered 1024x1024 image about 5x faster than libpng's defaults (level 6, all five
    // filters), in a file about a quarter larger (Blender's default PNG compression is 15%).
    png_set_compression_level(png, 2);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB | PNG_FILTER_UP);
    png_write_info(png, info);
    png_write_image(png, const_cast<png_bytepp>(rows));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

void checkSize(const std::filesystem::path& path, int width, int height, size_t values,
               size_t perPixel) {
    if (width < 1 || height < 1 || values != size_t(width) * size_t(height) * perPixel)
        throw InputError(path.string() + ": image of " + std::to_string(width) + "x" +
                         std::to_string(height) + " does not match its " + std::to_string(values) +
                         " values");
}

uint32_t byteSwap(uint32_t x) {
    return (x >> 24) | ((x >> 8) & 0xff00u) | ((x << 8) & 0xff0000u) | (x << 24);
}

}  // namespace

unsigned char linearToSrgb8(float linear) {
    float c = std::isnan(linear) ? 0.0f : std::clamp(linear, 0.0f, 1.0f);
    return static_cast<unsigned char>(std::lround(std::clamp(encodeSrgb(c), 0.0f, 1.0f) * 255.0f));
}

void writePng(const std::filesystem::path& path, int width, int height,
              const std::vector<glm::vec3>& linearTopFirst) {
    AtomicFileSet file;
    writePng(file, path, width, height, linearTopFirst);
    file.commit();
}

void writePfm(const std::filesystem::path& path, int width, int height, int channels,
              const std::vector<float>& topFirst) {
    AtomicFileSet file;
    writePfm(file, path, width, height, channels, topFirst);
    file.commit();
}

void writePng(AtomicFileSet& files, const std::filesystem::path& path, int width, int height,
              const std::vector<glm::vec3>& linearTopFirst) {
    checkSize(path, width, height, linearTopFirst.size(), 1);
    std::vector<unsigned char> pixels(size_t(width) * size_t(height) * 3);
    for (size_t k = 0; k < linearTopFirst.size(); ++k)
        for (int c = 0; c < 3; ++c) pixels[3 * k + size_t(c)] = linearToSrgb8(linearTopFirst[k][c]);
    std::vector<unsigned char*> rows(static_cast<size_t>(height));
    for (int j = 0; j < height; ++j)
        rows[size_t(j)] = pixels.data() + size_t(j) * size_t(width) * 3;
    files.add(path, [&](FILE* file) {
        PngErrorState state;
        if (!writePngRows(file, width, height, rows.data(), state))
            throw InputError(path.string() + ": cannot write PNG (" + state.message + ")");
    });
}

void writePngRgb8(const std::filesystem::path& path, int width, int height,
                  const std::vector<unsigned char>& rgbTopFirst) {
    checkSize(path, width, height, rgbTopFirst.size(), 3);
    std::vector<unsigned char*> rows(static_cast<size_t>(height));
    for (int j = 0; j < height; ++j)
        rows[size_t(j)] = const_cast<unsigned char*>(rgbTopFirst.data()) + size_t(j) * size_t(width) * 3;
    AtomicFileSet files;
    files.add(path, [&](FILE* file) {
        PngErrorState state;
        if (!writePngRows(file, width, height, rows.data(), state))
            throw InputError(path.string() + ": cannot write PNG (" + state.message + ")");
    });
    files.commit();
}

void writePfm(AtomicFileSet& files, const std::filesystem::path& path, int width, int height,
              int channels, const std::vector<float>& topFirst) {
    if (channels != 1 && channels != 3)
        throw InputError(path.string() + ": a PFM has 1 or 3 channels, not " +
                         std::to_string(channels));
    checkSize(path, width, height, topFirst.size(), size_t(channels));
    const size_t rowFloats = size_t(width) * size_t(channels);
    std::vector<float> row(rowFloats);
    files.add(path, [&](FILE* file) {
        std::fprintf(file, "%s\n%d %d\n-1.0\n", channels == 1 ? "Pf" : "PF", width, height);
        // The file's first scanline is the image's bottom row.
        for (int j = height - 1; j >= 0; --j) {
            const float* src = topFirst.data() + size_t(j) * rowFloats;
            if constexpr (std::endian::native == std::endian::little) {
                std::copy(src, src + rowFloats, row.begin());
            } else {
                for (size_t k = 0; k < rowFloats; ++k)
                    row[k] = std::bit_cast<float>(byteSwap(std::bit_cast<uint32_t>(src[k])));
            }
            if (std::fwrite(row.data(), sizeof(float), rowFloats, file) != rowFloats)
                throw InputError(path.string() + ": cannot write file (" + errnoText() + ")");
        }
    });
}

std::vector<unsigned char> readPngRgb8(const std::filesystem::path& path, int& width, int& height) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path.string() + ": cannot open file (" + errnoText() + ")");
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size()))
        throw InputError(path.string() + ": not a readable PNG (" + image.message + ")");
    image.format = PNG_FORMAT_RGB;
    std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(image));
    if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr)) {
        png_image_free(&image);
        throw InputError(path.string() + ": not a readable PNG (" + image.message + ")");
    }
    width = int(image.width);
    height = int(image.height);
    return pixels;
}

std::vector<float> readPfm(const std::filesystem::path& path, int& width, int& height,
                           int& channels) {
    const std::string name = path.string();
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(name + ": cannot open file (" + errnoText() + ")");
    std::string magic;
    double scale = 0;
    in >> magic >> width >> height >> scale;
    if (!in || (magic != "Pf" && magic != "PF") || width < 1 || height < 1 || scale == 0)
        throw InputError(name + ": not a PFM file (bad header)");
    if (size_t(width) * size_t(height) > (size_t(1) << 28))
        throw InputError(name + ": PFM image is too large");
    // Exactly one whitespace character separates the header from the data.
    if (!std::isspace(in.get())) throw InputError(name + ": not a PFM file (bad header)");
    channels = magic == "PF" ? 3 : 1;
    const size_t rowFloats = size_t(width) * size_t(channels);
    // The data must be there before its room is taken (a header may claim 2^28 pixels).
    const std::streampos data = in.tellg();
    in.seekg(0, std::ios::end);
    const std::streamoff bytes = in.tellg() - data;
    in.seekg(data);
    if (bytes < 0 || uint64_t(bytes) < uint64_t(rowFloats) * uint64_t(height) * sizeof(float))
        throw InputError(name + ": PFM data is truncated");
    std::vector<float> topFirst(rowFloats * size_t(height));
    const bool fileLittle = scale < 0;
    const bool swap = fileLittle != (std::endian::native == std::endian::little);
    for (int j = height - 1; j >= 0; --j) {
        float* dst = topFirst.data() + size_t(j) * rowFloats;
        in.read(reinterpret_cast<char*>(dst), std::streamsize(rowFloats * sizeof(float)));
        if (!in) throw InputError(name + ": PFM data is truncated");
        if (swap)
            for (size_t k = 0; k < rowFloats; ++k)
                dst[k] = std::bit_cast<float>(byteSwap(std::bit_cast<uint32_t>(dst[k])));
    }
    return topFirst;
}

}  // namespace gpurt
