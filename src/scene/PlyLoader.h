// Stanford PLY meshes (ASCII, binary little and big endian) into a Scene: vertex positions,
// optional vertex normals, faces as index lists fanned as the contract says (CONTRACT.md, triangle
// numbering: the faces in file order, (v0, vi, vi+1)). A small strict reader of our own: the
// format is one page long, and the field's readers (Assimp, rply, tinyply, happly) accept headers
// that do not match their data (short files padded with zeros, counts larger than the file,
// trailing bytes), which gpurt must refuse with the file's name.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "scene/Scene.h"

namespace gpurt {

// Reads a PLY file: every element the header declares, in order, with every property (those gpurt
// does not use, like the Stanford scans' confidence and intensity, or whole elements such as edges,
// are read and skipped, and named in one warning; the vertex's s, t, u, v and alpha are not named).
// Uses vertex x, y, z (required), nx, ny, nz (all three or none), red, green, blue (all three, else
// unused: sRGB-encoded display colours, integers over their type's largest value, floats in
// [0, 1], decoded to linear vertex colours), the face list vertex_indices (or vertex_index) and
// the tristrips list vertex_indices (strips with -1 restarts, OpenGL's alternating order, the
// triangles with a vertex twice skipped). Faces and strips become triangles in the order of their
// elements. Every triangle gets the default material. A file that makes no triangle is read with a
// warning naming it. Throws InputError naming the file (and the header line, the ASCII line, or
// the element and byte offset) for a file that is not PLY, a header that does not match its data
// (a short file, trailing data, a count the file cannot hold), a face of fewer than 3 vertices, an
// index out of range and non-finite positions, normals or colours.
Scene loadPly(const std::filesystem::path& path);

// How parsePly reads an ASCII file: on `threads` threads (0: all cores) in chunks of about
// `chunkBytes` cut at line starts, or (parallel false) with the serial reader alone. The result,
// and the error for a bad file, are the same either way (the tests cut at awkward places).
struct PlyReadOptions {
    bool parallel = true;
    int threads = 0;
    size_t chunkBytes = size_t(1) << 20;
};

// loadPly on bytes already in memory; `name` names the file in messages (the fuzz target).
Scene parsePly(const std::string& bytes, const std::string& name, const PlyReadOptions& options = {});

// Whether `bytes` start like a PLY file ("ply" and a line end).
bool looksLikePly(const std::string& head);

}  // namespace gpurt
