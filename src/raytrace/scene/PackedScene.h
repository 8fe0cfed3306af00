// Packed scene files (`gpurt pack`, docs/PACKED_FORMAT.md): the scene and its prebuilt
// acceleration structure in one little-endian binary file with a magic number, a format version, a section table
// and a CRC-32, so that a render loads the grid instead of building it. The reader trusts nothing
// it has not checked: every problem is an InputError naming the file, never a crash or an
// allocation sized by an unchecked field.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "raytrace/scene/SceneLoader.h"
#include "raytrace/accel/Accelerator.h"

namespace gpurt {

// The format version this gpurt writes and the only one it reads.
inline constexpr uint32_t kPackedSceneVersion = 2;  // 2: materials carry their emission
// Bytes before the section table, and bytes per section table entry.
inline constexpr size_t kPackedHeaderBytes = 32;
inline constexpr size_t kPackedSectionEntryBytes = 24;

// The file's bytes for `scene` (its scene and image size; scene.accel is ignored) and `accel`,
// which must have been built for scene.scene (a file holds one structure, the one `gpurt pack
// --accel` chose; its accelerator writes its sections). Deterministic: the bytes depend only on
// the arguments. Throws InputError("NAME: ...") when the scene cannot be packed: the limits the
// reader enforces (at most kMaxTextureTriangles triangles, material ids in range, finite values,
// a well-formed structure that contains the scene, ...); `name` names the scene in those messages.
std::vector<unsigned char> encodePackedScene(const LoadedScene& scene, const AccelStructure& accel,
                                             const std::string& name);

// Writes encoded bytes atomically to `path` (a temporary file in the same folder, renamed), so
// the file appears whole or not at all. Throws InputError("PATH: cannot ...").
void writePackedScene(const std::filesystem::path& path, std::span<const unsigned char> bytes);

// encodePackedScene, then written as above.
void writePackedScene(const std::filesystem::path& path, const LoadedScene& scene, const AccelStructure& accel,
                      const std::string& name);

// Decodes and validates a packed file's bytes; the result's accel is the structure it holds. Throws
// InputError("NAME: what is wrong") for a wrong magic, an unknown version, a truncated file, a
// checksum mismatch, a bad section table, sizes that do not fit the file or the GL limits, counts
// that overflow, non-finite values, out-of-range material or triangle ids, unknown material
// models and an inconsistent grid.
LoadedScene decodePackedScene(std::span<const unsigned char> bytes, const std::string& name);

// Reads `path` whole and decodes it (decodePackedScene with the path as the name).
LoadedScene readPackedScene(const std::filesystem::path& path);

}  // namespace gpurt
