#include "scene/SceneFile.h"

#include <cctype>
#include <cstdio>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "image/AtomicFile.h"
#include "image/InputError.h"

#include "scene/ObjLoader.h"
#include "scene/PlyLoader.h"

namespace gpurt {

bool isReadableKind(const std::filesystem::file_status& status) {
    return std::filesystem::is_regular_file(status) || std::filesystem::is_fifo(status);
}

void checkSceneFile(const std::filesystem::path& path) {
    const FileLoc file{path.string()};
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (!std::filesystem::exists(status)) failAt(file, "no such file");
    if (std::filesystem::is_directory(status)) failAt(file, "is a directory, not a scene file");
    if (!isReadableKind(status)) failAt(file, "is a device or socket, not a scene file");
}

std::string readSceneFile(const std::filesystem::path& path) {
    checkSceneFile(path);
    const FileLoc file{path.string()};
    std::ifstream in(path, std::ios::binary);
    if (!in) failAt(file, std::string("cannot read (") + std::strerror(errno) + ")");
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (in.bad()) failAt(file, "cannot read");
    return buffer.str();
}

std::string printable(std::string_view text) {
    std::string out;
    for (unsigned char c : text) {
        if (c >= 0x20 && c < 0x7f) {
            out += static_cast<char>(c);
        } else {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02x", c);
            out += hex;
        }
    }
    return out;
}

Scene loadMesh(const std::filesystem::path& path) {
    const std::string ext = lowerExtension(path);
    char head[5] = {};
    std::ifstream in(path, std::ios::binary);
    in.read(head, sizeof head);
    if (ext == ".ply" || looksLikePly(std::string(head, size_t(in.gcount())))) return loadPly(path);
    return loadObj(path);
}

}  // namespace gpurt
