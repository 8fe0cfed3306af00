// What every scene reader does before and around parsing: the checks that a path names a file a
// reader can read, reading it whole, bytes shown as one printable line, and the mesh readers
// chosen by content (OBJ or PLY).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "base/LargeArray.h"
#include "scene/Scene.h"

namespace gpurt {

// A regular file or a pipe: a device such as /dev/zero would be read forever.
bool isReadableKind(const std::filesystem::file_status& status);

// Throws InputError "FILE: no such file", "FILE: is a directory, not a scene file" or "FILE: is a
// device or socket, not a scene file" (a device such as /dev/zero would be read forever; pipes are
// fine).
void checkSceneFile(const std::filesystem::path& path);

// checkSceneFile, then the whole file (its real size sizes the buffer, never a field of it).
// Throws InputError "FILE: cannot read (...)".
std::string readSceneFile(const std::filesystem::path& path);

// readSceneFile into an array of huge pages (LargeArray.h), for a big mesh's bytes: no zeroing
// and no 4 KiB page faults before the file's own bytes are written.
LargeArray<char> readSceneBytes(const std::filesystem::path& path);

// Text or file bytes as one line of ASCII: other bytes as \xNN.
std::string printable(std::string_view text);

// A mesh file (a JSON scene's mesh): a PLY by content ("ply" and a line end) or by a .ply name,
// else an OBJ. Throws the reader's InputError.
Scene loadMesh(const std::filesystem::path& path);

}  // namespace gpurt
