#include "image/ExrIO.h"

#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include "image/AtomicFile.h"
#include "image/InputError.h"

namespace gpurt {
namespace {

// OpenEXR's output through the FILE* of an atomic file.
class FileStream : public Imf::OStream {
  public:
    FileStream(std::FILE* file, const std::string& name) : Imf::OStream(name.c_str()), file_(file), name_(name) {}
    void write(const char c[], int n) override {
        if (std::fwrite(c, 1, size_t(n), file_) != size_t(n))
            throw InputError(name_ + ": cannot write file (" + std::strerror(errno) + ")");
    }
    uint64_t tellp() override { return uint64_t(ftello(file_)); }
    void seekp(uint64_t pos) override {
        if (fseeko(file_, off_t(pos), SEEK_SET) != 0)
            throw InputError(name_ + ": cannot write file (" + std::strerror(errno) + ")");
    }

  private:
    std::FILE* file_;
    std::string name_;
};

}  // namespace

ExrLayout exrLayout(const std::string& output) {
    if (output == "exr") return {{"R", "G", "B"}, true};
    if (output == "depth") return {{"Z"}, false};
    if (output == "normal" || output == "shading_normal") return {{"X", "Y", "Z"}, false};
    if (output == "color" || output == "variance" || output == "albedo") return {{"R", "G", "B"}, false};
    return {{output}, false};  // prim, steps
}

std::vector<float> exrStored(const ExrLayout& layout, std::vector<float> values) {
    if (layout.half)
        for (float& v : values) v = float(Imath::half(v));
    return values;
}

void writeExr(AtomicFileSet& files, const std::filesystem::path& path, int width, int height,
              const ExrLayout& layout, const std::vector<float>& topFirst) {
    const size_t n = layout.channels.size();
    files.add(path, [&](std::FILE* file) {
        Imf::Header header(width, height);
        header.compression() = Imf::ZIP_COMPRESSION;
        const Imf::PixelType type = layout.half ? Imf::HALF : Imf::FLOAT;
        for (const std::string& c : layout.channels) header.channels().insert(c, Imf::Channel(type));
        std::vector<Imath::half> halves;
        if (layout.half) halves.assign(topFirst.begin(), topFirst.end());
        Imf::FrameBuffer frame;
        const size_t size = layout.half ? sizeof(Imath::half) : sizeof(float);
        char* base = layout.half ? reinterpret_cast<char*>(halves.data())
                                 : reinterpret_cast<char*>(const_cast<float*>(topFirst.data()));
        for (size_t c = 0; c < n; ++c)
            frame.insert(layout.channels[c], Imf::Slice(type, base + c * size, n * size, n * size * size_t(width)));
        FileStream stream(file, path.string());
        try {
            Imf::OutputFile out(stream, header);
            out.setFrameBuffer(frame);
            out.writePixels(height);
        } catch (const InputError&) {
            throw;
        } catch (const std::exception& e) {
            throw InputError(path.string() + ": cannot write EXR (" + e.what() + ")");
        }
    });
}

std::vector<float> readExr(const std::filesystem::path& path, const ExrLayout& layout, int& width, int& height) {
    const std::string name = path.string();
    try {
        Imf::InputFile in(name.c_str());
        const Imath::Box2i window = in.header().dataWindow();
        const int64_t w = int64_t(window.max.x) - window.min.x + 1, h = int64_t(window.max.y) - window.min.y + 1;
        if (w < 1 || h < 1 || w > 16384 || h > 16384)
            throw InputError(name + ": " + std::to_string(w) + "x" + std::to_string(h) + " pixels, not 1..16384 per side");
        width = int(w);
        height = int(h);
        const size_t n = layout.channels.size();
        const Imf::PixelType type = layout.half ? Imf::HALF : Imf::FLOAT;
        for (const std::string& c : layout.channels) {
            const Imf::Channel* channel = in.header().channels().findChannel(c);
            if (!channel) throw InputError(name + ": no channel " + c);
            if (channel->type != type) throw InputError(name + ": channel " + c + " is not " + (layout.half ? "half" : "float"));
        }
        std::vector<float> values(size_t(width) * size_t(height) * n);
        Imf::FrameBuffer frame;
        // OpenEXR addresses pixel (x, y) of the data window at base + x xStride + y yStride.
        char* base = reinterpret_cast<char*>(values.data()) -
                     (std::ptrdiff_t(window.min.x) + std::ptrdiff_t(window.min.y) * width) * std::ptrdiff_t(n * sizeof(float));
        for (size_t c = 0; c < n; ++c)
            frame.insert(layout.channels[c],
                         Imf::Slice(Imf::FLOAT, base + c * sizeof(float), n * sizeof(float), n * sizeof(float) * size_t(width)));
        in.setFrameBuffer(frame);
        in.readPixels(window.min.y, window.max.y);
        return values;
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw InputError(name + ": not a readable EXR file (" + e.what() + ")");
    }
}

}  // namespace gpurt
