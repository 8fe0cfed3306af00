// A GL query object (GL_SAMPLES_PASSED, GL_ANY_SAMPLES_PASSED, GL_TIME_ELAPSED): a move-only value
// that frees its name on destruction.
#pragma once

#include "stream/GL.h"

#include <cstdint>

namespace gpurt {

class GPUQuery {
  public:
    explicit GPUQuery(GLenum target = GL_SAMPLES_PASSED);
    ~GPUQuery();
    GPUQuery(const GPUQuery&) = delete;
    GPUQuery& operator=(const GPUQuery&) = delete;
    GPUQuery(GPUQuery&& other) noexcept;
    GPUQuery& operator=(GPUQuery&& other) noexcept;

    void begin();
    void end();
    // Blocks: the CPU waits until every pass inside begin()/end() has finished.
    uint64_t result() const;
    // Does not block.
    bool available() const;

    GLuint id() const { return id_; }
    GLenum target() const { return target_; }

  private:
    GLenum target_;
    GLuint id_ = 0;
};

}  // namespace gpurt
