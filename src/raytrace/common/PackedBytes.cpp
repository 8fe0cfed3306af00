#include "raytrace/common/PackedBytes.h"

#include <bit>

namespace gpurt {

uint32_t load32(const unsigned char* p) {
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

uint64_t load64(const unsigned char* p) { return uint64_t(load32(p)) | uint64_t(load32(p + 4)) << 32; }

void ByteWriter::u32(uint32_t v) {
    for (int k = 0; k < 4; ++k) bytes_.push_back(static_cast<unsigned char>(v >> (8 * k)));
}

void ByteWriter::u64(uint64_t v) {
    for (int k = 0; k < 8; ++k) bytes_.push_back(static_cast<unsigned char>(v >> (8 * k)));
}

void ByteWriter::f32(float v) { u32(std::bit_cast<uint32_t>(v)); }

void ByteWriter::vec3(glm::vec3 v) {
    f32(v.x);
    f32(v.y);
    f32(v.z);
}

void ByteWriter::u32s(const std::vector<uint32_t>& values) {
    for (uint32_t v : values) u32(v);
}

void ByteWriter::raw(const void* data, size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    bytes_.insert(bytes_.end(), p, p + size);
}

void ByteWriter::padTo(size_t alignment) {
    while (bytes_.size() % alignment != 0) bytes_.push_back(0);
}

void ByteWriter::patch32(size_t at, uint32_t v) {
    for (int k = 0; k < 4; ++k) bytes_[at + size_t(k)] = static_cast<unsigned char>(v >> (8 * k));
}

void ByteWriter::patch64(size_t at, uint64_t v) {
    for (int k = 0; k < 8; ++k) bytes_[at + size_t(k)] = static_cast<unsigned char>(v >> (8 * k));
}

float ByteReader::f32() { return std::bit_cast<float>(u32()); }

glm::vec3 ByteReader::vec3() {
    glm::vec3 v;
    v.x = f32();
    v.y = f32();
    v.z = f32();
    return v;
}

void ByteReader::u32s(std::vector<uint32_t>& values) {
    for (uint32_t& v : values) v = u32();
}

const unsigned char* ByteReader::take(size_t n) {
    if (n > remaining()) failAt(file_, section_ + ": section ends early");
    const unsigned char* p = bytes_.data() + at_;
    at_ += n;
    return p;
}

void PackedSection::fixedSize(uint64_t expected) const {
    if (size() != expected)
        fail("section " + tag + ": " + std::to_string(size()) + " bytes, expected " + std::to_string(expected));
}

uint64_t PackedSection::count(ByteReader& in, uint64_t recordBytes, bool exact, uint64_t limit,
                              const char* what) const {
    if (size() < 8) fail("section " + tag + ": " + std::to_string(size()) + " bytes, too short for its count");
    const uint64_t n = in.u64();
    if (n > limit)
        fail(std::to_string(n) + " " + what + "; at most " + std::to_string(limit) +
             " fit the GL backend (ids travel as float32, exact below 2^24)");
    const uint64_t room = (size() - 8) / recordBytes;
    if (n > room || (exact && 8 + n * recordBytes != size()))
        fail("section " + tag + ": " + std::to_string(n) + " " + what + " of " + std::to_string(recordBytes) +
             " bytes do not fit its " + std::to_string(size()) + " bytes");
    return n;
}

}  // namespace gpurt
