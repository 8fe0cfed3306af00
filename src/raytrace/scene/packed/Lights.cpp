// Packed sections of the lights: the point lights (LGTS), their kinds (LGTX) and the environment
// light (ENVM).
#include "raytrace/scene/packed/Sections.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "image/EnvironmentImage.h"
#include "raytrace/common/RayMath.h"
#include "raytrace/textures/SceneTextureLayout.h"

namespace gpurt::packed {

namespace {

constexpr size_t kLightKindBytes = 7 * 4;
constexpr size_t kEnvironmentMinBytes = 6 * 4;  // flags, strength, rotation, width, height, the name's length
constexpr size_t kLightBytes = 7 * 4;

void readLights(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
    const uint64_t n = s.count(in, kLightBytes, true, UINT64_MAX, "lights");
    scene.lights.resize(size_t(n));
    for (Light& light : scene.lights) {
        light.position = in.vec3();
        light.color = in.vec3();
        light.intensity = in.f32();
    }
}

void writeLights(ByteWriter& out, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    out.u64(scene.lights.size());
    for (const Light& l : scene.lights) {
        out.vec3(l.position);
        out.vec3(l.color);
        out.f32(l.intensity);
    }
}

// Each light's kind and what the kind needs (count = the lights', then kLightKindBytes each:
// kind, direction, inner and outer cone angles, range). Read after the lights.
void readLightKinds(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
    const uint64_t n = oneEach(in, s, kLightKindBytes, "lights' kinds", UINT64_MAX, scene.lights.size(), "lights");
    for (uint64_t k = 0; k < n; ++k) {
        Light& l = scene.lights[size_t(k)];
        const uint32_t kind = in.u32();
        l.direction = in.vec3();
        l.innerCone = in.f32();
        l.outerCone = in.f32();
        l.range = in.f32();
        const std::string which = "section " + s.tag + ": light " + std::to_string(k);
        if (kind > 2) s.fail(which + ": kind " + std::to_string(kind) + " (0 point, 1 spot, 2 directional)");
        l.kind = LightKind(kind);
        const float length2 = glm::dot(l.direction, l.direction);
        if (!(std::abs(length2 - 1.0f) < 1e-3f)) s.fail(which + ": the direction is not a unit vector");
        if (!(l.innerCone >= 0.0f && l.innerCone < l.outerCone && l.outerCone <= 1.5707964f))
            s.fail(which + ": cone angles not 0 <= inner < outer <= pi / 2");
        if (!(l.range >= 0.0f && std::isfinite(l.range))) s.fail(which + ": range not finite and >= 0");
    }
}

void writeLightKinds(ByteWriter& out, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    out.u64(scene.lights.size());
    for (const Light& l : scene.lights) {
        out.u32(uint32_t(l.kind));
        out.vec3(l.direction);
        out.f32(l.innerCone);
        out.f32(l.outerCone);
        out.f32(l.range);
    }
}

void readEnvironment(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
    if (s.size() < 4) s.fail("section " + s.tag + ": " + std::to_string(s.size()) + " bytes, too short");
    const uint32_t flags = in.u32();
    if (flags > 3) s.fail("section " + s.tag + ": unknown flags " + std::to_string(flags));
    scene.backgroundGiven = (flags & 1u) != 0;
    if (!(flags & 2u)) {
        if (in.remaining() != 0) s.fail("section " + s.tag + ": " + std::to_string(in.remaining()) + " bytes after the flags");
        return;
    }
    if (s.size() < kEnvironmentMinBytes) s.fail("section " + s.tag + ": " + std::to_string(s.size()) + " bytes, too short");
    Environment env;
    env.strength = in.f32();
    env.rotation = in.f32();
    if (!std::isfinite(env.strength) || env.strength < 0.0f || !std::isfinite(env.rotation))
        s.fail("section " + s.tag + ": strength " + formatFloat(env.strength) + " or rotation " + formatFloat(env.rotation) +
             " is not valid");
    const uint64_t width = in.u32(), height = in.u32(), nameLength = in.u32();
    if (width < 1 || height < 1 || width > uint64_t(kMaxEnvironmentWidth) || height > uint64_t(kMaxEnvironmentHeight))
        s.fail("section " + s.tag + ": environment map of " + std::to_string(width) + "x" + std::to_string(height) +
             " texels, not 1.." + std::to_string(kMaxEnvironmentWidth) + " x 1.." + std::to_string(kMaxEnvironmentHeight));
    if (in.remaining() != nameLength + width * height * 12)
        s.fail("section " + s.tag + ": " + std::to_string(in.remaining()) + " bytes for a " + std::to_string(nameLength) +
             "-byte name and " + std::to_string(width) + "x" + std::to_string(height) + " texels");
    env.file.resize(size_t(nameLength));
    if (nameLength > 0) std::memcpy(env.file.data(), in.take(size_t(nameLength)), size_t(nameLength));
    auto image = std::make_shared<EnvironmentImage>();
    image->width = int(width);
    image->height = int(height);
    image->texels.resize(size_t(width * height));
    for (glm::vec3& t : image->texels) t = in.vec3();
    for (const glm::vec3& t : image->texels)
        if (!(t.x >= 0.0f && t.x <= kMaxEnvironmentRadiance && t.y >= 0.0f && t.y <= kMaxEnvironmentRadiance &&
              t.z >= 0.0f && t.z <= kMaxEnvironmentRadiance))
            s.fail("section " + s.tag + ": an environment texel is negative, above 1e30 or not finite");
    env.image = std::move(image);
    scene.environment = std::move(env);
}

// Flags (1: the file set the background, 2: an environment follows), then the environment's
// strength, rotation, width, height, file name and texels (linear RGB, top row first).
void writeEnvironment(ByteWriter& out, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    const std::optional<Environment>& env = scene.environment;
    out.u32((scene.backgroundGiven ? 1u : 0u) | (env ? 2u : 0u));
    if (!env) return;
    out.f32(env->strength);
    out.f32(env->rotation);
    out.u32(uint32_t(env->image->width));
    out.u32(uint32_t(env->image->height));
    out.u32(uint32_t(env->file.size()));
    out.raw(env->file.data(), env->file.size());
    for (const glm::vec3& t : env->image->texels) out.vec3(t);
}

}  // namespace

const SceneSection kLightSection{"LGTS", [](const LoadedScene&) { return true; }, true, writeLights,
                                  [](const PackedSection& s, LoadedScene& l) { readLights(s, l.scene); }};
// Only when some light is not a plain point light: other files stay as they were before the
// section existed.
const SceneSection kLightKindSection{
    "LGTX",
    [](const LoadedScene& l) {
        return std::any_of(l.scene.lights.begin(), l.scene.lights.end(), [](const Light& x) { return !x.plainPoint(); });
    },
    false, writeLightKinds, [](const PackedSection& s, LoadedScene& l) { readLightKinds(s, l.scene); }};
// Only for a scene with an environment or a background of its own: likewise.
const SceneSection kEnvironmentSection{
    "ENVM", [](const LoadedScene& l) { return l.scene.environment || l.scene.backgroundGiven; }, false,
    writeEnvironment, [](const PackedSection& s, LoadedScene& l) { readEnvironment(s, l.scene); }};

void checkLights(const FileLoc& file, const Scene& scene) {
    for (size_t l = 0; l < scene.lights.size(); ++l) {
        const Light& light = scene.lights[l];
        if (!isFinite(light.position) || !isFinite(light.color) || !std::isfinite(light.intensity))
            failAt(file, "light " + std::to_string(l) + ": values are not finite");
        if (!nonNegative(light.color) || !(light.intensity >= 0.0f))
            failAt(file, "light " + std::to_string(l) + ": colour and intensity must be >= 0");
    }
}

}  // namespace gpurt::packed
