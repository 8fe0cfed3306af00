// libFuzzer target for the OBJ reader (parseObj, the in-memory loadObj): any input must give a
// scene or an InputError, never a crash, a sanitizer report or another exception; an accepted
// scene then goes through the CPU pipeline (FuzzScene.h). Input is read as if it were the file
// fuzz.obj in the scratch folder, so "mtllib a.mtl" finds a real material library; what follows a
// line "%%mtl" is written to fuzz.mtl there first, for "mtllib fuzz.mtl" (the MTL reader's input).
//   build-fuzz/tests/fuzz/fuzz_obj -dict=tests/fuzz/obj.dict CORPUS_DIR tests/fuzz/corpus/obj
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include "FuzzScene.h"
#include "image/InputError.h"
#include "scene/ObjLoader.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gpurt::fuzz::scratchFolder();
    gpurt::fuzz::silenceWarnings();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string obj(reinterpret_cast<const char*>(data), size);
    const size_t split = obj.find("\n%%mtl\n");
    const std::string mtl = split == std::string::npos ? std::string() : obj.substr(split + 7);
    static std::string written = "(none yet)";
    if (mtl != written) {  // writing a file for every input would halve the inputs per second
        std::ofstream(gpurt::fuzz::scratchFolder() / "fuzz.mtl", std::ios::binary) << mtl;
        written = mtl;
    }
    if (split != std::string::npos) obj.resize(split + 1);
    gpurt::Scene scene;
    try {
        scene = gpurt::parseObj(obj, gpurt::fuzz::scratchFolder() / "fuzz.obj");
    } catch (const gpurt::InputError&) {
        return 0;
    }
    gpurt::fuzz::exerciseScene(scene);
    return 0;
}
