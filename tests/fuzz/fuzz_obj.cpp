// libFuzzer target for the OBJ reader (parseObj, the in-memory loadObj): any input must give a
// scene or an InputError, never a crash, a sanitizer report or another exception; an accepted
// scene then goes through the CPU pipeline (FuzzScene.h). Input is read as if it were the file
// fuzz.obj in the scratch folder, so "mtllib a.mtl" finds a real material library.
//   build-fuzz/tests/fuzz/fuzz_obj -dict=tests/fuzz/obj.dict CORPUS_DIR tests/fuzz/corpus/obj
#include <cstddef>
#include <cstdint>
#include <string>

#include "FuzzScene.h"
#include "raytrace/InputError.h"
#include "raytrace/ObjLoader.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gpurt::fuzz::scratchFolder();
    gpurt::fuzz::silenceWarnings();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    gpurt::Scene scene;
    try {
        scene = gpurt::parseObj(std::string(reinterpret_cast<const char*>(data), size),
                                gpurt::fuzz::scratchFolder() / "fuzz.obj");
    } catch (const gpurt::InputError&) {
        return 0;
    }
    gpurt::fuzz::exerciseScene(scene);
    return 0;
}
