#include "raytrace/scene/packed/Sections.h"

#include <cmath>
#include <cstdio>

#include "raytrace/textures/SceneTextureLayout.h"

namespace gpurt::packed {

bool nonNegative(const glm::vec3& v) { return v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f; }

std::string formatFloat(float value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", double(value));
    return text;
}

uint64_t oneEach(ByteReader& in, const PackedSection& s, uint64_t recordBytes, const char* what, uint64_t limit,
                 uint64_t expected, const char* of) {
    const uint64_t n = s.count(in, recordBytes, true, limit, what);
    if (n != expected)
        s.fail("section " + s.tag + ": " + std::to_string(n) + " " + what + " for " + std::to_string(expected) + " " +
               of);
    return n;
}

uint64_t perTriangle(ByteReader& in, const PackedSection& s, uint64_t recordBytes, const char* what,
                     const Scene& scene) {
    return oneEach(in, s, recordBytes, what, kMaxTextureTriangles, scene.triangles.size(), "triangles");
}

void writeName(ByteWriter& out, const std::string& text, const char* what) {
    if (text.size() > UINT32_MAX) throw InputError(std::string("a ") + what + " name is too long");
    out.u32(static_cast<uint32_t>(text.size()));
    out.raw(text.data(), text.size());
    out.padTo(4);
}

}  // namespace gpurt::packed
