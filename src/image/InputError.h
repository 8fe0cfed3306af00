// The "bad input" error channel (STYLE.md, habit 5): thrown for anything wrong in a scene file or
// an option. what() is one line, "FILE:LINE: what is wrong" (or "FILE: ..." / "--option: ..."),
// which the tools print unchanged before exiting with status 1 (CONTRACT.md, exit codes). The
// readers name the place through one type and one helper (pbrt-v4 util/error.h: FileLoc and
// ErrorExit), so that every reader writes places the same way.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace gpurt {

class InputError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// A place in a file: the file's name, and its line and column when the reader knows them.
struct FileLoc {
    std::string filename;
    size_t line = 0;    // 1-based; 0: the file as a whole
    size_t column = 0;  // 1-based; 0: the whole line (a column needs a line)

    // "FILE", "FILE:LINE" or "FILE:LINE:COLUMN".
    std::string toString() const;
};

// Throws InputError "LOC: message".
[[noreturn]] void failAt(const FileLoc& loc, const std::string& message);

// Prints "LOC: warning: message" and a line end to stderr (the file is read on).
void warnAt(const FileLoc& loc, const std::string& message);
// Prints "gpurt: warning: message" and a line end to stderr (a warning of no file).
void warn(const std::string& message);

// false (--quiet): a warning is printed only the first time its file and message occur (lines,
// columns and the numbers in the message aside); later ones are left out. true (the default): every warning is printed.
void setWarningRepeats(bool shown);

}  // namespace gpurt
