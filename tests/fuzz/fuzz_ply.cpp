// libFuzzer target for the PLY reader (parsePly, the in-memory loadPly): any input must give a
// scene or an InputError, never a crash, a sanitizer report, a hang or another exception; an
// accepted scene then goes through the CPU pipeline (FuzzScene.h). Differential too: the parallel
// ASCII reader, on 2 threads in chunks of 7 bytes, must give the serial reader's scene bit for bit,
// or its error word for word; a difference aborts.
//   build-fuzz/tests/fuzz/fuzz_ply -dict=tests/fuzz/ply.dict CORPUS_DIR tests/fuzz/corpus/ply
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "FuzzScene.h"
#include "image/InputError.h"
#include "scene/PlyLoader.h"

namespace {

// The scene or the error's message ("" and the scene when accepted).
std::string readPly(const std::string& bytes, const gpurt::PlyReadOptions& options, gpurt::Scene& scene) {
    try {
        scene = gpurt::parsePly(bytes, "fuzz.ply", options);
    } catch (const gpurt::InputError& e) {
        return std::string("error: ") + e.what();
    }
    return "";
}

template <typename T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gpurt::fuzz::silenceWarnings();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    gpurt::Scene scene, serial;
    const std::string error = readPly(bytes, gpurt::PlyReadOptions{true, 2, 7}, scene);
    const std::string serialError = readPly(bytes, gpurt::PlyReadOptions{false, 1, 0}, serial);
    if (error != serialError) std::abort();
    if (!error.empty()) return 0;
    if (!sameBits(scene.triangles, serial.triangles) || !sameBits(scene.normals, serial.normals) ||
        !sameBits(scene.colors, serial.colors) || scene.materialIds != serial.materialIds)
        std::abort();
    gpurt::fuzz::exerciseScene(scene);
    return 0;
}
