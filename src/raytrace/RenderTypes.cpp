#include "raytrace/RenderTypes.h"

#include "raytrace/RayMath.h"

#include <algorithm>
#include <cmath>

namespace gpurt {

uint32_t defaultMinSamples(float noiseThreshold) {
    if (!(noiseThreshold > 0.0f)) return 0;
    return std::max(4u, uint32_t(std::ceil(16.0f / std::pow(noiseThreshold, 0.3f))));
}

bool adaptiveCheckAfter(uint32_t taken, const RenderSettings& settings) {
    if (!settings.adaptive() || taken >= settings.samples || taken < settings.minSamples) return false;
    return taken == settings.minSamples || taken % GPURT_ADAPTIVE_STEP == 0;
}

glm::vec3 varianceOfMean(glm::vec3 sum, glm::vec3 squares, float n) {
    if (!(n >= 2.0f)) return glm::vec3(0.0f);
    const glm::vec3 mean = sum / n;
    return glm::max(squares / n - mean * mean, glm::vec3(0.0f)) / (n - 1.0f);
}

}  // namespace gpurt
