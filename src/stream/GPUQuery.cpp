#include "stream/GPUQuery.h"

#include <utility>

namespace gpurt {

GPUQuery::GPUQuery(GLenum target) : target_(target) { glCreateQueries(target, 1, &id_); }

GPUQuery::~GPUQuery() {
    if (id_) glDeleteQueries(1, &id_);
}

GPUQuery::GPUQuery(GPUQuery&& other) noexcept
    : target_(other.target_), id_(std::exchange(other.id_, 0)) {}

GPUQuery& GPUQuery::operator=(GPUQuery&& other) noexcept {
    if (this != &other) {
        if (id_) glDeleteQueries(1, &id_);
        target_ = other.target_;
        id_ = std::exchange(other.id_, 0);
    }
    return *this;
}

void GPUQuery::begin() { glBeginQuery(target_, id_); }
void GPUQuery::end() { glEndQuery(target_); }

uint64_t GPUQuery::result() const {
    GLuint64 value = 0;
    glGetQueryObjectui64v(id_, GL_QUERY_RESULT, &value);
    return value;
}

bool GPUQuery::available() const {
    GLuint ready = 0;
    glGetQueryObjectuiv(id_, GL_QUERY_RESULT_AVAILABLE, &ready);
    return ready != 0;
}

}  // namespace gpurt
