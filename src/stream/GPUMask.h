// Masking: restricts a kernel to the stream elements whose state is in a given range, read from
// one channel of a state stream (e.g. ray state == WAIT).
//
//   EarlyZ    the seed's way (Purcell 2002): a mask pass writes depth 0 where the state matches
//             and 1 elsewhere; the kernel draws at depth 0.5 with GL_GREATER, so the early depth
//             test rejects masked elements before shading.
//   Stencil   the mask pass writes stencil 1 where the state matches; the kernel runs with
//             glStencilFunc(GL_EQUAL, 1).
//   EarlyExit no mask pass: the kernel's main is wrapped so that it first reads the state and
//             discards non-matching elements.
// On Mesa llvmpipe all three skip work only for 4x2 blocks whose 8 pixels are all masked
// (../shared/LLVMPIPE.md); docs/PERFORMANCE.md has the measurements behind the default.
#pragma once

#include "stream/GPUFloatArray.h"
#include "stream/GPUProgram.h"
#include "stream/GPUQuery.h"
#include "stream/GPUStreamGenerator.h"

#include <optional>
#include <string>

namespace gpurt {

enum class MaskMode { None, EarlyZ, Stencil, EarlyExit };

const char* maskModeName(MaskMode mode);
bool parseMaskMode(const std::string& text, MaskMode& mode);
// The fastest mode for the current driver, from the measurements in docs/PERFORMANCE.md.
MaskMode defaultMaskMode();

// How a kernel is wrapped for MaskMode::EarlyExit: the preamble renames its main to
// gpu_kernelMain, the epilogue adds the mask condition and a main that tests it first.
struct EarlyExitWrapping {
    std::string preamble;
    std::string epilogue;
};
EarlyExitWrapping earlyExitWrapping();

class GPUMask {
  public:
    // Elements with lo <= state[channel] <= hi are active. `state` must outlive the mask.
    GPUMask(std::string name, MaskMode mode, const GPUFloatArray& state, int channel, float lo,
            float hi);
    GPUMask(std::string name, MaskMode mode, const GPUPingPongArray& state, int channel, float lo,
            float hi);
    ~GPUMask();
    GPUMask(const GPUMask&) = delete;
    GPUMask& operator=(const GPUMask&) = delete;

    MaskMode mode() const { return mode_; }
    const std::string& name() const { return name_; }
    const GPUFloatArray& state() const { return pingPong_ ? pingPong_->front() : *state_; }
    int channel() const { return channel_; }
    float lo() const { return lo_; }
    float hi() const { return hi_; }
    void setRange(float lo, float hi);

    // EarlyZ / Stencil: runs the mask pass, writing the depth-stencil buffer from the current
    // state. A no-op for EarlyExit and None.
    void update();
    // update(), then the number of active elements (the mask pass's occlusion count; blocks).
    // EarlyExit / None have no mask pass: returns std::nullopt.
    std::optional<uint64_t> updateAndCount();
    // The depth-stencil texture kernels attach (0 for EarlyExit / None).
    GLuint depthStencil() const { return depthStencil_; }

  private:
    void init();

    std::string name_;
    MaskMode mode_;
    const GPUFloatArray* state_ = nullptr;
    const GPUPingPongArray* pingPong_ = nullptr;
    int channel_;
    float lo_, hi_;
    GLuint depthStencil_ = 0;
    GLuint framebuffer_ = 0;
    std::optional<GPUProgram> program_;
    std::optional<GPUQuery> counter_;
    GPUStreamGenerator generator_;
};

}  // namespace gpurt
