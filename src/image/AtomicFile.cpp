// Atomic output through mkstemp and rename (POSIX rename replaces the target in one step).
#include "image/AtomicFile.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include "image/InputError.h"

namespace gpurt {
namespace {

std::string errnoText() { return std::strerror(errno); }

// The absolute, normalised form of a target, to recognise one named twice.
std::string targetKey(const std::filesystem::path& path) {
    std::error_code ec;
    const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
    return (ec ? path : absolute).lexically_normal().string();
}

}  // namespace

void checkOutputPath(const std::filesystem::path& path) {
    const std::string target = path.string();
    std::error_code ec;
    if (path.empty()) throw InputError("output file name is empty");
    if (std::filesystem::is_directory(path, ec))
        throw InputError(target + ": is a folder, not a file name");
    const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : ".";
    if (!std::filesystem::is_directory(folder, ec))
        throw InputError(target + ": cannot create file (no folder " + folder.string() + ")");
}

std::string lowerExtension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

void checkOutputPaths(const std::vector<std::filesystem::path>& paths) {
    for (size_t i = 0; i < paths.size(); ++i) {
        checkOutputPath(paths[i]);
        for (size_t j = 0; j < i; ++j)
            if (targetKey(paths[j]) == targetKey(paths[i]))
                throw InputError(paths[i].string() + ": named twice as an output file");
    }
}

AtomicFileSet::~AtomicFileSet() {
    for (const auto& [temp, target] : staged_) unlink(temp.c_str());
}

void AtomicFileSet::add(const std::filesystem::path& path,
                        const std::function<void(std::FILE*)>& write) {
    const std::string target = path.string();
    checkOutputPath(path);
    const std::string key = targetKey(path);
    for (const auto& [temp, other] : staged_)
        if (targetKey(other) == key) throw InputError(target + ": named twice as an output file");
    std::string temp = target + ".tmp-XXXXXX";
    const int fd = mkstemp(temp.data());
    if (fd < 0) throw InputError(target + ": cannot create file (" + errnoText() + ")");
    // From here the destructor removes the temporary file unless commit() renamed it.
    staged_.emplace_back(temp, target);
    // mkstemp creates the file 0600; an output file should be readable like any other file.
    fchmod(fd, 0644);
    std::FILE* file = fdopen(fd, "wb");
    if (!file) {
        const std::string why = errnoText();
        close(fd);
        throw InputError(target + ": cannot write file (" + why + ")");
    }
    try {
        write(file);
        if (std::fflush(file) != 0 || std::ferror(file))
            throw InputError(target + ": cannot write file (" + errnoText() + ")");
    } catch (...) {
        std::fclose(file);
        throw;
    }
    if (std::fclose(file) != 0)
        throw InputError(target + ": cannot write file (" + errnoText() + ")");
}

void AtomicFileSet::commit() {
    while (!staged_.empty()) {
        const auto& [temp, target] = staged_.front();
        if (std::rename(temp.c_str(), target.c_str()) != 0)
            throw InputError(target + ": cannot write file (" + errnoText() + ")");
        staged_.erase(staged_.begin());
    }
}

void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::FILE*)>& write) {
    AtomicFileSet file;
    file.add(path, write);
    file.commit();
}

}  // namespace gpurt
