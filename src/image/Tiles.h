// Tiles of one image as units of work (--tile I/N, `gpurt stitch`; CONTRACT.md, tiles and
// frames). Each output a tile render writes (the PNG, every AOV) gets a sidecar FILE.tile naming
// its place in the whole image, a fingerprint of everything that decides its pixels (scene,
// camera, size, samples, options) and a CRC-32 of its pixel data; stitch refuses tiles that are
// missing, repeated, of another image or damaged, and writes the whole image with the same
// writers as a whole render, so the result is byte-identical to it. Frames of an animation
// (--frames A:B) are the other unit: each frame's files are named by a printf-style pattern.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace gpurt {

class AtomicFileSet;

struct TileInfo {
    std::string output;  // "png", or the AOV's name (depth, prim, normal, steps, color)
    int tile = 0, tiles = 1;
    int width = 0, height = 0;  // the whole image
    int row = 0, rows = 0;      // the tile's rows of it
    std::string fingerprint;    // of the whole render's inputs
    uint32_t crc = 0;           // CRC-32 of the tile's pixel data (8-bit RGB, or float32 values)
};

// The sidecar of a tile output file: FILE + ".tile".
std::filesystem::path tileSidecar(const std::filesystem::path& file);

// CRC-32 (zlib) of bytes, continuing from `crc`.
uint32_t crc32Of(const void* data, size_t bytes, uint32_t crc = 0);

// Adds the sidecar of `file` to the set, so that tile and sidecar appear together.
void addTileSidecar(AtomicFileSet& files, const std::filesystem::path& file, const TileInfo& info);

// Assembles the tiles (their files; each with its sidecar) into `output` (.png or .pfm, as the
// tiles). Throws InputError naming the tile (or the missing tile's index) when they do not make
// one image: a sidecar missing or malformed, a file damaged, tiles of another image, repeated or
// missing tiles.
void stitchTiles(const std::filesystem::path& output, const std::vector<std::filesystem::path>& tiles);

// --frames A:B: 0 <= A <= B <= 999999 (both inclusive); InputError naming the option otherwise.
void parseFrames(const std::string& text, int& first, int& last);

// A file name pattern with exactly one frame number in printf's style, `%d` or `%0Nd` (N 1..9), and
// `%%` for a percent sign: checked by checkFramePattern (InputError naming the pattern and
// `option`), filled in by frameFileName.
void checkFramePattern(const std::string& option, const std::string& pattern);
std::string frameFileName(const std::string& pattern, int frame);

}  // namespace gpurt
