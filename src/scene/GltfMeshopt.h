// glTF's EXT_meshopt_compression (the extension's specification, revision 1): buffer views whose
// data is meshoptimizer's vertex or index codec, decoded by Debian's libmeshoptimizer (decode
// only) before tinygltf reads the file, so that the rest of the loader sees plain buffer views.
#pragma once

#include <filesystem>
#include <string>

namespace gpurt {

// The glTF file `bytes` (JSON or binary) with every buffer view that EXT_meshopt_compression
// compresses decoded into a buffer of its own (a data URI) and the extension taken out of the
// file: its views point there, its fallback buffers (no data, "fallback": true) become empty
// placeholders, and extensionsUsed / extensionsRequired no longer name it. The bytes unchanged
// when the file does not use it. The compressed data is read from the file's buffers (a GLB's
// binary chunk, data URIs, files in `folder`). Throws InputError naming `name` and the buffer
// view for data that is missing, out of range or does not decode.
std::string withMeshoptDecoded(const std::string& bytes, const std::string& name, const std::filesystem::path& folder);

}  // namespace gpurt
