#include "scene/GltfBytes.h"

#include <cstdint>
#include <cstring>

namespace gpurt {

namespace {

constexpr uint32_t kJsonChunk = 0x4E4F534A, kBinChunk = 0x004E4942;  // "JSON", "BIN\0"

uint32_t readU32(const std::string& bytes, size_t at) {
    uint32_t v;
    std::memcpy(&v, bytes.data() + at, 4);
    return v;
}

void appendU32(std::string& out, uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); }

}  // namespace

// GLB: a 12-byte header (magic, version, total length), then the JSON chunk (length, type, text),
// then the rest (the BIN chunk).
bool splitGltf(const std::string& bytes, GltfParts& parts) {
    parts.glb = bytes.compare(0, 4, "glTF") == 0;
    if (!parts.glb) {
        parts.json = bytes;
        return true;
    }
    if (bytes.size() < 20 || readU32(bytes, 16) != kJsonChunk) return false;
    const size_t length = readU32(bytes, 12);
    if (length > bytes.size() - 20) return false;
    parts.json = bytes.substr(20, length);
    parts.rest = bytes.substr(20 + length);
    return true;
}

std::string joinGltf(const GltfParts& parts, std::string json, const std::string& bytes) {
    if (!parts.glb) return json;
    while (json.size() % 4) json += ' ';  // chunks are padded to 4 bytes, JSON with spaces
    if (20 + json.size() + parts.rest.size() > UINT32_MAX) return bytes;
    std::string glb = bytes.substr(0, 8);
    appendU32(glb, uint32_t(20 + json.size() + parts.rest.size()));
    appendU32(glb, uint32_t(json.size()));
    appendU32(glb, kJsonChunk);
    return glb + json + parts.rest;
}

bool glbBinChunk(const GltfParts& parts, std::string& bin) {
    if (!parts.glb || parts.rest.size() < 8 || readU32(parts.rest, 4) != kBinChunk) return false;
    const size_t length = readU32(parts.rest, 0);
    if (length > parts.rest.size() - 8) return false;
    bin = parts.rest.substr(8, length);
    return true;
}

}  // namespace gpurt
