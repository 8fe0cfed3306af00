#include "scene/GltfMeshopt.h"

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <map>
#include <string_view>
#include <vector>

#include "image/InputError.h"
#include "scene/GltfBytes.h"
#include "scene/SceneFile.h"

namespace gpurt {

namespace {

using nlohmann::json;

constexpr char kExtension[] = "EXT_meshopt_compression";

std::string base64(std::string_view bytes) {
    static const char table[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const uint32_t a = uint8_t(bytes[i]), b = i + 1 < bytes.size() ? uint8_t(bytes[i + 1]) : 0u,
                       c = i + 2 < bytes.size() ? uint8_t(bytes[i + 2]) : 0u;
        const uint32_t n = a << 16 | b << 8 | c;
        out += table[n >> 18 & 63];
        out += table[n >> 12 & 63];
        out += i + 1 < bytes.size() ? table[n >> 6 & 63] : '=';
        out += i + 2 < bytes.size() ? table[n & 63] : '=';
    }
    return out;
}

// -1 for a byte outside the alphabet.
int base64Value(char c) {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
}

int hexValue(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

class Decoder {
  public:
    Decoder(const std::string& bytes, const std::string& name, const std::filesystem::path& folder)
        : bytes_(bytes), file_{name}, folder_(folder) {}

    // False when the file does not use the extension (then nothing else is done).
    bool parse() {
        if (bytes_.find(kExtension) == std::string::npos || !splitGltf(bytes_, parts_)) return false;
        hasBin_ = glbBinChunk(parts_, bin_);
        root_ = json::parse(parts_.json, nullptr, false);
        return root_.is_object();  // tinygltf names what is wrong with a file that is not JSON
    }

    std::string decoded() {
        json& views = root_["bufferViews"];
        if (!views.is_array()) return bytes_;
        std::string blob;
        for (size_t v = 0; v < views.size(); ++v) {
            json& view = views[v];
            if (!view.is_object() || !view.contains("extensions") || !view["extensions"].is_object()) continue;
            json& extensions = view["extensions"];
            if (!extensions.contains(kExtension)) continue;
            const std::string at = "bufferView " + std::to_string(v) + ": " + kExtension;
            const std::string data = decode(extensions[kExtension], at);
            while (blob.size() % 16 != 0) blob += '\0';
            view["buffer"] = root_["buffers"].size();  // the buffer appended below
            view["byteOffset"] = blob.size();
            view["byteLength"] = data.size();
            extensions.erase(kExtension);
            if (extensions.empty()) view.erase("extensions");
            blob += data;
        }
        // Fallback buffers hold no data (tinygltf would refuse them): empty placeholders now.
        for (json& buffer : root_["buffers"])
            if (buffer.is_object() && buffer.contains("extensions") && buffer["extensions"].contains(kExtension) &&
                !buffer.contains("uri")) {
                buffer = json{{"byteLength", 4}, {"uri", "data:application/octet-stream;base64,AAAAAA=="}};
            }
        if (blob.empty()) blob.assign(4, '\0');
        root_["buffers"].push_back(json{{"byteLength", blob.size()}, {"uri", "data:application/octet-stream;base64," + base64(blob)}});
        for (const char* list : {"extensionsUsed", "extensionsRequired"})
            if (root_.contains(list) && root_[list].is_array()) {
                json kept = json::array();
                for (const json& e : root_[list])
                    if (e != kExtension) kept.push_back(e);
                root_[list] = kept;
            }
        return joinGltf(parts_, root_.dump(), bytes_);
    }

  private:
    uint64_t unsignedField(const json& object, const char* key, const std::string& at, bool required, uint64_t fallback = 0) const {
        if (!object.contains(key)) {
            if (required) failAt(file_, at + ": " + key + " is missing");
            return fallback;
        }
        const json& v = object[key];
        if (!v.is_number_unsigned()) failAt(file_, at + ": " + key + " is not a non-negative integer");
        return v.get<uint64_t>();
    }

    // The bytes of buffer `index`: a GLB's binary chunk, a data URI, or a file beside the glTF.
    const std::string& buffer(uint64_t index, const std::string& at) {
        const json& buffers = root_["buffers"];
        if (!buffers.is_array() || index >= buffers.size()) failAt(file_, at + ": buffer " + std::to_string(index) + " does not exist");
        if (const auto cached = buffers_.find(index); cached != buffers_.end()) return cached->second;
        const json& b = buffers[index];
        std::string data;
        const std::string uri = b.is_object() && b.contains("uri") && b["uri"].is_string() ? b["uri"].get<std::string>() : "";
        if (uri.empty()) {
            if (!parts_.glb || index != 0 || !hasBin_) failAt(file_, at + ": buffer " + std::to_string(index) + " has no data");
            data = bin_;
        } else if (uri.rfind("data:", 0) == 0) {
            const size_t comma = uri.find(',');
            if (comma == std::string::npos || comma < 7 || uri.compare(comma - 7, 7, ";base64") != 0)
                failAt(file_, at + ": buffer " + std::to_string(index) + ": not a base64 data URI");
            uint32_t bits = 0;
            int count = 0;
            for (size_t i = comma + 1; i < uri.size() && uri[i] != '='; ++i) {
                const int value = base64Value(uri[i]);
                if (value < 0) failAt(file_, at + ": buffer " + std::to_string(index) + ": not base64");
                bits = bits << 6 | uint32_t(value);
                if ((count += 6) >= 8) {
                    count -= 8;
                    data += char(bits >> count & 0xff);
                }
            }
        } else {
            std::string path;  // percent-decoded, as tinygltf reads it
            for (size_t i = 0; i < uri.size(); ++i) {
                const int high = i + 2 < uri.size() ? hexValue(uri[i + 1]) : -1, low = high >= 0 ? hexValue(uri[i + 2]) : -1;
                if (uri[i] == '%' && low >= 0) {
                    path += char(high * 16 + low);
                    i += 2;
                } else {
                    path += uri[i];
                }
            }
            data = readSceneFile(folder_ / path);
        }
        return buffers_[index] = std::move(data);
    }

    // One view's data decoded (mode ATTRIBUTES, TRIANGLES or INDICES; filter NONE, OCTAHEDRAL,
    // QUATERNION or EXPONENTIAL), count x byteStride bytes.
    std::string decode(const json& e, const std::string& at) {
        if (!e.is_object()) failAt(file_, at + " is not an object");
        const uint64_t index = unsignedField(e, "buffer", at, true), offset = unsignedField(e, "byteOffset", at, false),
                       length = unsignedField(e, "byteLength", at, true), stride = unsignedField(e, "byteStride", at, true),
                       count = unsignedField(e, "count", at, true);
        const std::string mode = e.contains("mode") && e["mode"].is_string() ? e["mode"].get<std::string>() : "";
        const std::string filter = e.contains("filter") && e["filter"].is_string() ? e["filter"].get<std::string>() : "NONE";
        const std::string& source = buffer(index, at);
        if (offset > source.size() || length > source.size() - offset)
            failAt(file_, at + ": bytes " + std::to_string(offset) + " + " + std::to_string(length) + " outside buffer " +
                              std::to_string(index) + " of " + std::to_string(source.size()));
        if (count > (uint64_t(1) << 28) || stride == 0 || stride > 256)
            failAt(file_, at + ": count " + std::to_string(count) + " or byteStride " + std::to_string(stride) + " out of range");
        std::string out(size_t(count * stride), '\0');
        const auto* src = reinterpret_cast<const unsigned char*>(source.data() + offset);
        int result = -1;
        if (mode == "ATTRIBUTES") {
            if (stride % 4 != 0) failAt(file_, at + ": ATTRIBUTES need a byteStride that is a multiple of 4");
            result = meshopt_decodeVertexBuffer(out.data(), size_t(count), size_t(stride), src, size_t(length));
        } else if (mode == "TRIANGLES" || mode == "INDICES") {
            if (stride != 2 && stride != 4) failAt(file_, at + ": " + mode + " need a byteStride of 2 or 4");
            if (mode == "TRIANGLES" && count % 3 != 0) failAt(file_, at + ": TRIANGLES need a count that is a multiple of 3");
            result = mode == "TRIANGLES"
                         ? meshopt_decodeIndexBuffer(out.data(), size_t(count), size_t(stride), src, size_t(length))
                         : meshopt_decodeIndexSequence(out.data(), size_t(count), size_t(stride), src, size_t(length));
        } else {
            failAt(file_, at + ": mode '" + mode + "' (ATTRIBUTES, TRIANGLES or INDICES)");
        }
        if (result != 0) failAt(file_, at + ": the data does not decode (meshoptimizer " + std::to_string(result) + ")");
        if (filter != "NONE") {
            if (mode != "ATTRIBUTES") failAt(file_, at + ": filter " + filter + " on " + mode);
            if (filter == "OCTAHEDRAL" && (stride == 4 || stride == 8))
                meshopt_decodeFilterOct(out.data(), size_t(count), size_t(stride));
            else if (filter == "QUATERNION" && stride == 8)
                meshopt_decodeFilterQuat(out.data(), size_t(count), size_t(stride));
            else if (filter == "EXPONENTIAL" && stride % 4 == 0)
                meshopt_decodeFilterExp(out.data(), size_t(count), size_t(stride));
            else
                failAt(file_, at + ": filter '" + filter + "' with byteStride " + std::to_string(stride));
        }
        return out;
    }

    const std::string& bytes_;
    FileLoc file_;
    std::filesystem::path folder_;
    GltfParts parts_;
    bool hasBin_ = false;
    std::string bin_;
    json root_;
    std::map<uint64_t, std::string> buffers_;
};

}  // namespace

std::string withMeshoptDecoded(const std::string& bytes, const std::string& name, const std::filesystem::path& folder) {
    Decoder decoder(bytes, name, folder);
    if (!decoder.parse()) return bytes;
    try {
        return decoder.decoded();
    } catch (const nlohmann::json::exception& e) {  // a field of the wrong type where the extension looks
        failAt(FileLoc{name}, std::string(kExtension) + ": " + e.what());
    }
}

}  // namespace gpurt
