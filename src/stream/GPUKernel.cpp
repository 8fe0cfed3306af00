#include "stream/GPUKernel.h"

#include "stream/GLContext.h"
#include "stream/KernelStats.h"
#include "stream/StreamErrors.h"

#include <glm/gtc/type_ptr.hpp>

#include <chrono>
#include <cstdio>
#include <utility>

namespace gpurt {

GPUKernel::FramebufferName& GPUKernel::FramebufferName::operator=(FramebufferName&& o) noexcept {
    if (this != &o) {
        if (id) glDeleteFramebuffers(1, &id);
        id = std::exchange(o.id, 0);
    }
    return *this;
}

GPUKernel::FramebufferName::~FramebufferName() {
    if (id) glDeleteFramebuffers(1, &id);
}

const GPUFloatArray& GPUKernel::Stream::current() const {
    if (pingPong) return pingPong->front();
    if (pingPongInput) return pingPongInput->front();
    return *array;
}

const GPUFloatArray& GPUKernel::Stream::target() const {
    return pingPong ? pingPong->back() : *array;
}

GPUKernel::GPUKernel(std::string name, std::string fragmentPath, std::vector<std::string> defines)
    : name_(std::move(name)), fragmentPath_(std::move(fragmentPath)), defines_(std::move(defines)) {
    glCreateFramebuffers(1, &framebuffer_.id);
    glObjectLabel(GL_FRAMEBUFFER, framebuffer_.id, GLsizei(name_.size()), name_.data());
    for (int i = 0; i < 2; ++i) {
        counters_.emplace_back(GL_SAMPLES_PASSED);
        timers_.emplace_back(GL_TIME_ELAPSED);
    }
}

GPUKernel& GPUKernel::addDefine(const std::string& define) {
    defines_.push_back(define);
    program_.reset();
    return *this;
}

GPUKernel& GPUKernel::addInput(const GPUFloatArray& array, const std::string& samplerName) {
    inputs_.push_back({Stream{&array, nullptr, nullptr}, samplerName});
    return *this;
}

GPUKernel& GPUKernel::addInput(const GPUPingPongArray& array, const std::string& samplerName) {
    inputs_.push_back({Stream{nullptr, nullptr, &array}, samplerName});
    return *this;
}

void GPUKernel::checkOutputSize(const GPUFloatArray& array) const {
    if (array.storage() == GPUStorage::Buffer)
        throw UsageError("kernel '" + name_ + "': '" + array.name() +
                         "' is a buffer table, which kernels only read");
    if (int(outputs_.size()) >= kMaxOutputs)
        throw UsageError("kernel '" + name_ + "': more than " + std::to_string(kMaxOutputs) +
                         " outputs");
    if (!outputs_.empty()) {
        const GPUFloatArray& first = outputs_.front().target();
        if (first.width() != array.width() || first.height() != array.height())
            throw UsageError("kernel '" + name_ + "': output '" + array.name() + "' is " +
                             std::to_string(array.width()) + "x" + std::to_string(array.height()) +
                             ", the first output " + std::to_string(first.width()) + "x" +
                             std::to_string(first.height()));
    }
}

GPUKernel& GPUKernel::addOutput(GPUFloatArray& array) {
    checkOutputSize(array);
    for (const Input& in : inputs_)
        if (&in.stream.current() == &array)
            throw UsageError("kernel '" + name_ + "': '" + array.name() +
                             "' is an input and an output; use addInOut or a GPUPingPongArray");
    outputs_.push_back(Stream{&array, nullptr, nullptr});
    return *this;
}

GPUKernel& GPUKernel::addOutput(GPUPingPongArray& array) {
    checkOutputSize(array.back());
    outputs_.push_back(Stream{nullptr, &array, nullptr});
    return *this;
}

GPUKernel& GPUKernel::addInOut(GPUFloatArray& array, const std::string& samplerName) {
    checkOutputSize(array);
    inputs_.push_back({Stream{&array, nullptr, nullptr}, samplerName});
    outputs_.push_back(Stream{&array, nullptr, nullptr});
    inPlace_ = true;
    return *this;
}

GPUKernel& GPUKernel::addImage(GPUFloatArray& array, const std::string& imageName) {
    images_.emplace_back(&array, imageName);
    program_.reset();  // the image unit uniforms are set when the program is built
    return *this;
}

GPUKernel& GPUKernel::setPreserveUnwritten(bool preserve) {
    preserveUnwritten_ = preserve;
    return *this;
}

GPUKernel& GPUKernel::setMask(GPUMask* mask, bool updateEachPass) {
    mask_ = mask;
    updateMaskEachPass_ = updateEachPass;
    return *this;
}

GPUKernel& GPUKernel::setRect(std::optional<StreamRect> rect) {
    rect_ = rect;
    return *this;
}

GPUKernel& GPUKernel::setPrimitive(StreamPrimitive primitive) {
    generator_.setPrimitive(primitive);
    return *this;
}

void GPUKernel::build() {
    const MaskMode mode = mask_ ? mask_->mode() : MaskMode::None;
    if (program_ && builtFor_ == mode) return;
    std::string preamble;
    for (const std::string& d : defines_) preamble += "#define " + d + "\n";
    // A kernel that stores to images has side effects, and GL then runs the depth and stencil
    // tests after the shader unless it asks for them first (GL 4.5, 14.9): without this a masked
    // element's fragment would run, stores and atomics included, and only its outputs be dropped.
    if ((mode == MaskMode::EarlyZ || mode == MaskMode::Stencil) && !images_.empty())
        preamble += "layout(early_fragment_tests) in;\n";
    std::string epilogue;
    if (mode == MaskMode::EarlyExit) {
        // Early exit: the kernel's own main becomes gpu_kernelMain, called after the mask test.
        const EarlyExitWrapping wrapping = earlyExitWrapping();
        preamble += wrapping.preamble;
        epilogue = wrapping.epilogue;
    }
    const auto start = std::chrono::steady_clock::now();
    program_.emplace(name_, fragmentPath_, preamble, epilogue);
    KernelStats::global().compileMs +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    builtFor_ = mode;
    for (size_t i = 0; i < inputs_.size(); ++i)
        glProgramUniform1i(program_->id(), program_->uniformLocation(inputs_[i].sampler), GLint(i));
    for (size_t i = 0; i < images_.size(); ++i)
        glProgramUniform1i(program_->id(), program_->uniformLocation(images_[i].second), GLint(i));
    if (mode == MaskMode::EarlyExit)
        glProgramUniform1i(program_->id(), program_->uniformLocation("gpu_maskState"),
                           GLint(inputs_.size()));
    // NDC z 0 (window depth 0.5): in front of masked elements (depth 1), behind active ones (0).
    glProgramUniform1f(program_->id(), program_->uniformLocation("gpu_depth"), 0.0f);
    for (auto& [uniformName, uniform] : uniforms_) uniform.dirty = true;
}

const GPUProgram& GPUKernel::program() {
    build();
    return *program_;
}

void GPUKernel::applyUniforms() {
    const GLuint p = program_->id();
    for (auto& [uniformName, uniform] : uniforms_) {
        if (!uniform.dirty) continue;
        uniform.dirty = false;
        const GLint l = program_->uniformLocation(uniformName);
        if (l < 0) continue;  // not used by this variant: GL ignores it as well
        std::visit(
            [&](const auto& v) {
                using T = std::decay_t<decltype(v)>;
                if constexpr (std::is_same_v<T, float>) glProgramUniform1f(p, l, v);
                else if constexpr (std::is_same_v<T, int>) glProgramUniform1i(p, l, v);
                else if constexpr (std::is_same_v<T, unsigned>) glProgramUniform1ui(p, l, v);
                else if constexpr (std::is_same_v<T, glm::vec2>) glProgramUniform2fv(p, l, 1, glm::value_ptr(v));
                else if constexpr (std::is_same_v<T, glm::vec3>) glProgramUniform3fv(p, l, 1, glm::value_ptr(v));
                else if constexpr (std::is_same_v<T, glm::vec4>) glProgramUniform4fv(p, l, 1, glm::value_ptr(v));
                else if constexpr (std::is_same_v<T, glm::ivec2>) glProgramUniform2iv(p, l, 1, glm::value_ptr(v));
                else if constexpr (std::is_same_v<T, glm::ivec3>) glProgramUniform3iv(p, l, 1, glm::value_ptr(v));
                else if constexpr (std::is_same_v<T, glm::ivec4>) glProgramUniform4iv(p, l, 1, glm::value_ptr(v));
                else if constexpr (std::is_same_v<T, glm::uvec2>) glProgramUniform2uiv(p, l, 1, glm::value_ptr(v));
                else if constexpr (std::is_same_v<T, glm::mat3>) glProgramUniformMatrix3fv(p, l, 1, GL_FALSE, glm::value_ptr(v));
                else if constexpr (std::is_same_v<T, glm::mat4>) glProgramUniformMatrix4fv(p, l, 1, GL_FALSE, glm::value_ptr(v));
            },
            uniform.value);
    }
}

GPUKernel& GPUKernel::setScreenTarget(int width, int height) {
    screenWidth_ = width;
    screenHeight_ = height;
    return *this;
}

void GPUKernel::bindFramebuffer() {
    if (screenWidth_ > 0) {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        glDrawBuffer(GL_BACK);
        return;
    }
    if (outputs_.empty()) throw UsageError("kernel '" + name_ + "' has no output");
    const GLuint fb = framebuffer_.id;
    bool changed = false;
    for (size_t i = 0; i < outputs_.size(); ++i) {
        const GLuint texture = outputs_[i].target().texture();
        if (attached_[i] != texture) {
            glNamedFramebufferTexture(fb, GLenum(GL_COLOR_ATTACHMENT0 + i), texture, 0);
            attached_[i] = texture;
            changed = true;
        }
    }
    const bool attachMask = mask_ && (mask_->mode() == MaskMode::EarlyZ ||
                                      mask_->mode() == MaskMode::Stencil);
    const GLuint depthStencil = attachMask ? mask_->depthStencil() : 0;
    if (attached_[kMaxOutputs] != depthStencil) {
        if (attachMask && (mask_->state().width() != outputs_[0].target().width() ||
                           mask_->state().height() != outputs_[0].target().height()))
            throw UsageError("kernel '" + name_ + "': mask '" + mask_->name() +
                             "' is not the size of the outputs");
        glNamedFramebufferTexture(fb, GL_DEPTH_STENCIL_ATTACHMENT, depthStencil, 0);
        attached_[kMaxOutputs] = depthStencil;
        changed = true;
    }
    if (changed) {
        // Exactly the outputs as draw buffers: llvmpipe writes every enabled draw buffer.
        std::array<GLenum, kMaxOutputs> buffers{};
        for (size_t i = 0; i < outputs_.size(); ++i) buffers[i] = GLenum(GL_COLOR_ATTACHMENT0 + i);
        glNamedFramebufferDrawBuffers(fb, GLsizei(outputs_.size()), buffers.data());
        const GLenum status = glCheckNamedFramebufferStatus(fb, GL_DRAW_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE)
            throw EnvironmentError("kernel '" + name_ + "': framebuffer incomplete (status 0x" +
                                   [&] {
                                       char hex[16];
                                       std::snprintf(hex, sizeof hex, "%x", status);
                                       return std::string(hex);
                                   }() + ")");
    }
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fb);
}

void GPUKernel::readPending(int slot) {
    if (!pending_[slot]) return;
    pending_[slot] = false;
    PassStats& stats = KernelStats::global()[name_];
    const uint64_t count = counters_[slot].result();
    stats.fragments += count;
    if (slot == slot_) lastCount_ = count;
    if (timed_[slot]) {
        if (passWallMs_[slot] >= 0.0) {
            stats.gpuMs += passWallMs_[slot];
        } else {
            // No pass takes longer than the wall time until its result.
            const double wallMs = std::chrono::duration<double, std::milli>(
                                      std::chrono::steady_clock::now() - dispatchedAt_[slot]).count();
            stats.gpuMs += std::min(double(timers_[slot].result()) * 1e-6, wallMs);
        }
        timed_[slot] = false;
    }
}

void GPUKernel::dispatch() {
    build();
    if (mask_ && updateMaskEachPass_) mask_->update();

    slot_ = 1 - slot_;
    readPending(slot_);  // the pass two calls ago; long finished in a loop that reads counts

    for (Stream& out : outputs_)
        if (out.pingPong && preserveUnwritten_) out.pingPong->back().copyFrom(out.pingPong->front());

    bindFramebuffer();
    for (size_t i = 0; i < inputs_.size(); ++i)
        glBindTextureUnit(GLuint(i), inputs_[i].stream.current().texture());
    for (size_t i = 0; i < images_.size(); ++i)
        glBindImageTexture(GLuint(i), images_[i].first->texture(), 0, GL_FALSE, 0, GL_READ_WRITE,
                           images_[i].first->internalFormat());
    const MaskMode mode = mask_ ? mask_->mode() : MaskMode::None;
    if (mode == MaskMode::EarlyExit) {
        glBindTextureUnit(GLuint(inputs_.size()), mask_->state().texture());
        setUniform("gpu_maskChannel", mask_->channel());
        setUniform("gpu_maskRange", glm::vec2(mask_->lo(), mask_->hi()));
    }

    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    if (mode == MaskMode::EarlyZ) {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GREATER);  // active elements hold depth 0, masked ones 1
        glDepthMask(GL_FALSE);
    } else if (mode == MaskMode::Stencil) {
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(GL_EQUAL, 1, 0xff);
        glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
        glStencilMask(0);
    }
    if (inPlace_) glTextureBarrier();

    glUseProgram(program_->id());
    applyUniforms();

    const StreamRect whole = screenWidth_ > 0 ? StreamRect{0, 0, screenWidth_, screenHeight_}
                                              : StreamRect{0, 0, outputs_.front().target().width(),
                                                           outputs_.front().target().height()};
    const StreamRect rect = rect_.value_or(whole);
    const bool timing = KernelStats::global().timing();
    // On a software renderer the pass runs on the CPU, and llvmpipe's (Mesa 22.3) GL_TIME_ELAPSED
    // misses the rasterisation of some passes (a one-pass trace read 0.2 ms for 56 ms of work):
    // the pass is timed by the wall clock between two glFinish instead.
    const bool wallTiming = timing && isSoftwareRenderer();
    if (wallTiming) glFinish();
    const auto start = std::chrono::steady_clock::now();
    if (timing && !wallTiming) timers_[slot_].begin();
    counters_[slot_].begin();
    generator_.draw(rect);
    counters_[slot_].end();
    if (timing && !wallTiming) timers_[slot_].end();
    if (wallTiming) glFinish();
    pending_[slot_] = true;
    timed_[slot_] = timing;
    dispatchedAt_[slot_] = start;
    passWallMs_[slot_] =
        wallTiming ? std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count()
                   : -1.0;

    if (!images_.empty())  // later passes read the stores by fetches, loads or as render targets
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                        GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    glDepthMask(GL_TRUE);
    glStencilMask(0xff);
    for (Stream& out : outputs_)
        if (out.pingPong) out.pingPong->swap();
    ++calls_;
    ++KernelStats::global()[name_].calls;
    GPURT_CHECK_GL(("kernel " + name_).c_str());
}

void GPUKernel::dispatchIf(const GPUKernel& condition) {
    glBeginConditionalRender(condition.lastQueryId(), GL_QUERY_WAIT);
    dispatch();
    glEndConditionalRender();
}

uint64_t GPUKernel::lastCount() {
    readPending(slot_);
    return lastCount_;
}

uint64_t GPUKernel::execute() {
    dispatch();
    return lastCount();
}

int GPUKernel::loop(int maxCalls) {
    for (int calls = 1;; ++calls) {
        const uint64_t written = execute();
        if (written == 0) return calls;
        if (calls >= maxCalls)
            throw LoopLimitError("kernel '" + name_ + "': loop still wrote " +
                                 std::to_string(written) + " elements after " +
                                 std::to_string(maxCalls) + " calls (its limit)");
    }
}

void GPUKernel::flushStats() {
    readPending(1 - slot_);
    readPending(slot_);
}

GLuint GPUKernel::lastQueryId() const { return counters_[slot_].id(); }

}  // namespace gpurt
