// glTF documents written by the tests (GltfLoaderTest, GltfGeometryTest): one buffer, its views
// and accessors, as a .gltf with the buffer in a data URI or as a .glb with it in the BIN chunk.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace gpurt::test {

inline std::string base64(const std::string& bytes) {
    static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 2]));
        out += kDigits[(v >> 18) & 63];
        out += kDigits[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? kDigits[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? kDigits[v & 63] : '=';
    }
    return out;
}

// A glTF document under construction: one buffer, its views and accessors.
struct Gltf {
    std::string bin;
    std::vector<std::string> views, accessors;

    // A buffer view of raw bytes.
    int view(const std::string& bytes, int stride = 0) {
        while (bin.size() % 4) bin += '\0';
        const size_t offset = bin.size();
        bin += bytes;
        views.push_back("{\"buffer\": 0, \"byteOffset\": " + std::to_string(offset) +
                        ", \"byteLength\": " + std::to_string(bytes.size()) +
                        (stride ? ", \"byteStride\": " + std::to_string(stride) : "") + "}");
        return int(views.size() - 1);
    }
    template <typename T>
    int view(const std::vector<T>& values, int stride = 0) {
        return view(
            std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T)),
            stride);
    }
    // An accessor of `view` (-1: none, as a Draco-compressed primitive's).
    int accessor(int view, int componentType, size_t count, const char* type,
                 const std::string& extra = "") {
        accessors.push_back(
            "{" + (view >= 0 ? "\"bufferView\": " + std::to_string(view) + ", " : std::string()) +
            "\"componentType\": " + std::to_string(componentType) +
            ", \"count\": " + std::to_string(count) + ", \"type\": \"" + type + "\"" + extra + "}");
        return int(accessors.size() - 1);
    }
    int positions(const std::vector<float>& xyz) {
        return accessor(view(xyz), 5126, xyz.size() / 3, "VEC3");
    }
    template <typename T>
    int indices(const std::vector<T>& i, int componentType) {
        return accessor(view(i), componentType, i.size(), "SCALAR");
    }

    static std::string list(const std::vector<std::string>& items) {
        std::string out;
        for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
        return "[" + out + "]";
    }
    // The document: `rest` holds the other top-level members ("nodes", "meshes", ...).
    std::string json(const std::string& rest) const {
        return "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [{\"byteLength\": " +
               std::to_string(bin.size()) + ", \"uri\": \"data:application/octet-stream;base64," +
               base64(bin) + "\"}], \"bufferViews\": " + list(views) +
               ", \"accessors\": " + list(accessors) + ", " + rest + "}";
    }
    // The same as a binary glTF: the header, the JSON chunk (padded with spaces) and the BIN chunk.
    std::string glb(const std::string& rest) const {
        std::string text = "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [{\"byteLength\": " +
                           std::to_string(bin.size()) + "}], \"bufferViews\": " + list(views) +
                           ", \"accessors\": " + list(accessors) + ", " + rest + "}";
        while (text.size() % 4) text += ' ';
        std::string data = bin;
        while (data.size() % 4) data += '\0';
        auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
        return "glTF" + u32(2) + u32(uint32_t(12 + 8 + text.size() + 8 + data.size())) +
               u32(uint32_t(text.size())) + "JSON" + text + u32(uint32_t(data.size())) +
               std::string("BIN\0", 4) + data;
    }
};

}  // namespace gpurt::test
