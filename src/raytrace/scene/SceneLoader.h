// One entry point for every way of giving a scene (CONTRACT.md: an OBJ, a scene JSON or a packed
// file), recognised by content rather than by extension.
#pragma once

#include <filesystem>
#include <optional>

#include <glm/glm.hpp>

#include "scene/Scene.h"
#include "raytrace/accel/Accelerator.h"

namespace gpurt {

// The first bytes of a file written by `gpurt pack`.
inline constexpr char kPackedSceneMagic[] = "GPRTSCN1";  // 8 bytes, no terminator in the file

struct LoadedScene {
    Scene scene;
    std::optional<glm::ivec2> size;  // the image size the scene file asks for, if any
    // A packed scene's prebuilt acceleration structure, the one its packing chose
    // (readPackedScene); none for the other formats, whose structure the renderer builds.
    std::shared_ptr<const AccelStructure> accel;
};

// Reads a scene file: the packed magic at byte 0 -> packed scene (readPackedScene, with its
// grid; "GPRTSCN" followed by another character too, which the reader refuses); "ply" and a line
// end -> PLY (loadPly); "glTF" -> binary glTF (loadGltf); a name ending .gpscene, .ply, .gltf or
// .glb -> that reader, which refuses what is not its format; a first non-whitespace byte '{' (after an
// optional UTF-8 byte order mark) -> JSON scene (loadJsonSceneFile); anything else -> OBJ (loadObj),
// which refuses a text file without an OBJ statement. Throws InputError "FILE: no such file",
// "FILE: is a directory ...", "FILE: cannot read ..." or the chosen loader's message
// (readPackedScene, loadJsonSceneFile, loadObj).
LoadedScene loadScene(const std::filesystem::path& path);

// Turns the loaded scene so that `axis` is up (rotateUpToY), with its acceleration structure
// (AccelStructure::turnedUp, exact: a packed BVH's boxes, a packed grid's box and cells).
void turnSceneUp(LoadedScene& loaded, UpAxis axis);

// The scene as the renderers take it (render, view): loaded (loadScene), turned up (`upAxis`, else
// the file's own up axis), with smooth normals for the crease angle (< 0: faceted; smoothNormals),
// and, far from unit size where float32 tracing would over- or underflow, rescaled by
// 2^-scaleExponent with its accelerator (SceneScale.h: the same image). normalsMs: the time the
// normals took.
LoadedScene prepareScene(const std::filesystem::path& path, std::optional<UpAxis> upAxis, float crease,
                         int& scaleExponent, double* normalsMs = nullptr);

}  // namespace gpurt
