// A stream: a W x H array of 1, 2 or 4 channels of 32 bits in a texture (Christen's GPUFloatArray).
// A kernel reads it as a sampler (random access "gather", texelFetch) and writes it as a colour
// attachment. Float channels by default; unsigned/signed integer formats hold exact indices (float
// holds integers exactly only up to 2^24).
//
// GPUStorage::Buffer keeps the same W x H elements, row after row, in a buffer texture instead: a
// read-only gather table (never an output) that kernels address in 1D, texelFetch(samplerBuffer,
// x + W * y). On Mesa llvmpipe such a fetch costs far less than a 2D one (docs/PERFORMANCE.md).
#pragma once

#include "stream/GL.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace gpurt {

enum class GPUFormat { R32F, RG32F, RGBA32F, R32UI, RG32UI, RGBA32UI, R32I, RG32I, RGBA32I };

enum class GPUScalar { Float, Uint, Int };

enum class GPUStorage {
    Texture2D,  // a 2D texture: a stream kernels read and write
    Buffer,     // a buffer texture: a table kernels only read (GL_MAX_TEXTURE_BUFFER_SIZE elements)
};

int channelCount(GPUFormat format);
GPUScalar scalarType(GPUFormat format);
GPUFormat floatFormat(int channels);  // 1, 2 or 4 channels; throws UsageError otherwise

class GPUFloatArray {
  public:
    // A float array with `channels` (1, 2 or 4) channels.
    GPUFloatArray(int width, int height, int channels, std::string name = "stream");
    GPUFloatArray(int width, int height, GPUFormat format, std::string name = "stream",
                  GPUStorage storage = GPUStorage::Texture2D);
    ~GPUFloatArray();
    GPUFloatArray(const GPUFloatArray&) = delete;
    GPUFloatArray& operator=(const GPUFloatArray&) = delete;
    GPUFloatArray(GPUFloatArray&& other) noexcept;
    GPUFloatArray& operator=(GPUFloatArray&& other) noexcept;

    int width() const { return width_; }
    int height() const { return height_; }
    int channels() const { return channelCount(format_); }
    size_t elements() const { return size_t(width_) * size_t(height_); }
    GPUFormat format() const { return format_; }
    GLenum internalFormat() const;  // GL_RGBA32F, ...: for binding as an image
    GPUStorage storage() const { return storage_; }
    GLuint texture() const { return texture_; }
    const std::string& name() const { return name_; }

    // Whole-array transfers; `data` holds elements() * channels() values, row 0 first.
    void upload(std::span<const float> data);
    void upload(std::span<const uint32_t> data);
    void upload(std::span<const int32_t> data);
    // Rows [y, y + rows) of the array.
    void uploadRows(int y, int rows, std::span<const float> data);
    void uploadRows(int y, int rows, std::span<const uint32_t> data);
    std::vector<float> download() const;
    std::vector<uint32_t> downloadUint() const;
    std::vector<int32_t> downloadInt() const;

    // Sets every element to `value` (all channels).
    void fill(float value);
    // Copies all of `source` (same size and format) into this array; no CPU round trip.
    void copyFrom(const GPUFloatArray& source);

  private:
    void release();
    void uploadRaw(int y, int rows, GPUScalar scalar, const void* data, size_t count);
    void downloadRaw(GPUScalar scalar, void* data, size_t bytes) const;

    int width_ = 0;
    int height_ = 0;
    GPUFormat format_ = GPUFormat::RGBA32F;
    GPUStorage storage_ = GPUStorage::Texture2D;
    GLuint texture_ = 0;
    GLuint buffer_ = 0;  // the buffer behind a GPUStorage::Buffer texture
    std::string name_;
};

// The double-buffered form for kernels that read a stream and write its next state: they read
// front() and write back(); GPUKernel swaps the two after each pass.
class GPUPingPongArray {
  public:
    GPUPingPongArray(int width, int height, int channels, const std::string& name = "stream");
    GPUPingPongArray(int width, int height, GPUFormat format, const std::string& name = "stream");

    GPUFloatArray& front() { return buffers_[current_]; }
    const GPUFloatArray& front() const { return buffers_[current_]; }
    GPUFloatArray& back() { return buffers_[1 - current_]; }
    const GPUFloatArray& back() const { return buffers_[1 - current_]; }
    void swap() { current_ = 1 - current_; }

    int width() const { return front().width(); }
    int height() const { return front().height(); }

  private:
    GPUFloatArray buffers_[2];
    int current_ = 0;
};

}  // namespace gpurt
