// Scene format detection: a look at the first bytes, then the format's own loader.
#include "raytrace/scene/SceneLoader.h"

#include <cctype>
#include <chrono>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>

#include "image/AtomicFile.h"
#include "raytrace/scene/SceneScale.h"
#include "scene/SmoothNormals.h"
#include "image/InputError.h"
#include "scene/GltfLoader.h"
#include "scene/JsonScene.h"
#include "scene/ObjLoader.h"
#include "raytrace/scene/PackedScene.h"
#include "scene/PlyLoader.h"
#include "scene/SceneFile.h"

namespace gpurt {
namespace {

enum class SceneFormat { Obj, Json, Packed, Ply, Gltf };


bool isJsonSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// Reads only as far as the decision needs: the magic, then past leading whitespace.
SceneFormat detectFormat(const std::filesystem::path& path) {
    const std::string name = path.string();
    checkSceneFile(path);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(name + ": cannot read (" + std::strerror(errno) + ")");

    const size_t magicSize = sizeof kPackedSceneMagic - 1;
    char head[sizeof kPackedSceneMagic - 1] = {};
    in.read(head, static_cast<std::streamsize>(magicSize));
    if (in.bad()) throw InputError(name + ": cannot read");
    const size_t got = static_cast<size_t>(in.gcount());
    // The magic without its last character (the format generation) is enough: the packed
    // reader then names a magic it does not know, which says more than an OBJ parse error.
    if (got >= magicSize - 1 && std::memcmp(head, kPackedSceneMagic, magicSize - 1) == 0)
        return SceneFormat::Packed;
    if (looksLikePly(std::string(head, got))) return SceneFormat::Ply;
    if (looksLikeGlb(std::string(head, got))) return SceneFormat::Gltf;
    // A file named as one of the binary formats is that format's reader's to refuse ("not a PLY
    // file", "wrong magic"): read as an OBJ it would give a less useful message.
    const std::string ext = lowerExtension(path);
    if (ext == ".gpscene") return SceneFormat::Packed;
    if (ext == ".ply") return SceneFormat::Ply;
    if (ext == ".glb" || ext == ".gltf") return SceneFormat::Gltf;

    // First non-whitespace byte, skipping a UTF-8 byte order mark (nlohmann skips it too).
    std::string bytes(head, got);
    size_t pos = bytes.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
    char buffer[4096];
    while (true) {
        while (pos < bytes.size() && isJsonSpace(bytes[pos])) ++pos;
        if (pos < bytes.size()) return bytes[pos] == '{' ? SceneFormat::Json : SceneFormat::Obj;
        if (!in) return SceneFormat::Obj;  // empty or all whitespace: an (empty) OBJ
        in.read(buffer, sizeof buffer);
        if (in.bad()) throw InputError(name + ": cannot read");
        bytes.assign(buffer, static_cast<size_t>(in.gcount()));
        pos = 0;
    }
}

}  // namespace

LoadedScene loadScene(const std::filesystem::path& path) {
    switch (detectFormat(path)) {
        case SceneFormat::Packed:
            return readPackedScene(path);
        case SceneFormat::Json: {
            JsonSceneFile file = loadJsonSceneFile(path);
            return LoadedScene{std::move(file.scene), file.size, nullptr};
        }
        case SceneFormat::Ply:
            return LoadedScene{loadPly(path), std::nullopt, nullptr};
        case SceneFormat::Gltf:
            return LoadedScene{loadGltf(path), std::nullopt, nullptr};
        case SceneFormat::Obj:
            break;
    }
    return LoadedScene{loadObj(path), std::nullopt, nullptr};
}

void turnSceneUp(LoadedScene& loaded, UpAxis axis) {
    if (axis == UpAxis::PosY) return;
    rotateUpToY(loaded.scene, axis);
    if (loaded.accel) loaded.accel = loaded.accel->turnedUp(axis);
}

LoadedScene prepareScene(const std::filesystem::path& path, std::optional<UpAxis> upAxis, float crease,
                         int& scaleExponent, double* normalsMs) {
    LoadedScene loaded = loadScene(path);
    turnSceneUp(loaded, upAxis.value_or(loaded.scene.upAxis));
    const auto normalsStart = std::chrono::steady_clock::now();
    smoothNormals(loaded.scene, crease);
    if (normalsMs)
        *normalsMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - normalsStart).count();
    scaleExponent = renderScaleExponent(loaded.scene);
    rescaleScene(loaded.scene, scaleExponent);
    if (loaded.accel && scaleExponent != 0) loaded.accel = loaded.accel->rescaled(scaleExponent);
    return loaded;
}

}  // namespace gpurt
