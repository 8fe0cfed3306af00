#include "image/EnvironmentImage.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <iterator>
#include <sstream>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>

#include "image/InputError.h"

// stb_image, only its Radiance reader, compiled into this file with static linkage (tinygltf's
// prebuilt library carries its own copy; the fuzz build instruments this one).
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_HDR
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

// OpenEXR's input from bytes in memory.
class MemoryStream : public Imf::IStream {
  public:
    MemoryStream(const std::string& bytes, const std::string& name) : Imf::IStream(name.c_str()), bytes_(bytes) {}
    bool read(char c[], int n) override {
        if (n < 0 || uint64_t(n) > bytes_.size() - pos_) throw InputError("unexpected end of file");
        std::memcpy(c, bytes_.data() + pos_, size_t(n));
        pos_ += uint64_t(n);
        return pos_ < bytes_.size();
    }
    uint64_t tellg() override { return pos_; }
    void seekg(uint64_t pos) override { pos_ = std::min<uint64_t>(pos, bytes_.size()); }

  private:
    const std::string& bytes_;
    uint64_t pos_ = 0;
};

void checkSize(int64_t w, int64_t h, const std::string& name) {
#ifdef GPURT_FUZZ_ENVIRONMENT_TEXELS  // the fuzzer's memory limit (tests/fuzz/CMakeLists.txt)
    if (w > 0 && h > 0 && w * h > GPURT_FUZZ_ENVIRONMENT_TEXELS)
        throw InputError(name + ": environment map too large for the fuzzer");
#endif
    if (w < 1 || h < 1 || w > kMaxEnvironmentWidth || h > kMaxEnvironmentHeight)
        throw InputError(name + ": environment map of " + std::to_string(w) + "x" + std::to_string(h) +
                         " texels, not 1.." + std::to_string(kMaxEnvironmentWidth) + " x 1.." +
                         std::to_string(kMaxEnvironmentHeight));
}

// stb_image reads through these callbacks so that a file that ends early is told from one that
// does not: stb itself reads zeros past the end. `overrun` is set when stb asks for bytes past it,
// and it is then given line ends ('\n'): on zeros stb's run-length decoder would loop for ever (a
// run of length 0 makes no progress) and on other bytes its header reader (which reads to a line
// end); on '\n' the header ends and every run has length 10, so stb returns soon.
struct HdrSource {
    const std::string& bytes;
    size_t pos = 0;
    bool overrun = false;
};
int hdrRead(void* user, char* data, int size) {
    auto* s = static_cast<HdrSource*>(user);
    if (size <= 0) return 0;
    const size_t n = std::min(size_t(size), s->bytes.size() - s->pos);
    if (n == 0) {
        s->overrun = true;
        std::memset(data, '\n', size_t(size));
        return size;
    }
    std::memcpy(data, s->bytes.data() + s->pos, n);
    s->pos += n;
    return int(n);
}
void hdrSkip(void* user, int n) {
    auto* s = static_cast<HdrSource*>(user);
    if (n < 0 || size_t(n) > s->bytes.size() - s->pos) {
        s->overrun = n > 0;
        s->pos = n > 0 ? s->bytes.size() : s->pos;
        return;
    }
    s->pos += size_t(n);
}
int hdrEof(void* user) {
    auto* s = static_cast<HdrSource*>(user);
    return s->pos >= s->bytes.size() ? 1 : 0;
}
const stbi_io_callbacks kHdrCallbacks = {hdrRead, hdrSkip, hdrEof};

EnvironmentImage decodeHdr(const std::string& bytes, const std::string& name) {
    if (bytes.size() > size_t(INT32_MAX)) throw InputError(name + ": file too large");
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    int w = 0, h = 0, comp = 0;
    if (!stbi_is_hdr_from_memory(data, int(bytes.size())))
        throw InputError(name + ": not a Radiance .hdr file (no #?RADIANCE or #?RGBE header)");
    HdrSource info{bytes};
    if (!stbi_info_from_callbacks(&kHdrCallbacks, &info, &w, &h, &comp))
        throw InputError(name + ": not a readable Radiance .hdr file (" + stbi_failure_reason() + ")");
    checkSize(w, h, name);
    HdrSource source{bytes};
    float* texels = stbi_loadf_from_callbacks(&kHdrCallbacks, &source, &w, &h, &comp, 3);
    if (!texels) throw InputError(name + ": not a readable Radiance .hdr file (" + stbi_failure_reason() + ")");
    if (source.overrun) {
        stbi_image_free(texels);
        throw InputError(name + ": truncated Radiance .hdr file (its " + std::to_string(w) + "x" + std::to_string(h) +
                         " texels end early)");
    }
    EnvironmentImage image;
    image.width = w;
    image.height = h;
    image.texels.resize(size_t(w) * size_t(h));
    for (size_t i = 0; i < image.texels.size(); ++i)
        image.texels[i] = glm::vec3(texels[3 * i], texels[3 * i + 1], texels[3 * i + 2]);
    stbi_image_free(texels);
    return image;
}

EnvironmentImage decodeExr(const std::string& bytes, const std::string& name) {
    try {
        MemoryStream stream(bytes, name);
        Imf::InputFile in(stream);
        const Imath::Box2i window = in.header().dataWindow();
        const int64_t w = int64_t(window.max.x) - window.min.x + 1, h = int64_t(window.max.y) - window.min.y + 1;
        checkSize(w, h, name);
        for (const char* c : {"R", "G", "B"})
            if (!in.header().channels().findChannel(c))
                throw InputError(name + ": no channel " + c + " (an environment map needs R, G and B)");
        EnvironmentImage image;
        image.width = int(w);
        image.height = int(h);
        image.texels.assign(size_t(w) * size_t(h), glm::vec3(0.0f));
        Imf::FrameBuffer frame;
        const size_t stride = sizeof(glm::vec3);
        char* base = reinterpret_cast<char*>(image.texels.data()) -
                     (std::ptrdiff_t(window.min.x) + std::ptrdiff_t(window.min.y) * std::ptrdiff_t(w)) * std::ptrdiff_t(stride);
        const char* names[3] = {"R", "G", "B"};
        for (size_t c = 0; c < 3; ++c)
            frame.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), stride, stride * size_t(w)));
        in.setFrameBuffer(frame);
        in.readPixels(window.min.y, window.max.y);
        return image;
    } catch (const InputError& e) {
        const std::string what = e.what();
        if (what.rfind(name + ":", 0) == 0) throw;
        throw InputError(name + ": not a readable EXR file (" + what + ")");
    } catch (const std::exception& e) {
        throw InputError(name + ": not a readable EXR file (" + e.what() + ")");
    }
}

}  // namespace

void checkEnvironmentImage(EnvironmentImage& image, const std::string& name) {
    checkSize(image.width, image.height, name);
    size_t negative = 0, huge = 0;
    for (size_t i = 0; i < image.texels.size(); ++i) {
        glm::vec3& t = image.texels[i];
        for (int c = 0; c < 3; ++c) {
            if (!std::isfinite(t[c]))
                throw InputError(name + ": texel (" + std::to_string(i % size_t(image.width)) + ", " +
                                 std::to_string(i / size_t(image.width)) + ") is " + (std::isnan(t[c]) ? "NaN" : "infinite") +
                                 "; an environment map's texels must be finite");
            if (t[c] < 0.0f) {
                t[c] = 0.0f;
                ++negative;
            }
            if (t[c] > kMaxEnvironmentRadiance) {  // the harmonics' sums would overflow float
                t[c] = kMaxEnvironmentRadiance;
                ++huge;
            }
        }
    }
    if (negative > 0) warnAt({name}, std::to_string(negative) + " negative texel channels clamped to 0");
    if (huge > 0) warnAt({name}, std::to_string(huge) + " texel channels above 1e30 clamped to 1e30");
}

EnvironmentImage decodeEnvironmentImage(const std::string& bytes, const std::string& name, bool exr) {
    EnvironmentImage image = exr ? decodeExr(bytes, name) : decodeHdr(bytes, name);
    checkEnvironmentImage(image, name);
    return image;
}

EnvironmentImage readEnvironmentImage(const std::filesystem::path& path) {
    const std::string name = path.string();
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext != ".hdr" && ext != ".pic" && ext != ".exr")
        throw InputError(name + ": not an environment map (.hdr or .exr expected)");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw InputError(name + ": cannot open environment map (no such file)");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(name + ": cannot open environment map");
    std::ostringstream buffer;
    buffer << in.rdbuf();
    return decodeEnvironmentImage(buffer.str(), name, ext == ".exr");
}

void writeHdr(const std::filesystem::path& path, const EnvironmentImage& image) {
    std::ofstream out(path, std::ios::binary);
    out << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " << image.height << " +X " << image.width << "\n";
    for (const glm::vec3& t : image.texels) {
        const float m = std::max(t.x, std::max(t.y, t.z));
        unsigned char rgbe[4] = {0, 0, 0, 0};
        if (m > 1e-32f) {
            int e;
            const float scale = std::frexp(m, &e) * 256.0f / m;
            // Rounded to the nearest code (the decoder takes code x 2^(e - 136), no half step).
            auto code = [&](float c) { return (unsigned char)std::min(255.0f, std::max(0.0f, c) * scale + 0.5f); };
            rgbe[0] = code(t.x);
            rgbe[1] = code(t.y);
            rgbe[2] = code(t.z);
            rgbe[3] = (unsigned char)(e + 128);
        }
        out.write(reinterpret_cast<const char*>(rgbe), 4);
    }
    if (!out) throw InputError(path.string() + ": cannot write file");
}

}  // namespace gpurt
