// The byte level of packed scene files (docs/PACKED_FORMAT.md), shared by the scene's sections
// (scene/PackedScene) and each accelerator's (accel/*/...Accelerator.cpp): little-endian output,
// checked input from one section, and the checks every section's decoder makes before it sizes
// anything by a count it read.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "image/InputError.h"

namespace gpurt {

uint32_t load32(const unsigned char* p);
uint64_t load64(const unsigned char* p);

// Little-endian output, whatever the host's byte order.
class ByteWriter {
  public:
    void u32(uint32_t v);
    void u64(uint64_t v);
    void f32(float v);
    void vec3(glm::vec3 v);
    void u32s(const std::vector<uint32_t>& values);
    void raw(const void* data, size_t size);
    void padTo(size_t alignment);
    void patch32(size_t at, uint32_t v);
    void patch64(size_t at, uint64_t v);
    size_t size() const { return bytes_.size(); }
    std::vector<unsigned char>& bytes() { return bytes_; }

  private:
    std::vector<unsigned char> bytes_;
};

// Little-endian input from one section. Reads past its end throw; the decoders check sizes
// first, so that is a second line of defence, not the way errors are found.
class ByteReader {
  public:
    // `section` ("section TAG") names the section in `file` in messages.
    ByteReader(std::span<const unsigned char> bytes, FileLoc file, std::string section)
        : bytes_(bytes), file_(std::move(file)), section_(std::move(section)) {}

    uint32_t u32() { return load32(take(4)); }
    uint64_t u64() { return load64(take(8)); }
    float f32();
    glm::vec3 vec3();
    void u32s(std::vector<uint32_t>& values);
    const unsigned char* take(size_t n);
    size_t remaining() const { return bytes_.size() - at_; }

  private:
    std::span<const unsigned char> bytes_;
    size_t at_ = 0;
    FileLoc file_;
    std::string section_;
};

// One section of a packed file being read: its tag, its bytes, the file (for messages).
struct PackedSection {
    std::string tag;
    std::span<const unsigned char> bytes;
    FileLoc file;

    uint64_t size() const { return bytes.size(); }
    ByteReader reader() const { return ByteReader(bytes, file, "section " + tag); }
    // InputError "FILE: what".
    [[noreturn]] void fail(const std::string& what) const { failAt(file, what); }
    // Refuses a section of any other size than `expected` bytes.
    void fixedSize(uint64_t expected) const;
    // The section's leading u64 count of records of `recordBytes` each (at least, for records of
    // varying size), checked against the section's size before anything is sized by it. A
    // count above `limit` (the GL backend's) is refused first, naming what `what` counts.
    uint64_t count(ByteReader& in, uint64_t recordBytes, bool exact, uint64_t limit, const char* what) const;
};

}  // namespace gpurt
