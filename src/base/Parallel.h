// Work on all cores: `threads` workers (0: one per core) take chunks of [0, n) from a shared
// counter, so uneven chunks (image rows, ray batches) balance themselves. An exception in a worker
// is rethrown in the caller once all have stopped.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace gpurt {

inline int resolveThreads(int threads) {
    return threads > 0 ? threads : std::max(1, int(std::thread::hardware_concurrency()));
}

// Calls body(begin, end, worker) for consecutive chunks of at most `chunk` elements.
template <typename Body>
void parallelChunks(size_t n, size_t chunk, int threads, const Body& body) {
    chunk = std::max<size_t>(1, chunk);
    const size_t workerCount = std::clamp<size_t>(size_t(resolveThreads(threads)), 1, std::max<size_t>(1, (n + chunk - 1) / chunk));
    std::atomic<size_t> next{0};
    std::vector<std::exception_ptr> errors(workerCount);
    std::vector<std::thread> workers;
    workers.reserve(workerCount);
    for (size_t t = 0; t < workerCount; ++t)
        workers.emplace_back([&, t] {
            try {
                for (size_t begin = next.fetch_add(chunk); begin < n; begin = next.fetch_add(chunk))
                    body(begin, std::min(n, begin + chunk), t);
            } catch (...) {
                errors[t] = std::current_exception();
            }
        });
    for (std::thread& w : workers) w.join();
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);
}

}  // namespace gpurt
