// libFuzzer target for the tile sidecar reader behind `gpurt stitch` (stitchTiles): the input is
// taken as the sidecar tile.pfm.tile of a fixed 4x3 one-channel tile, tile.pfm, in the scratch
// folder; stitching it must give the whole image or an InputError, never a crash, a sanitizer
// report or another exception. The seed (corpus/tile) describes the tile correctly as tile 0 of 1.
//   build-fuzz/tests/fuzz/fuzz_tile -dict=tests/fuzz/tile.dict CORPUS_DIR tests/fuzz/corpus/tile
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "FuzzScene.h"
#include "image/ImageIO.h"
#include "image/InputError.h"
#include "image/Tiles.h"

namespace {

const std::filesystem::path& tileFile() {
    static const std::filesystem::path path = [] {
        const std::filesystem::path p = gpurt::fuzz::scratchFolder() / "tile.pfm";
        std::vector<float> values(12);
        for (size_t k = 0; k < values.size(); ++k) values[k] = float(k);  // rows top first: 0..3, 4..7, 8..11
        gpurt::writePfm(p, 4, 3, 1, values);
        return p;
    }();
    return path;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gpurt::fuzz::scratchFolder();
    gpurt::fuzz::silenceWarnings();
    tileFile();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::ofstream(gpurt::tileSidecar(tileFile()), std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), std::streamsize(size));
    try {
        gpurt::stitchTiles(gpurt::fuzz::scratchFolder() / "out.pfm", {tileFile()});
    } catch (const gpurt::InputError&) {
    }
    return 0;
}
