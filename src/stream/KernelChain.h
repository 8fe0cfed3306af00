// Kernel chains (Christen 2005, section 4.3): the control structures a stream program is built
// from, with the CPU deciding between passes from occlusion-query counts.
//
//   sequence({&generate, &precalc});                      // each kernel once
//   forLoop(bounces, [&](int i) { ... });                 // a fixed number of times
//   traverse.loop(maxSteps);                              // while over one kernel
//   whileLoop("trace", maxIterations, [&] {               // while over several kernels:
//       traverse.dispatch();                              //   the last count ends it
//       return intersect.execute();
//   });
//   whileLoop("outer", n, [&] {                           // nested while
//       inner.loop(m);
//       return outer.execute();
//   });
#pragma once

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

namespace gpurt {

class GPUKernel;

// Runs each kernel once, in order, and returns the fragments each wrote (reads every count).
std::vector<uint64_t> sequence(std::initializer_list<GPUKernel*> kernels);

// Runs `body(i)` for i = 0 .. count-1.
void forLoop(int count, const std::function<void(int)>& body);

// Runs `body` until it returns 0 (the fragments written by the pass that decides); returns the
// number of iterations, the final one included. Throws LoopLimitError naming `name` when
// `maxIterations` iterations all returned non-zero: a loop never hangs.
int whileLoop(const std::string& name, int maxIterations, const std::function<uint64_t()>& body);

// While over several kernels: each iteration dispatches all but the last kernel without reading
// their counts and ends when the last kernel's pass writes nothing.
int whileLoop(const std::string& name, int maxIterations, std::initializer_list<GPUKernel*> kernels);

}  // namespace gpurt
