// GLSL sources: embedded into the binary at build time (cmake/EmbedGlsl.cmake), or read from a
// folder given with --glsl-dir. Assembles a kernel from its file and #include'd files, with #line
// directives so that compile errors name file:line.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace gpurt {

struct EmbeddedFile {
    const char* path;  // relative to glsl/, e.g. "common/stream.glsl"
    const char* text;
};
// Generated at build time.
const std::vector<EmbeddedFile>& embeddedGlslFiles();

// One assembled shader: the source, and the name of each GLSL source-string number used in its
// #line directives (names[i] is the file that "#line N i" refers to).
struct AssembledShader {
    std::string source;
    std::vector<std::string> names;

    // Rewrites a compiler log ("0:12(3): error", "0(12) : error", "ERROR: 0:12:") so that each
    // source-string number reads as its file name: "glsl/test/broken.frag:12(3): error".
    std::string mapLog(const std::string& log) const;
};

class ShaderLibrary {
  public:
    // The process-wide library (embedded sources unless setDirectory was called).
    static ShaderLibrary& global();

    // Reads sources from `dir` instead of the embedded copies; an empty path goes back to them.
    void setDirectory(const std::filesystem::path& dir);
    const std::filesystem::path& directory() const { return directory_; }

    // The text of `path` (relative to glsl/); throws KernelBuildError when there is none.
    std::string read(const std::string& path) const;
    bool exists(const std::string& path) const;

    // "#version 450 core", then `preamble` (defines of a variant), then `path` with its
    // #include "file" lines expanded (each file once), with #line mapping throughout.
    // `epilogue` is appended at the end (used to wrap main for early-exit masking).
    AssembledShader assemble(const std::string& path, const std::string& preamble = {},
                             const std::string& epilogue = {}) const;

  private:
    std::filesystem::path directory_;
};

}  // namespace gpurt
