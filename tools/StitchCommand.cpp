// `gpurt stitch -o OUT TILE...`: assembles the tiles of one output of a render (--tile I/N) into
// the whole image, byte for byte what the whole render writes (raytrace/Tiles.h).
#include "Commands.h"
#include "CommonOptions.h"

#include "image/Tiles.h"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace gpurt {

void addStitchCommand(CLI::App& app, std::function<int()>& run) {
    struct Options {
        std::string output;
        std::vector<std::string> tiles;
    };
    auto o = std::make_shared<Options>();
    auto* cmd = app.add_subcommand("stitch", "Assemble the tiles of one output (gpurt render --tile I/N) into the whole image");
    cmd->add_option("-o,--output", o->output, "The whole image (.png, or .pfm for an AOV)")->required()->check(kNotEmpty);
    cmd->add_option("tiles", o->tiles, "The tiles' files (each with its FILE.tile sidecar), in any order")
        ->required()
        ->check(kNotEmpty);
    cmd->callback([&run, o] {
        run = [o] {
            std::vector<std::filesystem::path> tiles(o->tiles.begin(), o->tiles.end());
            stitchTiles(o->output, tiles);
            return 0;
        };
    });
}

}  // namespace gpurt
