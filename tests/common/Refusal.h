// What the reader tests expect of a refusal: an InputError whose message starts with the file's
// name and is one line.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "image/InputError.h"

namespace gpurt::test {

// The message of the InputError that read() throws ("" and a failure if it throws none); it must
// start with `name` and be one line.
template <typename Read>
std::string refusalOf(const Read& read, const std::string& name) {
    try {
        read();
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(name, 0), 0u) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        return message;
    }
    ADD_FAILURE() << "accepted";
    return "";
}

}  // namespace gpurt::test

// Expects refusal(input) (each test's wrapper of refusalOf) to contain `part`.
#define EXPECT_REFUSED(input, part)                                                                  \
    do {                                                                                             \
        const std::string message_ = refusal(input);                                                 \
        EXPECT_NE(message_.find(part), std::string::npos) << "'" << (part) << "' not in: " << message_; \
    } while (0)
