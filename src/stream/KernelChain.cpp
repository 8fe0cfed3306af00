#include "stream/KernelChain.h"

#include "stream/GPUKernel.h"
#include "stream/StreamErrors.h"

namespace gpurt {

std::vector<uint64_t> sequence(std::initializer_list<GPUKernel*> kernels) {
    std::vector<uint64_t> counts;
    counts.reserve(kernels.size());
    for (GPUKernel* k : kernels) counts.push_back(k->execute());
    return counts;
}

void forLoop(int count, const std::function<void(int)>& body) {
    for (int i = 0; i < count; ++i) body(i);
}

int whileLoop(const std::string& name, int maxIterations, const std::function<uint64_t()>& body) {
    for (int iteration = 1;; ++iteration) {
        const uint64_t written = body();
        if (written == 0) return iteration;
        if (iteration >= maxIterations)
            throw LoopLimitError("loop '" + name + "': still wrote " + std::to_string(written) +
                                 " elements after " + std::to_string(maxIterations) +
                                 " iterations (its limit)");
    }
}

int whileLoop(const std::string& name, int maxIterations, std::initializer_list<GPUKernel*> kernels) {
    if (kernels.size() == 0) throw UsageError("loop '" + name + "' has no kernels");
    std::vector<GPUKernel*> list(kernels);
    return whileLoop(name, maxIterations, [&] {
        for (size_t i = 0; i + 1 < list.size(); ++i) list[i]->dispatch();
        return list.back()->execute();
    });
}

}  // namespace gpurt
