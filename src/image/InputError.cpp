#include "image/InputError.h"

#include <cctype>
#include <iostream>
#include <set>

namespace gpurt {

std::string FileLoc::toString() const {
    // Built by appending (GCC 12 warns falsely on ":" + std::string).
    std::string text = filename;
    if (line > 0) {
        text += ':';
        text += std::to_string(line);
        if (column > 0) {
            text += ':';
            text += std::to_string(column);
        }
    }
    return text;
}

void failAt(const FileLoc& loc, const std::string& message) {
    throw InputError(loc.toString() + ": " + message);
}

namespace {
bool repeatsShown = true;
std::set<std::string>& warningsSeen() {
    static std::set<std::string> seen;
    return seen;
}
// Whether a warning about `file` saying `message` is to be printed now. Numbers are left out of
// the comparison: "light 3: ..." repeats "light 0: ...".
bool shouldWarn(const std::string& file, const std::string& message) {
    if (repeatsShown) return true;
    std::string key = file + '\n';
    for (char c : message)
        if (!std::isdigit(static_cast<unsigned char>(c)) || key.back() != '#')
            key += std::isdigit(static_cast<unsigned char>(c)) ? '#' : c;
    return warningsSeen().insert(key).second;
}
}  // namespace

void setWarningRepeats(bool shown) { repeatsShown = shown; }

void warnAt(const FileLoc& loc, const std::string& message) {
    if (shouldWarn(loc.filename, message)) std::cerr << loc.toString() << ": warning: " << message << "\n";
}

void warn(const std::string& message) {
    if (shouldWarn("", message)) std::cerr << "gpurt: warning: " << message << "\n";
}

}  // namespace gpurt
