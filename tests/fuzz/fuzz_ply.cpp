// libFuzzer target for the PLY reader (parsePly, the in-memory loadPly): any input must give a
// scene or an InputError, never a crash, a sanitizer report, a hang or another exception; an
// accepted scene then goes through the CPU pipeline (FuzzScene.h).
//   build-fuzz/tests/fuzz/fuzz_ply -dict=tests/fuzz/ply.dict CORPUS_DIR tests/fuzz/corpus/ply
#include <cstddef>
#include <cstdint>
#include <string>

#include "FuzzScene.h"
#include "image/InputError.h"
#include "scene/PlyLoader.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gpurt::fuzz::silenceWarnings();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    gpurt::Scene scene;
    try {
        scene = gpurt::parsePly(std::string(reinterpret_cast<const char*>(data), size), "fuzz.ply");
    } catch (const gpurt::InputError&) {
        return 0;
    }
    gpurt::fuzz::exerciseScene(scene);
    return 0;
}
