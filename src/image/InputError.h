// The "bad input" error channel (STYLE.md, habit 5): thrown for anything wrong in a scene file or
// an option. what() is one line, "FILE:LINE: what is wrong" (or "FILE: ..." / "--option: ..."),
// which the tools print unchanged before exiting with status 1 (CONTRACT.md, exit codes).
#pragma once

#include <stdexcept>

namespace gpurt {

class InputError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

}  // namespace gpurt
