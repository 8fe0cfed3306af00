// A glTF file's bytes as the JSON rewrites before tinygltf see them (GltfDraco's, GltfMeshopt's):
// its JSON text, and for a GLB the chunks after it; and the file again with another JSON text.
#pragma once

#include <string>

namespace gpurt {

struct GltfParts {
    bool glb = false;
    std::string json;  // the JSON text (a GLB's JSON chunk)
    std::string rest;  // GLB: the chunks after the JSON chunk (the BIN chunk), as they are
};

// False for a GLB whose JSON chunk is missing or longer than the file (tinygltf then says what is
// wrong with it).
bool splitGltf(const std::string& bytes, GltfParts& parts);

// The file with `json` as its JSON text: the text itself, or the GLB with its JSON chunk replaced
// (padded with spaces to 4 bytes) and the header's length set. `bytes` when a GLB would pass 4 GiB.
std::string joinGltf(const GltfParts& parts, std::string json, const std::string& bytes);

// A GLB's BIN chunk (the first chunk of `rest` when its type is BIN); false when there is none.
bool glbBinChunk(const GltfParts& parts, std::string& bin);

}  // namespace gpurt
