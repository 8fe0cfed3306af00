// libFuzzer target for the denoiser's image reader behind `gpurt denoise` (readDenoiseImages): the
// input is written as a PFM and read as the colour, albedo and normal (and the depth, which needs
// one channel: the same file tries both counts); it must give the images and a denoised picture
// or an InputError, never a crash, a sanitizer report or another exception. The seed
// (corpus/denoise) is a 3x2 three-channel PFM.
//   build-fuzz/tests/fuzz/fuzz_denoise CORPUS_DIR tests/fuzz/corpus/denoise
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include "FuzzScene.h"
#include "image/InputError.h"
#include "raytrace/denoise/Denoise.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gpurt::fuzz::scratchFolder();
    gpurt::fuzz::silenceWarnings();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string file = (gpurt::fuzz::scratchFolder() / "image.pfm").string();
    std::ofstream(file, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), std::streamsize(size));
    for (bool depth : {false, true}) {
        try {
            const gpurt::DenoiseImages in = gpurt::readDenoiseImages({file, file, file, depth ? file : "", ""});
            if (size_t(in.width) * size_t(in.height) <= 4096) gpurt::denoiseCpu(in, 1);
        } catch (const gpurt::InputError&) {
        }
    }
    return 0;
}
