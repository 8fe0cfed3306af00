#include "stream/GPUFloatArray.h"

#include "stream/KernelStats.h"
#include "stream/StreamErrors.h"

#include <chrono>
#include <utility>

namespace gpurt {

namespace {

struct FormatInfo {
    GLenum internal;
    GLenum pixelFormat;
    GLenum type;
    int channels;
    GPUScalar scalar;
};

FormatInfo info(GPUFormat format) {
    switch (format) {
        case GPUFormat::R32F: return {GL_R32F, GL_RED, GL_FLOAT, 1, GPUScalar::Float};
        case GPUFormat::RG32F: return {GL_RG32F, GL_RG, GL_FLOAT, 2, GPUScalar::Float};
        case GPUFormat::RGBA32F: return {GL_RGBA32F, GL_RGBA, GL_FLOAT, 4, GPUScalar::Float};
        case GPUFormat::R32UI:
            return {GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, 1, GPUScalar::Uint};
        case GPUFormat::RG32UI:
            return {GL_RG32UI, GL_RG_INTEGER, GL_UNSIGNED_INT, 2, GPUScalar::Uint};
        case GPUFormat::RGBA32UI:
            return {GL_RGBA32UI, GL_RGBA_INTEGER, GL_UNSIGNED_INT, 4, GPUScalar::Uint};
        case GPUFormat::R32I: return {GL_R32I, GL_RED_INTEGER, GL_INT, 1, GPUScalar::Int};
        case GPUFormat::RG32I: return {GL_RG32I, GL_RG_INTEGER, GL_INT, 2, GPUScalar::Int};
        case GPUFormat::RGBA32I: return {GL_RGBA32I, GL_RGBA_INTEGER, GL_INT, 4, GPUScalar::Int};
    }
    throw UsageError("unknown GPUFormat");
}

const char* scalarName(GPUScalar s) {
    return s == GPUScalar::Float ? "float" : s == GPUScalar::Uint ? "uint" : "int";
}

}  // namespace

int channelCount(GPUFormat format) { return info(format).channels; }
GPUScalar scalarType(GPUFormat format) { return info(format).scalar; }

GPUFormat floatFormat(int channels) {
    switch (channels) {
        case 1: return GPUFormat::R32F;
        case 2: return GPUFormat::RG32F;
        case 4: return GPUFormat::RGBA32F;
        default: throw UsageError("a GPUFloatArray has 1, 2 or 4 channels, not " +
                                  std::to_string(channels));
    }
}

GPUFloatArray::GPUFloatArray(int width, int height, int channels, std::string name)
    : GPUFloatArray(width, height, floatFormat(channels), std::move(name)) {}

GPUFloatArray::GPUFloatArray(int width, int height, GPUFormat format, std::string name,
                             GPUStorage storage)
    : width_(width), height_(height), format_(format), storage_(storage), name_(std::move(name)) {
    if (width <= 0 || height <= 0)
        throw UsageError("stream '" + name_ + "': size " + std::to_string(width) + "x" +
                         std::to_string(height) + " is empty");
    while (glGetError() != GL_NO_ERROR) {
    }
    if (storage == GPUStorage::Buffer) {
        GLint maxTexels = 0;
        glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
        if (elements() > size_t(maxTexels))
            throw EnvironmentError("table '" + name_ + "': " + std::to_string(elements()) +
                                   " elements exceed GL_MAX_TEXTURE_BUFFER_SIZE " +
                                   std::to_string(maxTexels));
        glCreateBuffers(1, &buffer_);
        glNamedBufferData(buffer_, GLsizeiptr(elements() * size_t(channels()) * 4), nullptr,
                          GL_STATIC_DRAW);
        glCreateTextures(GL_TEXTURE_BUFFER, 1, &texture_);
        glTextureBuffer(texture_, info(format).internal, buffer_);
    } else {
        GLint maxSize = 0;
        glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
        if (width > maxSize || height > maxSize)
            throw EnvironmentError("stream '" + name_ + "': " + std::to_string(width) + "x" +
                                   std::to_string(height) + " exceeds GL_MAX_TEXTURE_SIZE " +
                                   std::to_string(maxSize));
        glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
        glTextureStorage2D(texture_, 1, info(format).internal, width, height);
        glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(texture_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(texture_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    glObjectLabel(GL_TEXTURE, texture_, GLsizei(name_.size()), name_.data());
    if (glGetError() == GL_OUT_OF_MEMORY) {
        release();
        throw EnvironmentError("stream '" + name_ + "': out of GL memory for " +
                               std::to_string(width) + "x" + std::to_string(height));
    }
}

void GPUFloatArray::release() {
    if (texture_) glDeleteTextures(1, &texture_);
    if (buffer_) glDeleteBuffers(1, &buffer_);
    texture_ = 0;
    buffer_ = 0;
}

GPUFloatArray::~GPUFloatArray() { release(); }

GPUFloatArray::GPUFloatArray(GPUFloatArray&& other) noexcept
    : width_(other.width_),
      height_(other.height_),
      format_(other.format_),
      storage_(other.storage_),
      texture_(std::exchange(other.texture_, 0)),
      buffer_(std::exchange(other.buffer_, 0)),
      name_(std::move(other.name_)) {}

GPUFloatArray& GPUFloatArray::operator=(GPUFloatArray&& other) noexcept {
    if (this != &other) {
        release();
        width_ = other.width_;
        height_ = other.height_;
        format_ = other.format_;
        storage_ = other.storage_;
        texture_ = std::exchange(other.texture_, 0);
        buffer_ = std::exchange(other.buffer_, 0);
        name_ = std::move(other.name_);
    }
    return *this;
}

void GPUFloatArray::uploadRaw(int y, int rows, GPUScalar scalar, const void* data, size_t count) {
    const FormatInfo f = info(format_);
    if (scalar != f.scalar)
        throw UsageError("stream '" + name_ + "': uploading " + scalarName(scalar) +
                         " data into a " + scalarName(f.scalar) + " array");
    if (y < 0 || rows < 0 || y + rows > height_ ||
        count != size_t(width_) * size_t(rows) * size_t(f.channels))
        throw UsageError("stream '" + name_ + "': upload of " + std::to_string(count) +
                         " values does not fit rows " + std::to_string(y) + "+" +
                         std::to_string(rows));
    if (rows == 0) return;
    if (buffer_) {
        const size_t rowBytes = size_t(width_) * size_t(f.channels) * 4;
        glNamedBufferSubData(buffer_, GLintptr(size_t(y) * rowBytes),
                             GLsizeiptr(size_t(rows) * rowBytes), data);
    } else {
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTextureSubImage2D(texture_, 0, 0, y, width_, rows, f.pixelFormat, f.type, data);
    }
    GPURT_CHECK_GL("upload");
}

void GPUFloatArray::upload(std::span<const float> data) {
    uploadRaw(0, height_, GPUScalar::Float, data.data(), data.size());
}
void GPUFloatArray::upload(std::span<const uint32_t> data) {
    uploadRaw(0, height_, GPUScalar::Uint, data.data(), data.size());
}
void GPUFloatArray::upload(std::span<const int32_t> data) {
    uploadRaw(0, height_, GPUScalar::Int, data.data(), data.size());
}
void GPUFloatArray::uploadRows(int y, int rows, std::span<const float> data) {
    uploadRaw(y, rows, GPUScalar::Float, data.data(), data.size());
}
void GPUFloatArray::uploadRows(int y, int rows, std::span<const uint32_t> data) {
    uploadRaw(y, rows, GPUScalar::Uint, data.data(), data.size());
}

void GPUFloatArray::downloadRaw(GPUScalar scalar, void* data, size_t bytes) const {
    const auto start = std::chrono::steady_clock::now();
    const FormatInfo f = info(format_);
    if (scalar != f.scalar)
        throw UsageError("stream '" + name_ + "': downloading a " + scalarName(f.scalar) +
                         " array as " + scalarName(scalar));
    if (buffer_) {
        glGetNamedBufferSubData(buffer_, 0, GLsizeiptr(bytes), data);
    } else {
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glGetTextureImage(texture_, 0, f.pixelFormat, f.type, GLsizei(bytes), data);
    }
    GPURT_CHECK_GL("download");
    KernelStats::global().readBackMs +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::vector<float> GPUFloatArray::download() const {
    std::vector<float> data(elements() * size_t(channels()));
    downloadRaw(GPUScalar::Float, data.data(), data.size() * sizeof(float));
    return data;
}
std::vector<uint32_t> GPUFloatArray::downloadUint() const {
    std::vector<uint32_t> data(elements() * size_t(channels()));
    downloadRaw(GPUScalar::Uint, data.data(), data.size() * sizeof(uint32_t));
    return data;
}
std::vector<int32_t> GPUFloatArray::downloadInt() const {
    std::vector<int32_t> data(elements() * size_t(channels()));
    downloadRaw(GPUScalar::Int, data.data(), data.size() * sizeof(int32_t));
    return data;
}

void GPUFloatArray::fill(float value) {
    const FormatInfo f = info(format_);
    const auto clear = [&](GLenum type, const void* v) {
        if (buffer_)
            glClearNamedBufferData(buffer_, f.internal, f.pixelFormat, type, v);
        else
            glClearTexImage(texture_, 0, f.pixelFormat, type, v);
    };
    if (f.scalar == GPUScalar::Float) {
        const float v[4] = {value, value, value, value};
        clear(GL_FLOAT, v);
    } else if (f.scalar == GPUScalar::Uint) {
        const uint32_t u = uint32_t(value);
        const uint32_t v[4] = {u, u, u, u};
        clear(GL_UNSIGNED_INT, v);
    } else {
        const int32_t i = int32_t(value);
        const int32_t v[4] = {i, i, i, i};
        clear(GL_INT, v);
    }
    GPURT_CHECK_GL("fill");
}

void GPUFloatArray::copyFrom(const GPUFloatArray& source) {
    if (source.width_ != width_ || source.height_ != height_ || source.format_ != format_ ||
        source.storage_ != storage_)
        throw UsageError("stream '" + name_ + "': copy from '" + source.name_ +
                         "' of another size, format or storage");
    if (buffer_) {
        glCopyNamedBufferSubData(source.buffer_, buffer_, 0, 0,
                                 GLsizeiptr(elements() * size_t(channels()) * 4));
        GPURT_CHECK_GL("copyFrom");
        return;
    }
    glCopyImageSubData(source.texture_, GL_TEXTURE_2D, 0, 0, 0, 0, texture_, GL_TEXTURE_2D, 0, 0, 0,
                       0, width_, height_, 1);
    GPURT_CHECK_GL("copyFrom");
}

GPUPingPongArray::GPUPingPongArray(int width, int height, int channels, const std::string& name)
    : GPUPingPongArray(width, height, floatFormat(channels), name) {}

GPUPingPongArray::GPUPingPongArray(int width, int height, GPUFormat format, const std::string& name)
    : buffers_{GPUFloatArray(width, height, format, name + "[0]"),
               GPUFloatArray(width, height, format, name + "[1]")} {}

GLenum GPUFloatArray::internalFormat() const { return info(format_).internal; }

}  // namespace gpurt
