#include "stream/GPUProgram.h"

#include "stream/StreamErrors.h"

#include <utility>

namespace gpurt {

namespace {

std::string shaderLog(GLuint shader) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(size_t(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, GLsizei(log.size()), nullptr, log.data());
    log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
    return log;
}

GLuint compile(GLenum stage, const std::string& kernelName, const AssembledShader& shader) {
    GLuint id = glCreateShader(stage);
    const char* text = shader.source.c_str();
    glShaderSource(id, 1, &text, nullptr);
    glCompileShader(id);
    GLint ok = 0;
    glGetShaderiv(id, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        std::string log = shader.mapLog(shaderLog(id));
        glDeleteShader(id);
        while (!log.empty() && (log.back() == '\n' || log.back() == ' ')) log.pop_back();
        throw KernelBuildError("kernel '" + kernelName + "': " + log);
    }
    return id;
}

}  // namespace

GPUProgram::GPUProgram(const std::string& name, const std::string& fragmentPath,
                       const std::string& preamble, const std::string& epilogue) {
    const ShaderLibrary& library = ShaderLibrary::global();
    vertex_ = library.assemble("stream/generator.vert");
    fragment_ = library.assemble(fragmentPath, preamble, epilogue);
    GLuint vs = compile(GL_VERTEX_SHADER, name, vertex_);
    GLuint fs = 0;
    try {
        fs = compile(GL_FRAGMENT_SHADER, name, fragment_);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    program_ = glCreateProgram();
    glAttachShader(program_, vs);
    glAttachShader(program_, fs);
    glLinkProgram(program_);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(program_, GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(program_, GL_INFO_LOG_LENGTH, &length);
        std::string log(size_t(std::max(length, 1)), '\0');
        glGetProgramInfoLog(program_, GLsizei(log.size()), nullptr, log.data());
        glDeleteProgram(program_);
        program_ = 0;
        throw KernelBuildError("kernel '" + name + "' (glsl/" + fragmentPath +
                               "): link failed: " + fragment_.mapLog(log.c_str()));
    }
    glObjectLabel(GL_PROGRAM, program_, GLsizei(name.size()), name.data());
}

GPUProgram::~GPUProgram() {
    if (program_) glDeleteProgram(program_);
}

GPUProgram::GPUProgram(GPUProgram&& other) noexcept
    : program_(std::exchange(other.program_, 0)),
      vertex_(std::move(other.vertex_)),
      fragment_(std::move(other.fragment_)),
      locations_(std::move(other.locations_)) {}

GPUProgram& GPUProgram::operator=(GPUProgram&& other) noexcept {
    if (this != &other) {
        if (program_) glDeleteProgram(program_);
        program_ = std::exchange(other.program_, 0);
        vertex_ = std::move(other.vertex_);
        fragment_ = std::move(other.fragment_);
        locations_ = std::move(other.locations_);
    }
    return *this;
}

GLint GPUProgram::uniformLocation(const std::string& name) const {
    auto it = locations_.find(name);
    if (it != locations_.end()) return it->second;
    const GLint location = glGetUniformLocation(program_, name.c_str());
    locations_.emplace(name, location);
    return location;
}

}  // namespace gpurt
