// Environment maps in (CONTRACT.md, "Environment light and the default light"): a Radiance .hdr
// (RGBE, read with Debian libstb-dev's stb_image) or an OpenEXR .exr (its R, G and B channels, half
// or float, read with OpenEXR) as linear RGB, latitude-longitude, top row first.
//
// Hostile input: a missing, truncated or unreadable file, a map of zero size or larger than
// kMaxEnvironmentWidth x kMaxEnvironmentHeight, and a texel that is NaN or infinite are refused
// with InputError naming the file (and the texel); negative texels (EXR can hold them) are clamped
// to 0, and channels above kMaxEnvironmentRadiance (RGBE reaches 1.7e38) to it, each with one
// warning naming the file.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace gpurt {

// The largest map read: 16384 x 8192 texels (a 16k lat-long; GL_MAX_TEXTURE_SIZE on llvmpipe).
constexpr int kMaxEnvironmentWidth = 16384;
constexpr int kMaxEnvironmentHeight = 8192;
// The largest radiance kept: sums over the map (its harmonics, 4 pi x radiance) stay finite in float.
constexpr float kMaxEnvironmentRadiance = 1e30f;

struct EnvironmentImage {
    int width = 0, height = 0;
    std::vector<glm::vec3> texels;  // width * height, row-major, top row first, linear RGB
};

// Reads `path` by its extension (.hdr / .pic: Radiance, .exr: OpenEXR; any other is refused).
EnvironmentImage readEnvironmentImage(const std::filesystem::path& path);
// The same from bytes in memory (the fuzz target; `name` names them in errors); `exr` chooses the
// reader.
EnvironmentImage decodeEnvironmentImage(const std::string& bytes, const std::string& name, bool exr);
// Checks the size and the texels as readEnvironmentImage does (InputError naming `name`); clamps
// negative texels to 0.
void checkEnvironmentImage(EnvironmentImage& image, const std::string& name);

// Writes a Radiance .hdr (flat RGBE scanlines) of `image` (tests and scripts; not atomic).
void writeHdr(const std::filesystem::path& path, const EnvironmentImage& image);

}  // namespace gpurt
