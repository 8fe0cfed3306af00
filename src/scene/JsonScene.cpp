// JSON scene loading: nlohmann-json parses; SceneReader walks the document against the schema of
// docs/SCENE_FORMAT.md, naming the JSON pointer of anything it refuses, and assembles the Scene
// from the OBJ files the meshes name.
#include "scene/JsonScene.h"

#include <algorithm>
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <numbers>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "image/InputError.h"
#include "scene/GltfLoader.h"
#include "scene/ObjLoader.h"
#include "scene/SceneFile.h"

namespace gpurt {
namespace {

using nlohmann::json;
using Pointer = json::json_pointer;

constexpr int kMaxImageSide = 16384;
constexpr int kMaxBounces = 64;

// 'text', built by appending (GCC 12 warns falsely on "'" + std::string).
std::string quote(std::string_view text) {
    std::string out(1, '\'');
    out.append(text);
    out += '\'';
    return out;
}

// Messages are one line of ASCII whatever the file holds: other bytes become \xNN.
std::string formatNumber(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}


// The line and column in `name` of a 1-based byte offset into text (nlohmann's
// parse_error::byte).
FileLoc locationOf(const std::string& name, std::string_view text, size_t byte) {
    const size_t end = std::min(byte > 0 ? byte - 1 : 0, text.size());
    size_t line = 1, lineStart = 0;
    for (size_t i = 0; i < end; ++i) {
        if (text[i] == '\n') {
            ++line;
            lineStart = i + 1;
        }
    }
    return FileLoc{name, line, end - lineStart + 1};
}

// nlohmann's message without its "[json.exception.parse_error.101] parse error at line 1,
// column 2: " prefix (the position is reported separately).
std::string parseErrorText(const std::string& what) {
    std::string text = what;
    const size_t bracket = text.find("] ");
    if (text.rfind("[json.exception.", 0) == 0 && bracket != std::string::npos)
        text.erase(0, bracket + 2);
    const size_t column = text.find("column ");
    if (text.rfind("parse error", 0) == 0 && column != std::string::npos) {
        const size_t colon = text.find(": ", column);
        if (colon != std::string::npos) text.erase(0, colon + 2);
    }
    return printable(text);
}

// nlohmann keeps the last of repeated keys silently; a scene file with two "camera" objects is
// more likely a mistake. A parser callback that follows the JSON pointer of the value being read.
class DuplicateKeyCheck {
  public:
    explicit DuplicateKeyCheck(std::string file) : file_(std::move(file)) {}

    bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
        switch (event) {
            case json::parse_event_t::object_start:
            case json::parse_event_t::array_start:
                enterChild();
                frames_.push_back({event == json::parse_event_t::array_start, {}, 0, {}});
                break;
            case json::parse_event_t::object_end:
            case json::parse_event_t::array_end:
                frames_.pop_back();
                break;
            case json::parse_event_t::key: {
                Frame& object = frames_.back();
                object.key = parsed.get<std::string>();
                if (!object.keys.insert(object.key).second) {
                    Pointer at;
                    for (const Frame& frame : frames_)
                        at = frame.isArray ? at / (frame.count - 1) : at / frame.key;
                    failAt(FileLoc{file_}, printable(at.to_string()) + ": duplicate key");
                }
                break;
            }
            case json::parse_event_t::value:
                enterChild();
                break;
        }
        return true;
    }

  private:
    struct Frame {
        bool isArray;
        std::string key;             // object: the key being read
        size_t count;                // array: elements started so far
        std::set<std::string> keys;  // object: keys seen so far
    };

    void enterChild() {
        if (!frames_.empty() && frames_.back().isArray) ++frames_.back().count;
    }

    std::string file_;
    std::vector<Frame> frames_;
};

// Walks one parsed scene document. Every accessor takes the value and its JSON pointer, so that
// a refusal can name the place.
class SceneReader {
  public:
    explicit SceneReader(const std::filesystem::path& path)
        : file_(path.string()), folder_(path.parent_path()) {}

    JsonSceneFile read(const json& root) {
        const Pointer top;
        requireObject(root, top, {"meshes", "lights", "camera", "animation", "background", "environment", "render", "up_axis"});
        JsonSceneFile result;
        Scene& scene = result.scene;

        const Pointer meshesAt = top / "meshes";
        const json& meshes = require(root, top, "meshes");
        requireArray(meshes, meshesAt);
        for (size_t i = 0; i < meshes.size(); ++i) readMesh(meshes[i], meshesAt / i, scene);
        // A scene always has a material 0 (Scene's invariant), also without meshes.
        if (scene.materials.empty()) scene.materials.push_back(Material{});

        if (const json* lights = find(root, "lights")) {
            const Pointer at = top / "lights";
            requireArray(*lights, at);
            for (size_t i = 0; i < lights->size(); ++i)
                scene.lights.push_back(readLight((*lights)[i], at / i));
        }
        if (const json* camera = find(root, "camera"))
            scene.camera = readCamera(*camera, top / "camera");
        if (const json* animation = find(root, "animation"))
            scene.animation = readAnimation(*animation, top / "animation");
        if (const json* background = find(root, "background"))
            scene.background = color(*background, top / "background");
        if (const json* up = find(root, "up_axis")) {
            if (!up->is_string() || !parseUpAxis(up->get<std::string>(), scene.upAxis))
                fail(top / "up_axis", "expected one of \"y\", \"z\", \"x\", \"-y\", \"-z\", \"-x\"");
        }
        scene.backgroundGiven = find(root, "background") != nullptr;
        if (const json* environment = find(root, "environment"))
            scene.environment = readEnvironment(*environment, top / "environment");
        if (const json* render = find(root, "render")) {
            const Pointer at = top / "render";
            requireObject(*render, at, {"size", "max_bounces"});
            if (const json* size = find(*render, "size")) {
                const Pointer sizeAt = at / "size";
                requireArrayOf(*size, sizeAt, 2, "2 integers");
                const int width =
                    integer((*size)[0], sizeAt / 0, 1, kMaxImageSide);  // checked in order
                const int height = integer((*size)[1], sizeAt / 1, 1, kMaxImageSide);
                result.size = glm::ivec2(width, height);
            }
            if (const json* bounces = find(*render, "max_bounces"))
                scene.maxBounces = integer(*bounces, at / "max_bounces", 0, kMaxBounces);
        }
        return result;
    }

  private:
    [[noreturn]] void fail(const Pointer& at, const std::string& what) const {
        const std::string where = at.empty() ? std::string("top level") : printable(at.to_string());
        failAt(FileLoc{file_}, where + ": " + what);
    }

    static const json* find(const json& object, const char* key) {
        auto it = object.find(key);
        return it == object.end() ? nullptr : &*it;
    }

    const json& require(const json& object, const Pointer& at, const char* key) const {
        const json* value = find(object, key);
        if (!value) fail(at / key, "missing required key");
        return *value;
    }

    // An object whose keys are all in `allowed`.
    void requireObject(const json& value, const Pointer& at,
                       std::initializer_list<const char*> allowed) const {
        if (!value.is_object())
            fail(at, std::string("expected an object, got ") + value.type_name());
        for (const auto& item : value.items()) {
            if (std::none_of(allowed.begin(), allowed.end(),
                             [&](const char* key) { return item.key() == key; })) {
                std::string expected;
                for (const char* key : allowed)
                    expected += (expected.empty() ? "" : ", ") + std::string(key);
                fail(at / item.key(), "unknown key (expected one of: " + expected + ")");
            }
        }
    }

    void requireArray(const json& value, const Pointer& at) const {
        if (!value.is_array()) fail(at, std::string("expected an array, got ") + value.type_name());
    }

    void requireArrayOf(const json& value, const Pointer& at, size_t count,
                        const char* what) const {
        if (!value.is_array())
            fail(at, std::string("expected an array of ") + what + ", got " + value.type_name());
        if (value.size() != count)
            fail(at, "expected an array of " + std::string(what) + ", got " +
                         std::to_string(value.size()) + " elements");
    }

    // A number that fits a float (JSON has no NaN, but 1e39 overflows float).
    double number(const json& value, const Pointer& at) const {
        if (!value.is_number())
            fail(at, std::string("expected a number, got ") + value.type_name());
        const double result = value.get<double>();
        if (!std::isfinite(result)) fail(at, "number is not finite");
        if (std::fabs(result) > FLT_MAX)
            fail(at, formatNumber(result) + " does not fit in a 32-bit float");
        return result;
    }

    double numberAtLeast(const json& value, const Pointer& at, double min) const {
        const double result = number(value, at);
        if (result < min)
            fail(at, "must be >= " + formatNumber(min) + ", got " + formatNumber(result));
        return result;
    }

    int integer(const json& value, const Pointer& at, int min, int max) const {
        if (!value.is_number_integer()) {
            if (value.is_number())
                fail(at, "expected an integer, got " + formatNumber(value.get<double>()));
            fail(at, std::string("expected an integer, got ") + value.type_name());
        }
        bool inRange;
        if (value.is_number_unsigned()) {  // nlohmann keeps every non-negative integer unsigned
            const uint64_t u = value.get<uint64_t>();
            inRange = u <= static_cast<uint64_t>(max) && static_cast<int64_t>(u) >= min;
        } else {
            const int64_t s = value.get<int64_t>();
            inRange = s >= min && s <= max;
        }
        if (!inRange)
            fail(at, "must be in " + std::to_string(min) + ".." + std::to_string(max) + ", got " +
                         value.dump());
        return static_cast<int>(value.get<int64_t>());
    }

    glm::dvec3 vector3(const json& value, const Pointer& at) const {
        requireArrayOf(value, at, 3, "3 numbers");
        glm::dvec3 result;
        for (int i = 0; i < 3; ++i)
            result[i] = number(value[i], at / i);  // first bad element first
        return result;
    }

    // [r, g, b], each >= 0 (no upper bound: HDR colours are fine).
    glm::vec3 color(const json& value, const Pointer& at) const {
        requireArrayOf(value, at, 3, "3 numbers (r, g, b)");
        glm::vec3 result;
        for (int i = 0; i < 3; ++i)
            result[i] = static_cast<float>(numberAtLeast(value[i], at / i, 0.0));
        return result;
    }

    // A number or [x, y, z] (the number stands for all three).
    glm::dvec3 scalarOrVector3(const json& value, const Pointer& at) const {
        if (value.is_number()) return glm::dvec3(number(value, at));
        if (!value.is_array())
            fail(at, std::string("expected a number or an array of 3 numbers, got ") +
                         value.type_name());
        return vector3(value, at);
    }

    // "environment": {"file": F (.hdr or .exr, relative to the scene's folder), "strength": S
    // (>= 0, default 1), "rotation": degrees about +Y (default 0)}.
    Environment readEnvironment(const json& value, const Pointer& at) const {
        requireObject(value, at, {"file", "strength", "rotation"});
        Environment env;
        const Pointer fileAt = at / "file";
        const std::string fileName = meshFileName(require(value, at, "file"), fileAt);
        const std::filesystem::path path = meshPath(fileName, fileAt);
        env.image = std::make_shared<const EnvironmentImage>(readEnvironmentImage(path));
        env.file = path.string();
        if (const json* strength = find(value, "strength"))
            env.strength = static_cast<float>(numberAtLeast(*strength, at / "strength", 0.0));
        if (const json* rotation = find(value, "rotation")) env.rotation = static_cast<float>(number(*rotation, at / "rotation"));
        return env;
    }

    // A mesh: its file's triangles, moved by its transform, with the file's materials (and
    // their textures) or the mesh's own material.
    void readMesh(const json& mesh, const Pointer& at, Scene& scene) {
        requireObject(mesh, at, {"file", "transform", "material"});
        const Pointer fileAt = at / "file";
        const std::string fileName = meshFileName(require(mesh, at, "file"), fileAt);

        // Transform and material first: their errors are cheaper to find than the OBJ's.
        std::optional<glm::dmat4> transform;
        if (const json* value = find(mesh, "transform"))
            transform = readTransform(*value, at / "transform");
        std::optional<Material> override;
        if (const json* value = find(mesh, "material"))
            override = readMaterial(*value, at / "material", fileName);

        const std::filesystem::path objPath = meshPath(fileName, fileAt);
        // The same OBJ listed twice (e.g. with two transforms) is read once.
        const std::string key = objPath.lexically_normal().string();
        auto cached = objCache_.find(key);
        if (cached == objCache_.end()) cached = objCache_.emplace(key, loadMesh(objPath)).first;
        const Scene& obj = cached->second;

        const uint32_t materialBase = static_cast<uint32_t>(scene.materials.size());
        if (override)
            scene.materials.push_back(*override);
        else
            addMeshMaterials(obj, key, scene);
        addMeshTriangles(obj, transform, override.has_value(), materialBase, at / "transform", scene);
    }

    // The mesh's "file": a string that can name a file.
    std::string meshFileName(const json& value, const Pointer& at) const {
        if (!value.is_string()) fail(at, std::string("expected a string, got ") + value.type_name());
        const std::string fileName = value.get<std::string>();
        if (fileName.empty()) fail(at, "empty file name");
        if (fileName.find('\0') != std::string::npos) fail(at, "file name contains a NUL byte");
        return fileName;
    }

    // The file a mesh names (relative to the scene's folder), which must exist and be readable.
    std::filesystem::path meshPath(const std::string& fileName, const Pointer& at) const {
        std::filesystem::path objPath(fileName);
        if (objPath.is_relative()) objPath = folder_ / objPath;
        std::error_code ec;
        const std::filesystem::file_status status = std::filesystem::status(objPath, ec);
        if (!std::filesystem::exists(status))
            fail(at, "no such file " + quote(printable(fileName)));
        if (std::filesystem::is_directory(status))
            fail(at, quote(printable(fileName)) + " is a directory");
        if (!isReadableKind(status))
            fail(at, quote(printable(fileName)) + " is a device or socket, not a file");
        return objPath;
    }

    // The materials of mesh file `key`, their textures added once however often it is listed.
    void addMeshMaterials(const Scene& obj, const std::string& key, Scene& scene) {
        auto textures = textureBase_.find(key);
        if (textures == textureBase_.end()) {
            textures = textureBase_.emplace(key, int(scene.textures.size())).first;
            scene.textures.insert(scene.textures.end(), obj.textures.begin(), obj.textures.end());
        }
        const int base = textures->second;
        auto shift = [base](int& texture) {
            if (texture >= 0) texture += base;
        };
        for (Material m : obj.materials) {
            for (int* texture : {&m.diffuseTexture, &m.roughnessTexture.texture, &m.metallicTexture.texture,
                                 &m.normalTexture, &m.emissiveTexture, &m.occlusionTexture.texture,
                                 &m.alphaTexture.texture, &m.transmissionTexture.texture})
                shift(*texture);
            scene.materials.push_back(m);
        }
    }

    // The mesh's triangles with their normals, and texture coordinates and vertex colours (both
    // dropped with an overriding material, which is then shown as it is): all of material materialBase when `overridden`, else of the file's
    // materials, added from materialBase on.
    void addMeshTriangles(const Scene& obj, const std::optional<glm::dmat4>& transform, bool overridden,
                          uint32_t materialBase, const Pointer& transformAt, Scene& scene) const {
        const bool texcoords = !overridden && !obj.texcoords.empty();
        if (texcoords || !scene.texcoords.empty()) scene.texcoords.resize(scene.triangles.size());
        const bool colors = !overridden && !obj.colors.empty();
        if (colors || !scene.colors.empty()) scene.colors.resize(scene.triangles.size());
        // Vertex tangents (dropped with an overriding material, as the texture coordinates) go
        // through the transform's linear part; a mirroring one turns their handedness over.
        const bool tangents = !overridden && !obj.tangents.empty();
        if (tangents || !scene.tangents.empty()) scene.tangents.resize(scene.triangles.size());
        const glm::dmat3 tangentMatrix = transform ? glm::dmat3(*transform) : glm::dmat3(1.0);
        const float hand = glm::determinant(tangentMatrix) < 0.0 ? -1.0f : 1.0f;
        scene.triangles.reserve(scene.triangles.size() + obj.triangles.size());
        scene.materialIds.reserve(scene.materialIds.size() + obj.triangles.size());
        // Vertex normals go through the inverse transpose of the transform's linear part.
        if (!obj.normals.empty() || !scene.normals.empty()) scene.normals.resize(scene.triangles.size());
        const glm::dmat3 normalMatrix = transform ? glm::inverseTranspose(glm::dmat3(*transform)) : glm::dmat3(1.0);
        for (size_t k = 0; k < obj.triangles.size(); ++k) {
            if (!obj.normals.empty()) {
                TriangleNormals n = obj.normals[k];
                if (transform && n.given())
                    for (glm::vec3* v : {&n.n0, &n.n1, &n.n2}) {
                        const glm::dvec3 m = normalMatrix * glm::dvec3(*v);
                        const double len = glm::length(m);
                        *v = len > 0.0 && std::isfinite(len) ? glm::vec3(m / len) : glm::vec3(0.0f);
                    }
                scene.normals.push_back(n);
            } else if (!scene.normals.empty()) {
                scene.normals.push_back(TriangleNormals{});
            }
            Triangle triangle = obj.triangles[k];
            if (transform) {
                triangle.v0 = transformPoint(*transform, triangle.v0, transformAt, k);
                triangle.v1 = transformPoint(*transform, triangle.v1, transformAt, k);
                triangle.v2 = transformPoint(*transform, triangle.v2, transformAt, k);
            }
            scene.triangles.push_back(triangle);
            if (texcoords) scene.texcoords.push_back(obj.texcoords[k]);
            else if (!scene.texcoords.empty()) scene.texcoords.push_back(TriangleTexcoords{});
            if (colors) scene.colors.push_back(obj.colors[k]);
            else if (!scene.colors.empty()) scene.colors.push_back(TriangleColors{});
            if (tangents) {
                TriangleTangents t = obj.tangents[k];
                if (transform)
                    for (glm::vec4* c : {&t.t0, &t.t1, &t.t2}) {
                        const glm::dvec3 m = tangentMatrix * glm::dvec3(glm::vec3(*c));
                        const double len = glm::length(m);
                        *c = len > 0.0 && std::isfinite(len) ? glm::vec4(glm::vec3(m / len), c->w * hand) : glm::vec4(0.0f);
                    }
                scene.tangents.push_back(t);
            } else if (!scene.tangents.empty()) {
                scene.tangents.push_back(TriangleTangents{});
            }
            scene.materialIds.push_back(overridden ? materialBase : materialBase + obj.materialIds[k]);
        }
    }

    // The product in double, rounded to float once.
    glm::vec3 transformPoint(const glm::dmat4& m, glm::vec3 p, const Pointer& at,
                             size_t triangle) const {
        const glm::dvec4 q = m * glm::dvec4(glm::dvec3(p), 1.0);
        for (int i = 0; i < 3; ++i)
            if (!(std::fabs(q[i]) <= FLT_MAX))
                fail(at, "moves a vertex of the mesh's triangle " + std::to_string(triangle) +
                             " outside the 32-bit float range");
        return glm::vec3(q);
    }

    // T * Rz * Ry * Rx * S (rotation about x first, angles in degrees), or a row-major matrix.
    glm::dmat4 readTransform(const json& value, const Pointer& at) const {
        requireObject(value, at, {"translate", "rotate", "scale", "matrix"});
        glm::dmat4 m(1.0);
        if (const json* matrix = find(value, "matrix")) {
            const Pointer matrixAt = at / "matrix";
            for (const char* other : {"translate", "rotate", "scale"})
                if (find(value, other))
                    fail(matrixAt, std::string("cannot be combined with \"") + other + "\"");
            requireArrayOf(*matrix, matrixAt, 16, "16 numbers (a row-major 4x4 matrix)");
            for (int row = 0; row < 4; ++row)
                for (int column = 0; column < 4; ++column)
                    m[column][row] =
                        number((*matrix)[row * 4 + column], matrixAt / (row * 4 + column));
            if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
                fail(matrixAt, "last row must be 0, 0, 0, 1 (an affine transform)");
            double largest = 0.0;
            for (int column = 0; column < 3; ++column)
                for (int row = 0; row < 3; ++row)
                    largest = std::max(largest, std::fabs(m[column][row]));
            const double det = glm::determinant(glm::dmat3(m));
            if (!std::isfinite(det) || !(std::fabs(det) > 1e-12 * largest * largest * largest))
                fail(matrixAt, "singular matrix (the upper-left 3x3 has determinant " +
                                   formatNumber(det) + ")");
            return m;
        }
        if (const json* translate = find(value, "translate"))
            m = glm::translate(m, vector3(*translate, at / "translate"));
        if (const json* rotate = find(value, "rotate")) {
            const glm::dvec3 degrees = vector3(*rotate, at / "rotate");
            m = glm::rotate(m, glm::radians(degrees.z), glm::dvec3(0, 0, 1));
            m = glm::rotate(m, glm::radians(degrees.y), glm::dvec3(0, 1, 0));
            m = glm::rotate(m, glm::radians(degrees.x), glm::dvec3(1, 0, 0));
        }
        if (const json* scale = find(value, "scale")) {
            const Pointer scaleAt = at / "scale";
            const glm::dvec3 s = scalarOrVector3(*scale, scaleAt);
            if (s.x == 0.0 || s.y == 0.0 || s.z == 0.0)
                fail(scaleAt, "scale must not be 0 (a singular transform)");
            m = glm::scale(m, s);
        }
        return m;
    }

    // "metallic", "roughness" or a layer of glTF's extensions: glTF's metallic-roughness model,
    // "diffuse" its base colour; "clearcoat" and "clearcoat_roughness" (KHR_materials_clearcoat),
    // "specular_factor" and "specular_color" (KHR_materials_specular), "sheen_color" and
    // "sheen_roughness" (KHR_materials_sheen), each a factor in [0, 1] but the specular colour;
    // "attenuation_color" and "attenuation_distance" (KHR_materials_volume: the solid's medium);
    // "iridescence" (a factor), "iridescence_ior" and "iridescence_thickness" (readIridescence);
    // "anisotropy" (a factor) and "anisotropy_rotation" (radians) (KHR_materials_anisotropy, in the
    // tangent frame of the mesh's texture coordinates).
    void readGltfFactors(const json& value, const Pointer& at, Material& material) const {
        const std::pair<const char*, float*> factors[] = {
            {"metallic", &material.metallic}, {"roughness", &material.roughness}, {"clearcoat", &material.clearcoat},
            {"clearcoat_roughness", &material.clearcoatRoughness}, {"specular_factor", &material.specularFactor},
            {"sheen_roughness", &material.sheenRoughness}, {"iridescence", &material.iridescenceFactor},
            {"anisotropy", &material.anisotropyStrength}};
        for (const auto& [key, field] : factors) {
            const json* given = find(value, key);
            if (!given) continue;
            const double v = numberAtLeast(*given, at / key, 0.0);
            if (v > 1.0) fail(at / key, "must be <= 1, got " + formatNumber(v));
            *field = static_cast<float>(v);
            material.model = GPURT_MODEL_GLTF;
        }
        if (const json* tint = find(value, "specular_color")) {
            material.specularColor = color(*tint, at / "specular_color");
            material.model = GPURT_MODEL_GLTF;
        }
        if (const json* sheen = find(value, "sheen_color")) {  // KHR_materials_sheen: each in [0, 1]
            material.sheenColor = color(*sheen, at / "sheen_color");
            for (int i = 0; i < 3; ++i)
                if (material.sheenColor[i] > 1.0f)
                    fail(at / "sheen_color" / i, "must be <= 1, got " + formatNumber(material.sheenColor[i]));
            material.model = GPURT_MODEL_GLTF;
        }
        readVolume(value, at, material);
        readIridescence(value, at, material);
        if (const json* rotation = find(value, "anisotropy_rotation")) {
            material.anisotropyRotation = static_cast<float>(number(*rotation, at / "anisotropy_rotation"));
            material.model = GPURT_MODEL_GLTF;
        }
    }

    // KHR_materials_iridescence's "iridescence_ior" (>= 1) and "iridescence_thickness" (nm >= 0): a
    // thin film of that one thickness.
    void readIridescence(const json& value, const Pointer& at, Material& material) const {
        if (const json* ior = find(value, "iridescence_ior")) {
            const double n = numberAtLeast(*ior, at / "iridescence_ior", 1.0);
            if (n > 1e3) fail(at / "iridescence_ior", "must be <= 1000, got " + formatNumber(n));
            material.iridescenceIor = static_cast<float>(n);
            material.model = GPURT_MODEL_GLTF;
        }
        if (const json* thickness = find(value, "iridescence_thickness")) {
            const double d = numberAtLeast(*thickness, at / "iridescence_thickness", 0.0);
            if (d > 1e6) fail(at / "iridescence_thickness", "must be <= 1e6 (nm), got " + formatNumber(d));
            material.iridescenceThicknessMin = material.iridescenceThicknessMax = static_cast<float>(d);
            material.model = GPURT_MODEL_GLTF;
        }
    }

    // KHR_materials_volume's attenuation: "attenuation_color" (each in [0, 1]) and
    // "attenuation_distance" (> 0; infinite without). A JSON material's solid has no thin walls
    // (its thickness is 1).
    void readVolume(const json& value, const Pointer& at, Material& material) const {
        const json* tint = find(value, "attenuation_color");
        const json* distance = find(value, "attenuation_distance");
        if (!tint && !distance) return;
        if (tint) {
            material.attenuationColor = color(*tint, at / "attenuation_color");
            for (int i = 0; i < 3; ++i)
                if (material.attenuationColor[i] > 1.0f)
                    fail(at / "attenuation_color" / i, "must be <= 1, got " + formatNumber(material.attenuationColor[i]));
        }
        if (distance) {
            const double d = numberAtLeast(*distance, at / "attenuation_distance", 0.0);
            if (!(d > 0.0)) fail(at / "attenuation_distance", "must be > 0, got " + formatNumber(d));
            material.attenuationDistance = static_cast<float>(d);
        }
        material.thickness = 1.0f;
        material.model = GPURT_MODEL_GLTF;
    }

    // "transmission": glTF's model's factor in [0, 1] with "ior" >= 1 (KHR_materials_ior and
    // KHR_materials_transmission: a rough dielectric solid, glsl/common/materials/gltf.h), which
    // cannot also have the classic model's keys; the classic model's filter colour otherwise.
    void readTransmission(const json& value, const Pointer& at, Material& material) const {
        if (material.model == GPURT_MODEL_GLTF) {
            // glTF's model: "ior" (KHR_materials_ior) and "transmission" a factor in [0, 1]
            // (KHR_materials_transmission: a rough dielectric solid, glsl/common/materials/gltf.h).
            if (find(value, "reflectivity") || find(value, "specular") || find(value, "shininess"))
                fail(at, "metallic and roughness (glTF's model) do not go with specular, shininess or reflectivity");
            if (material.ior != 0.0f && material.ior < 1.0f) fail(at / "ior", "must be >= 1 with metallic and roughness, got " + formatNumber(material.ior));
            material.transmission = glm::vec3(0.0f);
            if (const json* transmission = find(value, "transmission")) {
                const double t = numberAtLeast(*transmission, at / "transmission", 0.0);
                if (t > 1.0) fail(at / "transmission", "must be <= 1, got " + formatNumber(t));
                material.transmission = glm::vec3(float(t));
                if (t > 0.0 && material.ior == 0.0f) material.ior = 1.5f;
            }
            if (const json* thin = find(value, "thin_walled")) {  // KHR_materials_transmission's thin wall
                if (!thin->is_boolean()) fail(at / "thin_walled", std::string("expected true or false, got ") + thin->type_name());
                if (!(material.transmission.x > 0.0f)) fail(at / "thin_walled", "needs a transmission above 0");
                if (thin->get<bool>() && (find(value, "attenuation_color") || find(value, "attenuation_distance")))
                    fail(at / "thin_walled", "a thin wall has no volume: no attenuation_color or attenuation_distance");
                material.thinWalled = thin->get<bool>();
            }
        } else if (find(value, "thin_walled")) {
            fail(at / "thin_walled", "goes with glTF's model (metallic and roughness) and its transmission");
        } else if (const json* transmission = find(value, "transmission")) {
            material.transmission = color(*transmission, at / "transmission");
            for (int i = 0; i < 3; ++i)
                if (material.transmission[i] > 1.0f)
                    fail(at / "transmission" / i, "must be <= 1, got " + formatNumber(material.transmission[i]));
    }
    }

    // KHR_materials_dispersion's "dispersion" (20 / the Abbe number, in [0, 1000]): only on a
    // transmissive solid (transmission and ior, not thin_walled), where it changes the index with
    // the wavelength; on any other material it would change nothing, so it is an error there
    // (readMaterial checks once the transmission is read).
    void readDispersion(const json& value, const Pointer& at, Material& material) const {
        const json* given = find(value, "dispersion");
        if (!given) return;
        const double v = numberAtLeast(*given, at / "dispersion", 0.0);
        if (v > 1e3) fail(at / "dispersion", "must be <= 1000, got " + formatNumber(v));
        material.dispersion = static_cast<float>(v);
        material.model = GPURT_MODEL_GLTF;
    }

    Material readMaterial(const json& value, const Pointer& at, const std::string& fileName) const {
        requireObject(value, at, {"name", "diffuse", "specular", "shininess", "reflectivity", "emission", "ior", "transmission",
                                  "metallic", "roughness", "clearcoat", "clearcoat_roughness", "specular_factor",
                                  "specular_color", "sheen_color", "sheen_roughness", "attenuation_color",
                                  "attenuation_distance", "iridescence", "iridescence_ior", "iridescence_thickness",
                                  "anisotropy", "anisotropy_rotation", "thin_walled", "dispersion", "doubleSided"});
        Material material;
        material.name = printable(fileName) + " (override)";
        if (const json* name = find(value, "name")) {
            if (!name->is_string())
                fail(at / "name", std::string("expected a string, got ") + name->type_name());
            material.name = name->get<std::string>();
        }
        if (const json* diffuse = find(value, "diffuse"))
            material.diffuse = color(*diffuse, at / "diffuse");
        if (const json* specular = find(value, "specular"))
            material.specular = color(*specular, at / "specular");
        if (const json* emission = find(value, "emission"))
            material.emission = color(*emission, at / "emission");
        if (const json* ior = find(value, "ior")) {
            const double eta = numberAtLeast(*ior, at / "ior", 0.0);
            if (!(eta > 0.0)) fail(at / "ior", "must be > 0, got " + formatNumber(eta));
            material.ior = static_cast<float>(eta);
        }
        readGltfFactors(value, at, material);
        readDispersion(value, at, material);
        readTransmission(value, at, material);
        if (material.dispersion > 0.0f && !material.disperses())
            fail(at / "dispersion", "applies to a transmissive solid only (\"transmission\" and \"ior\", not \"thin_walled\")");
        if (const json* shininess = find(value, "shininess"))
            material.shininess =
                static_cast<float>(numberAtLeast(*shininess, at / "shininess", 0.0));
        if (const json* reflectivity = find(value, "reflectivity")) {
            const Pointer reflectAt = at / "reflectivity";
            // A mirror weight above 1 would amplify light at every bounce.
            if (reflectivity->is_number()) {
                const double r = numberAtLeast(*reflectivity, reflectAt, 0.0);
                if (r > 1.0) fail(reflectAt, "must be <= 1, got " + formatNumber(r));
                material.reflectivity = glm::vec3(static_cast<float>(r));
            } else {
                material.reflectivity = color(*reflectivity, reflectAt);
                for (int i = 0; i < 3; ++i)
                    if (material.reflectivity[i] > 1.0f)
                        fail(reflectAt / i,
                             "must be <= 1, got " + formatNumber(material.reflectivity[i]));
            }
        }
        // false: the back faces are culled (as glTF's doubleSided; default true here).
        if (const json* sided = find(value, "doubleSided")) {
            if (!sided->is_boolean()) fail(at / "doubleSided", std::string("expected true or false, got ") + sided->type_name());
            material.doubleSided = sided->get<bool>();
        }
        return material;
    }

    // {"type": "point" (default) | "spot" | "directional", "position", "direction", "color",
    // "intensity", "inner_cone", "outer_cone" (spot, degrees), "range" (point, spot)}: gpurt's own
    // units (Scene.h Light; docs/SCENE_FORMAT.md).
    Light readLight(const json& value, const Pointer& at) const {
        requireObject(value, at, {"type", "position", "direction", "color", "intensity", "inner_cone", "outer_cone", "range"});
        Light light;
        if (const json* type = find(value, "type")) {
            const std::string t = type->is_string() ? type->get<std::string>() : std::string();
            if (t == "point") light.kind = LightKind::Point;
            else if (t == "spot") light.kind = LightKind::Spot;
            else if (t == "directional") light.kind = LightKind::Directional;
            else fail(at / "type", "expected \"point\", \"spot\" or \"directional\"");
        }
        auto refuse = [&](const char* key, const char* why) {
            if (find(value, key)) fail(at / key, why);
        };
        if (light.kind == LightKind::Directional) {
            refuse("position", "a directional light has no position");
            refuse("range", "a directional light has no range");
        } else {
            light.position = glm::vec3(vector3(require(value, at, "position"), at / "position"));
        }
        if (light.kind == LightKind::Point) refuse("direction", "a point light has no direction");
        else {
            const glm::dvec3 d = vector3(require(value, at, "direction"), at / "direction");
            if (!(glm::dot(d, d) > 0.0)) fail(at / "direction", "must be a non-zero vector");
            light.direction = glm::vec3(d / glm::length(d));
        }
        if (light.kind != LightKind::Spot) {
            refuse("inner_cone", "only a spot light has a cone");
            refuse("outer_cone", "only a spot light has a cone");
        } else {
            double inner = 0.0, outer = 45.0;
            if (const json* v = find(value, "inner_cone")) inner = number(*v, at / "inner_cone");
            if (const json* v = find(value, "outer_cone")) outer = number(*v, at / "outer_cone");
            if (!(inner >= 0.0 && inner < outer && outer <= 90.0))
                fail(at / "outer_cone", "the cone's angles must be 0 <= inner_cone < outer_cone <= 90 degrees");
            light.innerCone = float(inner * std::numbers::pi / 180.0);
            light.outerCone = float(outer * std::numbers::pi / 180.0);
        }
        if (const json* range = find(value, "range")) {
            light.range = static_cast<float>(number(*range, at / "range"));
            if (!(light.range > 0.0f)) fail(at / "range", "must be > 0");
        }
        if (const json* c = find(value, "color")) light.color = color(*c, at / "color");
        if (const json* intensity = find(value, "intensity"))
            light.intensity = static_cast<float>(numberAtLeast(*intensity, at / "intensity", 0.0));
        return light;
    }

    // {"fps": F, "camera": [KEY, ...]}: a key is a camera object with its "time" in seconds.
    CameraAnimation readAnimation(const json& value, const Pointer& at) const {
        requireObject(value, at, {"fps", "camera"});
        CameraAnimation animation;
        if (const json* fps = find(value, "fps")) {
            const double f = number(*fps, at / "fps");
            if (!(f > 0.0 && f <= 1000.0)) fail(at / "fps", "must be in (0, 1000], got " + formatNumber(f));
            animation.fps = static_cast<float>(f);
        }
        const Pointer keysAt = at / "camera";
        const json& keys = require(value, at, "camera");
        requireArray(keys, keysAt);
        if (keys.empty()) fail(keysAt, "needs at least one key");
        for (size_t i = 0; i < keys.size(); ++i) {
            const Pointer keyAt = keysAt / i;
            if (!keys[i].is_object()) fail(keyAt, std::string("expected an object, got ") + keys[i].type_name());
            CameraKey key;
            key.time = static_cast<float>(number(require(keys[i], keyAt, "time"), keyAt / "time"));
            if (i > 0 && !(key.time > animation.keys.back().time))
                fail(keyAt / "time", "must be later than the key before (" +
                                         formatNumber(animation.keys.back().time) + "), got " + formatNumber(key.time));
            key.camera = readCamera(keys[i], keyAt, true);
            animation.keys.push_back(key);
        }
        return animation;
    }

    // The thin lens (CONTRACT.md, depth of field): lens_radius >= 0 or fstop > 0 (not both),
    // focus_distance > 0, blades 0 or 3 to 64, blade_rotation in degrees.
    void readLens(const json& value, const Pointer& at, CameraSpec& camera) const {
        auto positive = [&](const char* key, bool zero) {
            const double v = number(value.at(key), at / key);
            if (!(zero ? v >= 0.0 : v > 0.0))
                fail(at / key, std::string("must be ") + (zero ? ">= 0" : "> 0") + ", got " + formatNumber(v));
            return static_cast<float>(v);
        };
        if (find(value, "lens_radius") && find(value, "fstop")) fail(at / "fstop", "give lens_radius or fstop, not both");
        if (find(value, "lens_radius")) camera.lensRadius = positive("lens_radius", true);
        if (find(value, "fstop")) camera.fstop = positive("fstop", false);
        if (find(value, "focus_distance")) camera.focusDistance = positive("focus_distance", false);
        if (const json* blades = find(value, "blades")) {
            camera.blades = integer(*blades, at / "blades", 0, 64);
            if (camera.blades == 1 || camera.blades == 2) fail(at / "blades", "must be 0 (a disc) or 3 to 64");
        }
        if (const json* rotation = find(value, "blade_rotation")) {
            camera.bladeRotation = static_cast<float>(number(*rotation, at / "blade_rotation"));
        }
    }

    // `keyed`: an animation key, which also has a "time".
    CameraSpec readCamera(const json& value, const Pointer& at, bool keyed = false) const {
        if (keyed)
            requireObject(value, at, {"time", "eye", "target", "up", "fovy"});  // the lens: the scene's camera only
        else
            requireObject(value, at, {"eye", "target", "up", "fovy", "lens_radius", "fstop", "focus_distance", "blades", "blade_rotation"});
        CameraSpec camera;
        camera.eye = glm::vec3(vector3(require(value, at, "eye"), at / "eye"));
        camera.target = glm::vec3(vector3(require(value, at, "target"), at / "target"));
        if (const json* up = find(value, "up")) camera.up = glm::vec3(vector3(*up, at / "up"));
        if (const json* fovy = find(value, "fovy")) {
            const double degrees = number(*fovy, at / "fovy");
            if (!(degrees > 0.0 && degrees < 180.0))
                fail(at / "fovy",
                     "must be between 0 and 180 degrees (exclusive), got " + formatNumber(degrees));
            camera.fovy = static_cast<float>(degrees);
        }
        if (!keyed) readLens(value, at, camera);
        // The contract's basis (CONTRACT.md, camera convention) must exist. In double: in float
        // the squared lengths would overflow for a camera far away in a huge scene, which the
        // renderer handles (SceneScale.h).
        const glm::dvec3 forward = glm::dvec3(camera.target) - glm::dvec3(camera.eye);
        if (forward == glm::dvec3(0.0))
            fail(at / "target", "target - eye must be a non-zero vector of finite length");
        const glm::dvec3 right = glm::cross(forward / glm::length(forward), glm::dvec3(camera.up));
        if (right == glm::dvec3(0.0))
            fail(at / "up", "up must be non-zero and not parallel to target - eye");
        return camera;
    }

    std::string file_;
    std::filesystem::path folder_;
    std::map<std::string, Scene> objCache_;
    std::map<std::string, int> textureBase_;  // where each mesh's textures start in the scene's
};

}  // namespace

JsonSceneFile loadJsonSceneFile(const std::filesystem::path& path) {
    return parseJsonScene(readSceneFile(path), path);
}

JsonSceneFile parseJsonScene(const std::string& text, const std::filesystem::path& path) {
    const std::string name = path.string();
    json root;
    DuplicateKeyCheck duplicates(name);
    try {
        root = json::parse(text, std::ref(duplicates));
    } catch (const json::parse_error& e) {
        failAt(locationOf(name, text, e.byte), parseErrorText(e.what()));
    } catch (const json::exception& e) {
        // out_of_range 406, "number overflow parsing '1e999'", carries no position: find the
        // number.
        const std::string what = e.what();
        const size_t open = what.find('\''), close = what.rfind('\'');
        const size_t at =
            open < close ? text.find(what.substr(open + 1, close - open - 1)) : std::string::npos;
        failAt(at == std::string::npos ? FileLoc{name} : locationOf(name, text, at + 1),
               parseErrorText(what));
    }
    // glTF is known by its content, whatever its name (CONTRACT.md): a gpurt scene has no "asset".
    if (root.is_object() && root.contains("asset")) {
        warnAt(FileLoc{name}, "a glTF file (it has an \"asset\"), not a gpurt JSON scene: read as glTF");
        JsonSceneFile file;
        file.scene = parseGltf(text, name, path.parent_path());
        return file;
    }
    return SceneReader(path).read(root);
}

Scene loadJsonScene(const std::filesystem::path& path) { return loadJsonSceneFile(path).scene; }

}  // namespace gpurt
