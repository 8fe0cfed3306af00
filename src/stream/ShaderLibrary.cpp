#include "stream/ShaderLibrary.h"

#include "stream/StreamErrors.h"

#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace gpurt {

ShaderLibrary& ShaderLibrary::global() {
    static ShaderLibrary library;
    return library;
}

void ShaderLibrary::setDirectory(const std::filesystem::path& dir) { directory_ = dir; }

bool ShaderLibrary::exists(const std::string& path) const {
    if (!directory_.empty()) return std::filesystem::is_regular_file(directory_ / path);
    for (const EmbeddedFile& f : embeddedGlslFiles())
        if (path == f.path) return true;
    return false;
}

std::string ShaderLibrary::read(const std::string& path) const {
    if (!directory_.empty()) {
        std::ifstream in(directory_ / path, std::ios::binary);
        if (!in) throw KernelBuildError("glsl/" + path + ": no such file in " + directory_.string());
        std::ostringstream text;
        text << in.rdbuf();
        return text.str();
    }
    for (const EmbeddedFile& f : embeddedGlslFiles())
        if (path == f.path) return f.text;
    throw KernelBuildError("glsl/" + path + ": no such embedded GLSL file");
}

namespace {

std::string parentOf(const std::string& path) {
    const size_t slash = path.rfind('/');
    return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

// Normalizes "a/b/../c.glsl" to "a/c.glsl".
std::string normalize(const std::string& path) {
    return std::filesystem::path(path).lexically_normal().generic_string();
}

struct Assembler {
    const ShaderLibrary& library;
    AssembledShader& out;
    std::set<std::string> included;

    void append(const std::string& path, const std::string& includedFrom, int includeLine) {
        if (!included.insert(path).second) return;  // each file once (#pragma once semantics)
        if (!library.exists(path)) {
            if (includedFrom.empty()) throw KernelBuildError("glsl/" + path + ": no such GLSL file");
            throw KernelBuildError("glsl/" + includedFrom + ":" + std::to_string(includeLine) +
                                   ": #include \"" + path + "\": no such file");
        }
        const std::string text = library.read(path);
        const int index = int(out.names.size());
        out.names.push_back("glsl/" + path);
        out.source += "#line 1 " + std::to_string(index) + "\n";

        std::istringstream lines(text);
        std::string line;
        static const std::regex includeRe(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
        static const std::regex versionRe(R"(^\s*#\s*version\b.*$)");
        for (int number = 1; std::getline(lines, line); ++number) {
            std::smatch match;
            if (std::regex_match(line, match, includeRe)) {
                std::string target = normalize(parentOf(path) + match[1].str());
                if (!library.exists(target)) target = normalize(match[1].str());
                append(target, path, number);
                out.source += "#line " + std::to_string(number + 1) + " " +
                              std::to_string(index) + "\n";
            } else if (std::regex_match(line, versionRe)) {
                out.source += "\n";  // the assembler writes #version itself
            } else {
                out.source += line + "\n";
            }
        }
    }
};

}  // namespace

AssembledShader ShaderLibrary::assemble(const std::string& path, const std::string& preamble,
                                        const std::string& epilogue) const {
    AssembledShader shader;
    shader.source = "#version 450 core\n";
    if (!preamble.empty()) {
        shader.names.push_back("<preamble of " + path + ">");
        shader.source += "#line 1 0\n" + preamble;
        if (preamble.back() != '\n') shader.source += "\n";
    }
    Assembler assembler{*this, shader, {}};
    assembler.append(normalize(path), {}, 0);
    if (!epilogue.empty()) {
        shader.source += "#line 1 " + std::to_string(shader.names.size()) + "\n" + epilogue + "\n";
        shader.names.push_back("<epilogue of " + path + ">");
    }
    return shader;
}

std::string AssembledShader::mapLog(const std::string& log) const {
    // Mesa "0:12(3):", NVIDIA "0(12) :", glslang "ERROR: 0:12:".
    static const std::regex locationRe(R"((^|[^0-9.])(\d+)(:(\d+)|\((\d+)\)))");
    std::string result;
    auto begin = log.cbegin();
    std::smatch m;
    while (std::regex_search(begin, log.cend(), m, locationRe,
                             begin == log.cbegin() ? std::regex_constants::match_default
                                                   : std::regex_constants::match_prev_avail)) {
        result.append(begin, m[0].first);
        const size_t index = std::stoul(m[2].str());
        const std::string line = m[4].matched ? m[4].str() : m[5].str();
        if (index < names.size())
            result += m[1].str() + names[index] + ":" + line;
        else
            result += m[0].str();
        begin = m[0].second;
    }
    result.append(begin, log.cend());
    return result;
}

}  // namespace gpurt
