// libFuzzer target for the glTF reader (parseGltf, the in-memory loadGltf, through tinygltf): any
// input, JSON or GLB, must give a scene or an InputError, never a crash, a sanitizer report, a hang
// or another exception; an accepted scene then goes through the CPU pipeline (FuzzScene.h).
// External buffers are looked for in the scratch folder, which holds tri.bin (36 bytes: a triangle).
//   build-fuzz/tests/fuzz/fuzz_gltf -dict=tests/fuzz/gltf.dict CORPUS_DIR tests/fuzz/corpus/gltf
#include <cstddef>
#include <cstdint>
#include <string>

#include "FuzzScene.h"
#include "image/InputError.h"
#include "scene/GltfLoader.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gpurt::fuzz::scratchFolder();
    gpurt::fuzz::silenceWarnings();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    gpurt::Scene scene;
    try {
        scene = gpurt::parseGltf(std::string(reinterpret_cast<const char*>(data), size), "fuzz.gltf",
                                 gpurt::fuzz::scratchFolder());
    } catch (const gpurt::InputError&) {
        return 0;
    }
    gpurt::fuzz::exerciseScene(scene);
    return 0;
}
