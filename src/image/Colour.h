// The colour pipeline of the PNG (CONTRACT.md): linear radiance times 2^EV, a tone map, then sRGB
// (writePng). The operations are glsl/common/colour.h's, shared with the kernels.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace gpurt {

enum class ToneMap { Clamp, Reinhard, Aces };

const char* toneMapName(ToneMap mode);
bool parseToneMap(const std::string& text, ToneMap& mode);  // clamp, reinhard, aces

struct ColourSettings {
    float exposure = 0.0f;  // EV: the linear colour is multiplied by 2^exposure
    ToneMap toneMap = ToneMap::Aces;
};

// The tone map as the GPURT_TONEMAP_* code of glsl/common/colour.h (for kernels), and 2^EV.
int toneMapCode(ToneMap mode);
float exposureScale(float exposure);

// The sRGB transfer function of one display-linear value in [0, 1] (colour.h srgbEncode).
float encodeSrgb(float displayLinear);
// Its inverse (IEC 61966-2-1): the linear value of an sRGB-encoded one in [0, 1] (the operations of
// glsl/common/texture.h srgbDecode8, for the readers of encoded colours: PLY vertex colours).
float decodeSrgb(float encoded);

// Display-linear colour in [0, 1] per pixel (what writePng sRGB-encodes) from linear radiance.
// NaN channels give 0.
std::vector<glm::vec3> toneMapImage(const std::vector<glm::vec3>& linear, const ColourSettings& settings);

}  // namespace gpurt
