// Error types of the stream framework. Each maps to one of the contract's exit codes at the CLI.
#pragma once

#include <stdexcept>
#include <string>

namespace gpurt {

// The environment cannot run gpurt: no GL context, a missing GL feature, out of GPU memory.
// The CLI answers these with exit code 2.
class EnvironmentError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// A kernel could not be built: a GLSL file is missing, does not compile or does not link.
// The message names the file and line (via the #line mapping of ShaderLibrary).
class KernelBuildError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// A kernel loop reached its call limit while passes still wrote fragments.
class LoopLimitError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// A broken invariant in the framework's own use (wrong sizes, too many outputs, ...).
class UsageError : public std::logic_error {
  public:
    using std::logic_error::logic_error;
};

}  // namespace gpurt
