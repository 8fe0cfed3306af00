// Image files: the PNG of the render and the PFM AOVs of the contract. Every write is atomic: a
// temporary file in the target's folder is renamed over the target only once complete.
#pragma once

#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

namespace gpurt {

class AtomicFileSet;

// 8-bit sRGB RGB PNG from display-linear colour (clamped to [0, 1], sRGB transfer, rounded;
// toneMapImage in raytrace/Colour.h makes it from the linear radiance); row 0 of
// `linearTopFirst` is the top row. Throws InputError("<path>: ...") when it cannot be written.
void writePng(const std::filesystem::path& path, int width, int height,
              const std::vector<glm::vec3>& linearTopFirst);

// PFM as the contract defines it: "Pf" (channels = 1) or "PF" (3), "W H", "-1.0", then float32
// little-endian scanlines from the BOTTOM row to the top. `topFirst` is row-major, top row first,
// width * height * channels floats. Throws InputError("<path>: ...") when it cannot be written.
void writePfm(const std::filesystem::path& path, int width, int height, int channels,
              const std::vector<float>& topFirst);

// The same, as part of a set of files that appear together (AtomicFileSet::commit).
void writePng(AtomicFileSet& files, const std::filesystem::path& path, int width, int height,
              const std::vector<glm::vec3>& linearTopFirst);
void writePfm(AtomicFileSet& files, const std::filesystem::path& path, int width, int height,
              int channels, const std::vector<float>& topFirst);

// An 8-bit RGB PNG of pixels already encoded (a window's screenshot), top row first, atomically.
void writePngRgb8(const std::filesystem::path& path, int width, int height,
                  const std::vector<unsigned char>& rgbTopFirst);

// Reads an 8-bit PNG back as RGB, top row first (libpng). Throws InputError naming the file when
// it is not a readable PNG.
std::vector<unsigned char> readPngRgb8(const std::filesystem::path& path, int& width, int& height);

// Reads a PFM (either byte order) back into top-first rows. Throws InputError on a malformed file.
std::vector<float> readPfm(const std::filesystem::path& path, int& width, int& height,
                           int& channels);

// The 8-bit sRGB encoding of one linear channel value, as writePng stores it.
unsigned char linearToSrgb8(float linear);

}  // namespace gpurt
