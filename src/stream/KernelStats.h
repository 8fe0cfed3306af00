// Per-kernel statistics, keyed by kernel name: calls, fragments written, GPU time.
#pragma once

#include <cstdint>
#include <map>
#include <string>

namespace gpurt {

struct PassStats {
    uint64_t calls = 0;
    uint64_t fragments = 0;  // summed over passes whose occlusion query was read
    double gpuMs = 0.0;      // the passes' time, when timing is enabled
};

class KernelStats {
  public:
    static KernelStats& global();

    // GPU timing wraps each pass in a GL_TIME_ELAPSED query (read with the pass's count); on a
    // software renderer, whose "GPU" is the CPU, each pass is timed by the wall clock between
    // two glFinish instead (llvmpipe's timer queries miss some passes).
    void setTiming(bool enabled) { timing_ = enabled; }
    bool timing() const { return timing_; }

    PassStats& operator[](const std::string& kernelName) { return passes_[kernelName]; }
    const std::map<std::string, PassStats>& passes() const { return passes_; }
    void reset() {
        passes_.clear();
        compileMs = readBackMs = 0.0;
    }

    // Wall time outside the passes (milliseconds, always measured): building the kernels'
    // programs (compiling on first use) and reading streams back (which waits for the passes
    // before it).
    double compileMs = 0.0, readBackMs = 0.0;

  private:
    std::map<std::string, PassStats> passes_;
    bool timing_ = false;
};

}  // namespace gpurt
