// A stream kernel (Christen's GPUKernel): one fragment-shader pass of a GLSL file from glsl/ over
// the output streams' elements, drawn by a GPUStreamGenerator into an FBO of up to 8 outputs.
// Each pass is counted by an occlusion query (GL_SAMPLES_PASSED): the number of elements it wrote,
// i.e. not discarded and not masked.
//
//   GPUKernel add("addStep", "test/add_step.frag");
//   add.addInput(values, "values").addOutput(values);    // values is a GPUPingPongArray
//   int calls = add.loop(200);                           // until a pass writes nothing
#pragma once

#include "stream/GPUFloatArray.h"
#include "stream/GPUMask.h"
#include "stream/GPUProgram.h"
#include "stream/GPUQuery.h"
#include "stream/GPUStreamGenerator.h"

#include <glm/glm.hpp>

#include <array>
#include <chrono>
#include <map>
#include <optional>
#include <utility>
#include <string>
#include <variant>
#include <vector>

namespace gpurt {

using UniformValue = std::variant<float, int, unsigned, glm::vec2, glm::vec3, glm::vec4, glm::ivec2,
                                  glm::ivec3, glm::ivec4, glm::uvec2, glm::mat3, glm::mat4>;

class GPUKernel {
  public:
    static constexpr int kMaxOutputs = 8;

    // `fragmentPath` is relative to glsl/; `defines` become "#define X" lines of this variant
    // ("NAME" or "NAME VALUE"). The program is built on the first pass (or by build()).
    GPUKernel(std::string name, std::string fragmentPath, std::vector<std::string> defines = {});
    GPUKernel(const GPUKernel&) = delete;
    GPUKernel& operator=(const GPUKernel&) = delete;
    GPUKernel(GPUKernel&&) = default;
    GPUKernel& operator=(GPUKernel&&) = default;

    const std::string& name() const { return name_; }

    // Random-access input, read in GLSL with texelFetch(samplerName, ...). A ping-pong input reads
    // its front.
    // One more "#define X" line for this kernel's source (before it is first built).
    GPUKernel& addDefine(const std::string& define);
    GPUKernel& addInput(const GPUFloatArray& array, const std::string& samplerName);
    GPUKernel& addInput(const GPUPingPongArray& array, const std::string& samplerName);
    // Outputs in the order of the shader's `layout(location = i) out` variables; all the same size.
    // A ping-pong output writes its back and is swapped after each pass. Elements a pass does not
    // write (discarded or masked) keep their values: the framework copies front to back first
    // unless setPreserveUnwritten(false).
    GPUKernel& addOutput(GPUFloatArray& array);
    GPUKernel& addOutput(GPUPingPongArray& array);
    // In-place update: the array is both input `samplerName` and the next output. Legal because
    // each fragment reads only its own texel, once, after a glTextureBarrier (ARB_texture_barrier).
    GPUKernel& addInOut(GPUFloatArray& array, const std::string& samplerName);
    GPUKernel& setPreserveUnwritten(bool preserve);
    // A per-element store (GLSL image `imageName`, read and written with imageLoad/imageStore)
    // beside the outputs, of any size: a fragment may write elements other than its own, such as
    // its own slots of a stack laid out in rows of slots. The kernel must keep every element
    // written by at most one fragment of a pass (so the result does not depend on the order in
    // which fragments run). Passes that follow see the writes (memory barrier after each pass).
    GPUKernel& addImage(GPUFloatArray& array, const std::string& imageName);

    // Restricts passes to the mask's active elements (nullptr: no mask). With `updateEachPass`,
    // EarlyZ/Stencil masks run their mask pass before each pass of this kernel.
    GPUKernel& setMask(GPUMask* mask, bool updateEachPass = true);
    // Draw into the default framebuffer of a window's context (width x height, its back buffer)
    // instead of outputs: a present pass. 0 x 0: back to the outputs.
    GPUKernel& setScreenTarget(int width, int height);
    // Draw over a sub-rectangle of the outputs only (std::nullopt: all of them).
    GPUKernel& setRect(std::optional<StreamRect> rect);
    GPUKernel& setPrimitive(StreamPrimitive primitive);

    // Uniforms are kept here and applied before the next pass (they survive rebuilds).
    template <typename T>
    GPUKernel& setUniform(const std::string& name, const T& value) {
        uniforms_[name] = Uniform{UniformValue(value), true};
        return *this;
    }

    // Compiles and links now (otherwise on the first pass); throws KernelBuildError.
    void build();
    const GPUProgram& program();

    // One pass; does not wait for it. The count stays readable through lastCount().
    void dispatch();
    // One pass, skipped on the GPU (no CPU round trip) when `condition`'s latest pass wrote
    // nothing (conditional rendering on its occlusion query).
    void dispatchIf(const GPUKernel& condition);
    // Fragments written by the latest pass. Blocks until that pass has finished.
    uint64_t lastCount();
    // dispatch() + lastCount().
    uint64_t execute();
    // Runs passes until one writes nothing; returns the number of calls, the final empty pass
    // included. Throws LoopLimitError after `maxCalls` calls that all wrote something.
    int loop(int maxCalls);

    // Reads the counts (and timings) of passes not read yet into KernelStats. Blocks until they
    // have finished.
    void flushStats();

    GLuint lastQueryId() const;
    int calls() const { return calls_; }

  private:
    struct Stream {
        const GPUFloatArray* array = nullptr;
        GPUPingPongArray* pingPong = nullptr;
        const GPUPingPongArray* pingPongInput = nullptr;
        const GPUFloatArray& current() const;
        const GPUFloatArray& target() const;  // what an output pass writes
    };
    struct Input {
        Stream stream;
        std::string sampler;
    };
    struct Uniform {
        UniformValue value;
        bool dirty;
    };

    void checkOutputSize(const GPUFloatArray& array) const;
    void bindFramebuffer();
    void applyUniforms();
    void readPending(int slot);

    std::string name_;
    std::string fragmentPath_;
    std::vector<std::string> defines_;
    std::optional<GPUProgram> program_;
    MaskMode builtFor_ = MaskMode::None;
    std::vector<Input> inputs_;
    std::vector<Stream> outputs_;
    std::vector<std::pair<GPUFloatArray*, std::string>> images_;
    bool inPlace_ = false;
    bool preserveUnwritten_ = true;
    GPUMask* mask_ = nullptr;
    bool updateMaskEachPass_ = true;
    std::optional<StreamRect> rect_;
    int screenWidth_ = 0, screenHeight_ = 0;
    std::map<std::string, Uniform> uniforms_;
    GPUStreamGenerator generator_;

    struct FramebufferName {
        GLuint id = 0;
        FramebufferName() = default;
        FramebufferName(FramebufferName&& o) noexcept : id(std::exchange(o.id, 0)) {}
        FramebufferName& operator=(FramebufferName&& o) noexcept;
        ~FramebufferName();
    } framebuffer_;
    std::array<GLuint, kMaxOutputs + 1> attached_{};  // colour attachments, then depth-stencil

    // Two query slots: the latest pass's query stays readable (and usable for conditional
    // rendering by another kernel) while the next pass runs.
    std::vector<GPUQuery> counters_;
    std::vector<GPUQuery> timers_;
    std::array<bool, 2> pending_{};
    std::array<bool, 2> timed_{};
    std::array<std::chrono::steady_clock::time_point, 2> dispatchedAt_{};
    std::array<double, 2> passWallMs_{-1.0, -1.0};  // a software renderer's pass time, else -1
    int slot_ = 1;
    uint64_t lastCount_ = 0;
    int calls_ = 0;
};

}  // namespace gpurt
