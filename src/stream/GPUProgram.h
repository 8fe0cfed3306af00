// A linked GL program of the stream generator's vertex shader and one fragment kernel from glsl/,
// assembled by ShaderLibrary. Move-only; frees its GL names on destruction.
#pragma once

#include "stream/GL.h"
#include "stream/ShaderLibrary.h"

#include <string>
#include <unordered_map>

namespace gpurt {

class GPUProgram {
  public:
    // Throws KernelBuildError with the compiler's log mapped to glsl/FILE:LINE.
    GPUProgram(const std::string& name, const std::string& fragmentPath,
               const std::string& preamble = {}, const std::string& epilogue = {});
    ~GPUProgram();
    GPUProgram(const GPUProgram&) = delete;
    GPUProgram& operator=(const GPUProgram&) = delete;
    GPUProgram(GPUProgram&& other) noexcept;
    GPUProgram& operator=(GPUProgram&& other) noexcept;

    GLuint id() const { return program_; }
    // -1 when the program has no active uniform of that name (the GL rule: setting it is a no-op).
    GLint uniformLocation(const std::string& name) const;
    const AssembledShader& fragment() const { return fragment_; }
    const AssembledShader& vertex() const { return vertex_; }

  private:
    GLuint program_ = 0;
    AssembledShader vertex_;
    AssembledShader fragment_;
    mutable std::unordered_map<std::string, GLint> locations_;
};

}  // namespace gpurt
