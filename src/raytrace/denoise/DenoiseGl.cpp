#include "raytrace/denoise/DenoiseGl.h"

#include "stream/StreamErrors.h"

#include <chrono>

namespace gpurt {

namespace {

std::vector<float> asTexels(const std::vector<glm::vec3>& v) {
    std::vector<float> out(v.size() * 4, 0.0f);
    for (size_t i = 0; i < v.size(); ++i)
        for (int c = 0; c < 3; ++c) out[4 * i + size_t(c)] = v[i][c];
    return out;
}

}  // namespace

DenoiserGl::DenoiserGl(int width, int height)
    : width_(width),
      height_(height),
      colorIn_(width, height, 4, "denoiseColor"),
      varianceIn_(width, height, 4, "denoiseVariance"),
      albedoIn_(width, height, 4, "denoiseAlbedoIn"),
      normalIn_(width, height, 4, "denoiseNormalIn"),
      signal_(width, height, 4, "denoiseSignal"),
      albedo_(width, height, 4, "denoiseAlbedo"),
      normal_(width, height, 4, "denoiseNormal"),
      output_(width, height, 4, "denoised"),
      demodulate_("denoiseDemodulate", "denoise/demodulate.frag"),
      demodulateSums_("denoiseDemodulate", "denoise/demodulate.frag", {"SUMS"}),
      atrous_("denoiseAtrous", "denoise/atrous.frag"),
      remodulate_("denoiseAtrous", "denoise/atrous.frag", {"REMODULATE"}) {
    demodulate_.addInput(colorIn_, "colorIn").addInput(varianceIn_, "varianceIn");
    demodulate_.addInput(albedoIn_, "albedoIn").addInput(normalIn_, "normalIn");
    for (GPUKernel* k : {&demodulate_, &demodulateSums_})
        k->addOutput(signal_).addOutput(albedo_).addOutput(normal_).setPreserveUnwritten(false);
    for (GPUKernel* k : {&atrous_, &remodulate_})
        k->addInput(signal_, "signal").addInput(albedo_, "albedoGuide").addInput(normal_, "normalGuide");
    atrous_.addOutput(signal_).setPreserveUnwritten(false);
    remodulate_.addOutput(output_).setPreserveUnwritten(false);
}

std::vector<glm::vec3> DenoiserGl::denoise(const DenoiseImages& in, DenoiseStats* stats) {
    checkDenoiseImages(in);
    if (in.width != width_ || in.height != height_) throw UsageError("DenoiserGl: images of another size");
    const auto start = std::chrono::steady_clock::now();
    colorIn_.upload(asTexels(in.color));
    varianceIn_.upload(asTexels(denoiseVariance(in)));
    albedoIn_.upload(asTexels(in.albedo));
    std::vector<float> normal = asTexels(in.normal);
    if (!in.depth.empty())
        for (size_t i = 0; i < in.depth.size(); ++i) normal[4 * i + 3] = in.depth[i];
    normalIn_.upload(normal);
    demodulate_.dispatch();
    iterate();
    const std::vector<float> texels = output_.download();
    std::vector<glm::vec3> out(size_t(width_) * size_t(height_));
    for (size_t i = 0; i < out.size(); ++i) out[i] = glm::vec3(texels[4 * i], texels[4 * i + 1], texels[4 * i + 2]);
    if (stats) {
        stats->refused = refusedPixels(in);
        stats->ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    return out;
}

void DenoiserGl::bindSums(const GPUFloatArray& sampleSum, const GPUFloatArray& squareSum, const GPUFloatArray& albedoSum,
                          const GPUFloatArray& normalSum, const GPUFloatArray& aovHit) {
    if (sumsBound_) throw UsageError("DenoiserGl::bindSums: bound already");
    demodulateSums_.addInput(sampleSum, "sampleSum").addInput(squareSum, "squareSum");
    demodulateSums_.addInput(albedoSum, "albedoSum").addInput(normalSum, "normalSum").addInput(aovHit, "aovHit");
    sumsBound_ = true;
}

void DenoiserGl::denoiseSums() {
    if (!sumsBound_) throw UsageError("DenoiserGl::denoiseSums before bindSums");
    demodulateSums_.dispatch();
    iterate();
}

std::vector<glm::vec3> denoise(Backend backend, const DenoiseImages& in, int threads, DenoiseStats* stats) {
    if (backend == Backend::Cpu) return denoiseCpu(in, threads, stats);
    checkDenoiseImages(in);
    DenoiserGl denoiser(in.width, in.height);
    return denoiser.denoise(in, stats);
}

// The iterations with holes of 1, 2, 4... pixels; the last remodulates into the output.
void DenoiserGl::iterate() {
    const int iterations = denoiseIterations(width_, height_);
    for (int i = 0; i < iterations; ++i) {
        GPUKernel& k = i + 1 < iterations ? atrous_ : remodulate_;
        k.setUniform("stride", 1 << i).dispatch();
    }
}

}  // namespace gpurt
