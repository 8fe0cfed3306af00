#include "image/InputError.h"

#include <iostream>

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

void warnAt(const FileLoc& loc, const std::string& message) {
    std::cerr << loc.toString() << ": warning: " << message << "\n";
}

}  // namespace gpurt
