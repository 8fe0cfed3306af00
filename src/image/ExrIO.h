// OpenEXR files (Debian libopenexr-dev): the render as linear half-float RGB, AOVs as 32-bit
// float channels, written atomically like the other outputs, and read back (stitch, tests).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace gpurt {

class AtomicFileSet;

// The channels of an EXR output: "exr" (the render: R, G, B as half), or an AOV's name: depth
// (Z), prim (prim), steps (steps), normal and shading_normal (X, Y, Z), color, variance and albedo
// (R, G, B), all 32-bit float.
struct ExrLayout {
    std::vector<std::string> channels;
    bool half = false;
};
ExrLayout exrLayout(const std::string& output);

// `topFirst`: width * height * channels values, row-major, top row first, channels interleaved in
// the layout's order. ZIP compression (lossless), scanlines from the top. Throws InputError naming
// the file when it cannot be written.
void writeExr(AtomicFileSet& files, const std::filesystem::path& path, int width, int height,
              const ExrLayout& layout, const std::vector<float>& topFirst);

// The values as the file stores them (rounded to half where the layout says so): what reading
// the file back gives, and what a tile's CRC covers.
std::vector<float> exrStored(const ExrLayout& layout, std::vector<float> values);

// Reads the layout's channels of an EXR file, interleaved in its order, top row first. Throws
// InputError naming the file when it is not a readable EXR, lacks a channel or has another type.
std::vector<float> readExr(const std::filesystem::path& path, const ExrLayout& layout, int& width, int& height);

}  // namespace gpurt
