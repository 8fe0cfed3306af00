#include "image/Colour.h"

#include <cmath>

#include <glm/glm.hpp>

// The kernels' tone mapping, word for word (glsl/common: the C++/GLSL headers every folder shares).
namespace gpurt::raymath {
using namespace glm;
#include "../../glsl/common/raymath.h"
#include "../../glsl/common/colour.h"
}  // namespace gpurt::raymath

namespace gpurt {

const char* toneMapName(ToneMap mode) {
    switch (mode) {
        case ToneMap::Clamp: return "clamp";
        case ToneMap::Reinhard: return "reinhard";
        case ToneMap::Aces: return "aces";
    }
    return "aces";
}

bool parseToneMap(const std::string& text, ToneMap& mode) {
    for (ToneMap m : {ToneMap::Clamp, ToneMap::Reinhard, ToneMap::Aces})
        if (text == toneMapName(m)) {
            mode = m;
            return true;
        }
    return false;
}

float encodeSrgb(float displayLinear) { return raymath::srgbEncode(displayLinear); }

float decodeSrgb(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

int toneMapCode(ToneMap mode) {
    return mode == ToneMap::Aces       ? GPURT_TONEMAP_ACES
           : mode == ToneMap::Reinhard ? GPURT_TONEMAP_REINHARD
                                       : GPURT_TONEMAP_CLAMP;
}

float exposureScale(float exposure) { return static_cast<float>(std::exp2(double(exposure))); }

std::vector<glm::vec3> toneMapImage(const std::vector<glm::vec3>& linear, const ColourSettings& settings) {
    const float scale = exposureScale(settings.exposure);
    const int mode = toneMapCode(settings.toneMap);
    std::vector<glm::vec3> display(linear.size());
    for (size_t k = 0; k < linear.size(); ++k) {
        glm::vec3 c = linear[k];
        for (int i = 0; i < 3; ++i)
            if (std::isnan(c[i])) c[i] = 0.0f;
        display[k] = raymath::toneMap(c, scale, mode);
    }
    return display;
}

}  // namespace gpurt
