// libFuzzer target for the packed-scene reader (decodePackedScene, the in-memory
// readPackedScene): any input must give a scene or an InputError, never a crash, a sanitizer
// report or another exception; an accepted scene and its own grid then go through the CPU
// pipeline (FuzzScene.h). Almost every mutation breaks the CRC-32, so each input is also tried
// with its CRC recomputed, which lets the fuzzer reach the checks behind it.
//   build-fuzz/tests/fuzz/fuzz_packed CORPUS_DIR tests/fuzz/corpus/packed
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <zlib.h>

#include "FuzzScene.h"
#include "image/InputError.h"
#include "raytrace/scene/PackedScene.h"

namespace {

void tryDecode(std::span<const unsigned char> bytes) {
    gpurt::LoadedScene loaded;
    try {
        loaded = gpurt::decodePackedScene(bytes, "fuzz.gpscene");
    } catch (const gpurt::InputError&) {
        return;
    }
    gpurt::fuzz::exerciseScene(loaded.scene, loaded.accel.get());
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gpurt::fuzz::silenceWarnings();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    tryDecode({data, size});
    // Bytes 12-15: CRC-32 of bytes 16 to the end (docs/PACKED_FORMAT.md), little-endian.
    if (size < 16) return 0;
    std::vector<unsigned char> fixed(data, data + size);
    const uLong crc = crc32(crc32(0L, Z_NULL, 0), fixed.data() + 16, uInt(size - 16));
    for (int k = 0; k < 4; ++k) fixed[12 + size_t(k)] = static_cast<unsigned char>(crc >> (8 * k));
    tryDecode(fixed);
    return 0;
}
