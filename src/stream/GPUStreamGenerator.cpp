#include "stream/GPUStreamGenerator.h"

#include <utility>

namespace gpurt {

GPUStreamGenerator::GPUStreamGenerator(StreamPrimitive primitive) : primitive_(primitive) {
    glCreateVertexArrays(1, &vertexArray_);  // core profile draws need a bound VAO, even empty
}

GPUStreamGenerator::~GPUStreamGenerator() {
    if (vertexArray_) glDeleteVertexArrays(1, &vertexArray_);
}

GPUStreamGenerator::GPUStreamGenerator(GPUStreamGenerator&& other) noexcept
    : primitive_(other.primitive_), vertexArray_(std::exchange(other.vertexArray_, 0)) {}

GPUStreamGenerator& GPUStreamGenerator::operator=(GPUStreamGenerator&& other) noexcept {
    if (this != &other) {
        if (vertexArray_) glDeleteVertexArrays(1, &vertexArray_);
        primitive_ = other.primitive_;
        vertexArray_ = std::exchange(other.vertexArray_, 0);
    }
    return *this;
}

void GPUStreamGenerator::draw(const StreamRect& rect) const {
    glViewport(rect.x, rect.y, rect.width, rect.height);
    glBindVertexArray(vertexArray_);
    if (primitive_ == StreamPrimitive::Triangle)
        glDrawArrays(GL_TRIANGLES, 0, 3);
    else
        glDrawArrays(GL_TRIANGLE_STRIP, 4, 4);  // vertex ids 4..7 select the quad's corners
}

}  // namespace gpurt
