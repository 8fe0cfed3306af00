// Draws the primitive that covers a kernel's output: one fullscreen triangle (default) or a quad
// (two triangles), over the whole output or a sub-rectangle of it. The vertex positions come from
// gl_VertexID in glsl/stream/generator.vert; no vertex buffers.
#pragma once

#include "stream/GL.h"

namespace gpurt {

enum class StreamPrimitive { Triangle, Quad };

struct StreamRect {
    int x = 0, y = 0, width = 0, height = 0;
};

class GPUStreamGenerator {
  public:
    explicit GPUStreamGenerator(StreamPrimitive primitive = StreamPrimitive::Triangle);
    ~GPUStreamGenerator();
    GPUStreamGenerator(const GPUStreamGenerator&) = delete;
    GPUStreamGenerator& operator=(const GPUStreamGenerator&) = delete;
    GPUStreamGenerator(GPUStreamGenerator&& other) noexcept;
    GPUStreamGenerator& operator=(GPUStreamGenerator&& other) noexcept;

    StreamPrimitive primitive() const { return primitive_; }
    void setPrimitive(StreamPrimitive p) { primitive_ = p; }

    // Sets the viewport to `rect` and draws. The bound program must use generator.vert, whose
    // uniform gpu_depth places the primitive in depth (early-Z masking draws at 0.5).
    void draw(const StreamRect& rect) const;

  private:
    StreamPrimitive primitive_;
    GLuint vertexArray_ = 0;
};

}  // namespace gpurt
