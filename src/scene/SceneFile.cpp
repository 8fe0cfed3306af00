#include "scene/SceneFile.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>

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

namespace {

// Reads the whole of `path` into `out` (resized by `resize`): a regular file in one read of its
// size, a pipe in pieces.
template <typename Bytes, typename Resize>
void readWhole(const std::filesystem::path& path, Bytes& out, const Resize& resize) {
    checkSceneFile(path);
    const FileLoc file{path.string()};
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) failAt(file, std::string("cannot read (") + std::strerror(errno) + ")");
    std::error_code ec;
    size_t size = 0;  // a pipe's is unknown
    if (std::filesystem::is_regular_file(path, ec)) {
        const uintmax_t fileSize = std::filesystem::file_size(path, ec);
        if (!ec) size = size_t(fileSize);
    }
    size_t got = 0;
    if (size > 0) {
        resize(out, size_t(size));
        got = std::fread(out.data(), 1, size, f);
    }
    if (got == size) {  // a pipe (size 0) or a file that grew: read on in pieces
        char piece[1 << 16];
        for (size_t n; (n = std::fread(piece, 1, sizeof piece, f)) > 0; got += n) {
            resize(out, got + n);
            std::memcpy(out.data() + got, piece, n);
        }
    }
    const bool bad = std::ferror(f);
    std::fclose(f);
    if (bad) failAt(file, "cannot read");
    resize(out, got);
}

}  // namespace

std::string readSceneFile(const std::filesystem::path& path) {
    std::string bytes;
    readWhole(path, bytes, [](std::string& s, size_t n) { s.resize(n); });
    return bytes;
}

LargeArray<char> readSceneBytes(const std::filesystem::path& path) {
    LargeArray<char> bytes;
    readWhole(path, bytes, [](LargeArray<char>& s, size_t n) { s.resize(n); });
    return bytes;
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
