// libFuzzer target for the JSON scene reader (parseJsonScene, the in-memory loadJsonSceneFile):
// any input must give a scene or an InputError, never a crash, a sanitizer report or another
// exception; an accepted scene then goes through the CPU pipeline (FuzzScene.h). Input is read as
// if it were the file fuzz.json in the scratch folder, so meshes can name tri.obj, quad.obj,
// bad.obj and empty.obj.
//   build-fuzz/tests/fuzz/fuzz_json -dict=tests/fuzz/json.dict CORPUS_DIR tests/fuzz/corpus/json
#include <cstddef>
#include <cstdint>
#include <string>

#include "FuzzScene.h"
#include "image/InputError.h"
#include "scene/JsonScene.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gpurt::fuzz::scratchFolder();
    gpurt::fuzz::silenceWarnings();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    gpurt::JsonSceneFile file;
    try {
        file = gpurt::parseJsonScene(std::string(reinterpret_cast<const char*>(data), size),
                                     gpurt::fuzz::scratchFolder() / "fuzz.json");
    } catch (const gpurt::InputError&) {
        return 0;
    }
    gpurt::fuzz::exerciseScene(file.scene);
    return 0;
}
