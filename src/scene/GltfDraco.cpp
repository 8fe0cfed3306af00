// KHR_draco_mesh_compression: the JSON rewrite that lets tinygltf read such files, and the
// decoding of one primitive's Draco data, every size and index checked before it is used.
#include "scene/GltfDraco.h"
#include "scene/GltfBytes.h"

#include <cstring>
#include <exception>
#include <new>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>
#include <nlohmann/json.hpp>

namespace gpurt {
namespace {

constexpr char kDraco[] = "KHR_draco_mesh_compression";

// The JSON text with "indices" taken out of the Draco primitives; false when there was none to
// take out or the text is no JSON object.
bool rewriteJson(const std::string& text, std::string& out) {
    nlohmann::json document = nlohmann::json::parse(text, nullptr, false);
    if (document.is_discarded() || !document.is_object()) return false;
    const auto meshes = document.find("meshes");
    if (meshes == document.end() || !meshes->is_array()) return false;
    bool changed = false;
    for (nlohmann::json& mesh : *meshes) {
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
            continue;
        for (nlohmann::json& primitive : mesh["primitives"]) {
            if (!primitive.is_object() || !primitive.contains("indices")) continue;
            const auto extensions = primitive.find("extensions");
            if (extensions == primitive.end() || !extensions->is_object() ||
                !extensions->contains(kDraco))
                continue;
            primitive.erase("indices");
            changed = true;
        }
    }
    // (replace: a string that is not UTF-8 can never make dump throw; parse has refused those
    // anyway)
    if (changed) out = document.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    return changed;
}

// Draco's stored component types, as doubles.
bool componentOf(draco::DataType type, const uint8_t* p, double& out) {
    switch (type) {
        case draco::DT_INT8: {
            int8_t v;
            std::memcpy(&v, p, 1);
            out = v;
            return true;
        }
        case draco::DT_UINT8:
            out = p[0];
            return true;
        case draco::DT_INT16: {
            int16_t v;
            std::memcpy(&v, p, 2);
            out = v;
            return true;
        }
        case draco::DT_UINT16: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            out = v;
            return true;
        }
        case draco::DT_INT32: {
            int32_t v;
            std::memcpy(&v, p, 4);
            out = v;
            return true;
        }
        case draco::DT_UINT32: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            out = v;
            return true;
        }
        case draco::DT_FLOAT32: {
            float v;
            std::memcpy(&v, p, 4);
            out = v;
            return true;
        }
        case draco::DT_FLOAT64: {
            double v;
            std::memcpy(&v, p, 8);
            out = v;
            return true;
        }
        default:
            return false;
    }
}

}  // namespace

std::string withoutDracoIndices(const std::string& bytes) {
    if (bytes.find(kDraco) == std::string::npos) return bytes;
    GltfParts parts;
    std::string json;
    if (!splitGltf(bytes, parts) || !rewriteJson(parts.json, json)) return bytes;
    return joinGltf(parts, json, bytes);
}

DracoMesh decodeDracoMesh(const unsigned char* data, size_t size, uint64_t maxPoints,
                          const FileLoc& file, const std::string& at) {
    auto fail = [&](const std::string& what) { failAt(file, at + ": Draco data " + what); };
    DracoMesh out;
    try {
        draco::DecoderBuffer buffer;
        buffer.Init(reinterpret_cast<const char*>(data), size);
        const auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
        if (!type.ok()) fail("that cannot be decoded (" + type.status().error_msg_string() + ")");
        if (type.value() != draco::TRIANGULAR_MESH)
            fail("holds a point cloud, not a triangle mesh");
        draco::Decoder decoder;
        auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
        if (!decoded.ok())
            fail("that cannot be decoded (" + decoded.status().error_msg_string() + ")");
        const draco::Mesh& mesh = *decoded.value();
        out.points = mesh.num_points();
        if (out.points > maxPoints) fail("of " + std::to_string(out.points) + " points");
        out.indices.reserve(size_t(mesh.num_faces()) * 3);
        for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
            for (int k = 0; k < 3; ++k) {
                const uint32_t point = mesh.face(f)[k].value();
                if (point >= out.points)
                    fail("with face " + std::to_string(f.value()) + " naming point " +
                         std::to_string(point) + " of " + std::to_string(out.points));
                out.indices.push_back(point);
            }
        for (int a = 0; a < mesh.num_attributes(); ++a) {
            const draco::PointAttribute& attribute = *mesh.attribute(a);
            const std::string what = "attribute " + std::to_string(attribute.unique_id());
            const int components = attribute.num_components();
            const size_t componentSize = size_t(draco::DataTypeLength(attribute.data_type()));
            double probe = 0.0;
            const uint8_t zero[8] = {};
            if (components <= 0 || componentSize == 0 ||
                !componentOf(attribute.data_type(), zero, probe))
                fail("with " + what + " of a type glTF has no accessor for");
            if (!attribute.is_mapping_identity() && attribute.indices_map_size() < out.points)
                fail("with " + what + " mapping fewer values than there are points");
            const draco::DataBuffer* values = attribute.buffer();
            if (values == nullptr) fail("with " + what + " without values");
            DracoAttribute decodedAttribute;
            decodedAttribute.components = components;
            decodedAttribute.integer = attribute.data_type() != draco::DT_FLOAT32 &&
                                       attribute.data_type() != draco::DT_FLOAT64;
            decodedAttribute.values.resize(out.points * size_t(components));
            for (size_t p = 0; p < out.points; ++p) {
                const draco::AttributeValueIndex value =
                    attribute.mapped_index(draco::PointIndex(uint32_t(p)));
                const int64_t byte = attribute.GetBytePos(value);
                if (value.value() >= attribute.size() || byte < 0 ||
                    uint64_t(byte) + uint64_t(components) * componentSize > values->data_size())
                    fail("with " + what + " reading past its values");
                const uint8_t* element = values->data() + byte;
                for (int c = 0; c < components; ++c)
                    componentOf(attribute.data_type(), element + size_t(c) * componentSize,
                                decodedAttribute.values[p * size_t(components) + size_t(c)]);
            }
            if (!out.attributes.emplace(int(attribute.unique_id()), std::move(decodedAttribute))
                     .second)
                fail("with two attributes of unique id " + std::to_string(attribute.unique_id()));
        }
    } catch (const InputError&) {
        throw;
    } catch (const std::bad_alloc&) {
        fail("that needs more memory than there is to decode");
    } catch (const std::exception& e) {
        fail(std::string("that cannot be decoded (") + e.what() + ")");
    }
    return out;
}

}  // namespace gpurt
