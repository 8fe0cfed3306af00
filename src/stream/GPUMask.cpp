#include "stream/GPUMask.h"

#include "stream/KernelStats.h"
#include "stream/GLContext.h"
#include "stream/StreamErrors.h"

#include <chrono>

namespace gpurt {

const char* maskModeName(MaskMode mode) {
    switch (mode) {
        case MaskMode::None: return "none";
        case MaskMode::EarlyZ: return "earlyz";
        case MaskMode::Stencil: return "stencil";
        case MaskMode::EarlyExit: return "exit";
    }
    return "?";
}

bool parseMaskMode(const std::string& text, MaskMode& mode) {
    for (MaskMode m : {MaskMode::None, MaskMode::EarlyZ, MaskMode::Stencil, MaskMode::EarlyExit})
        if (text == maskModeName(m)) {
            mode = m;
            return true;
        }
    return false;
}

MaskMode defaultMaskMode() {
    // Measured on the tracer's loop (docs/PERFORMANCE.md): on llvmpipe early-Z and stencil are
    // within noise of each other and 2-4x faster than the in-shader early exit, whose SIMD code
    // still runs the kernel's loops for discarded lanes. Early-Z is the seed's method.
    return MaskMode::EarlyZ;
}

EarlyExitWrapping earlyExitWrapping() {
    return {"#define main gpu_kernelMain\n",
            "#undef main\n" + ShaderLibrary::global().read("stream/mask_condition.glsl") +
                "\nvoid main() {\n    if (!gpu_maskAccepts()) discard;\n    gpu_kernelMain();\n}\n"};
}

GPUMask::GPUMask(std::string name, MaskMode mode, const GPUFloatArray& state, int channel,
                 float lo, float hi)
    : name_(std::move(name)), mode_(mode), state_(&state), channel_(channel), lo_(lo), hi_(hi) {
    init();
}

GPUMask::GPUMask(std::string name, MaskMode mode, const GPUPingPongArray& state, int channel,
                 float lo, float hi)
    : name_(std::move(name)), mode_(mode), pingPong_(&state), channel_(channel), lo_(lo), hi_(hi) {
    init();
}

void GPUMask::init() {
    if (channel_ < 0 || channel_ >= state().channels())
        throw UsageError("mask '" + name_ + "': channel " + std::to_string(channel_) +
                         " of a " + std::to_string(state().channels()) + "-channel stream");
    if (scalarType(state().format()) != GPUScalar::Float)
        throw UsageError("mask '" + name_ + "': the state stream must be a float stream");
    if (mode_ != MaskMode::EarlyZ && mode_ != MaskMode::Stencil) return;
    glCreateTextures(GL_TEXTURE_2D, 1, &depthStencil_);
    glTextureStorage2D(depthStencil_, 1, GL_DEPTH24_STENCIL8, state().width(), state().height());
    glCreateFramebuffers(1, &framebuffer_);
    glNamedFramebufferTexture(framebuffer_, GL_DEPTH_STENCIL_ATTACHMENT, depthStencil_, 0);
    glNamedFramebufferDrawBuffer(framebuffer_, GL_NONE);
    if (glCheckNamedFramebufferStatus(framebuffer_, GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw EnvironmentError("mask '" + name_ + "': depth-stencil framebuffer is incomplete");
    program_.emplace("mask:" + name_, "stream/mask.frag");
    counter_.emplace(GL_SAMPLES_PASSED);
    glProgramUniform1i(program_->id(), program_->uniformLocation("gpu_maskState"), 0);
}

GPUMask::~GPUMask() {
    if (framebuffer_) glDeleteFramebuffers(1, &framebuffer_);
    if (depthStencil_) glDeleteTextures(1, &depthStencil_);
}

std::optional<uint64_t> GPUMask::updateAndCount() {
    if (mode_ != MaskMode::EarlyZ && mode_ != MaskMode::Stencil) return std::nullopt;
    update();
    const uint64_t count = counter_->result();
    KernelStats::global()["mask:" + name_].fragments += count;
    return count;
}

void GPUMask::setRange(float lo, float hi) {
    lo_ = lo;
    hi_ = hi;
}

void GPUMask::update() {
    if (mode_ != MaskMode::EarlyZ && mode_ != MaskMode::Stencil) return;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    if (mode_ == MaskMode::EarlyZ) {
        // Depth 1 everywhere, then 0 (the primitive at NDC z = -1) where the state matches.
        glDisable(GL_STENCIL_TEST);
        glEnable(GL_DEPTH_TEST);
        glDepthMask(GL_TRUE);
        glDepthFunc(GL_ALWAYS);
        glClearNamedFramebufferfi(framebuffer_, GL_DEPTH_STENCIL, 0, 1.0f, 0);
    } else {
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_STENCIL_TEST);
        glStencilMask(0xff);
        glStencilFunc(GL_ALWAYS, 1, 0xff);
        glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
        glClearNamedFramebufferfi(framebuffer_, GL_DEPTH_STENCIL, 0, 1.0f, 0);
    }
    glUseProgram(program_->id());
    glProgramUniform1f(program_->id(), program_->uniformLocation("gpu_depth"), -1.0f);
    glProgramUniform1i(program_->id(), program_->uniformLocation("gpu_maskChannel"), channel_);
    glProgramUniform2f(program_->id(), program_->uniformLocation("gpu_maskRange"), lo_, hi_);
    glBindTextureUnit(0, state().texture());
    counter_->begin();
    generator_.draw({0, 0, state().width(), state().height()});
    counter_->end();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDepthMask(GL_TRUE);
    ++KernelStats::global()["mask:" + name_].calls;
    GPURT_CHECK_GL(("mask pass " + name_).c_str());
}

}  // namespace gpurt
