#include "scene/SceneFile.h"

#include <cctype>
#include <cstdio>
#include <fstream>

#include "scene/ObjLoader.h"
#include "scene/PlyLoader.h"

namespace gpurt {

bool isReadableKind(const std::filesystem::file_status& status) {
    return std::filesystem::is_regular_file(status) || std::filesystem::is_fifo(status);
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
    std::string ext = path.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    char head[5] = {};
    std::ifstream in(path, std::ios::binary);
    in.read(head, sizeof head);
    if (ext == ".ply" || looksLikePly(std::string(head, size_t(in.gcount())))) return loadPly(path);
    return loadObj(path);
}

}  // namespace gpurt
