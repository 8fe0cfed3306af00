#include "raytrace/common/RenderTypes.h"

#include "raytrace/common/RayMath.h"

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

glm::vec3 varianceOfMean(glm::vec3 sum, glm::vec3 squares, float n) { return raymath::sampleMeanVariance(sum, squares, n); }

}  // namespace gpurt
