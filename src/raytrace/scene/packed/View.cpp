// Packed sections of the view: the camera (CAMR), its lens (LENS), its animation (ANIM), the
// background (BKGD) and the render settings (RNDR).
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

constexpr size_t kCameraBytes = 10 * 4;
constexpr size_t kLensBytes = 5 * 4;
constexpr size_t kAnimationKeyBytes = 11 * 4;  // the time, then a camera
constexpr uint64_t kMaxAnimationKeys = 1 << 20;
constexpr size_t kBackgroundBytes = 3 * 4;
constexpr size_t kRenderBytes = 4 * 4;
// What a JSON scene may say (docs/SCENE_FORMAT.md): render.size and render.max_bounces.
constexpr uint32_t kMaxImageSide = 16384;
constexpr uint32_t kMaxBounces = 64;

void readCamera(const PackedSection& s, Scene& scene) {
    s.fixedSize(kCameraBytes);
    ByteReader in = s.reader();
    CameraSpec c;
    c.eye = in.vec3();
    c.target = in.vec3();
    c.up = in.vec3();
    c.fovy = in.f32();
    scene.camera = c;
}

void writeCamera(ByteWriter& out, const CameraSpec& c) {
    out.vec3(c.eye);
    out.vec3(c.target);
    out.vec3(c.up);
    out.f32(c.fovy);
}

// The camera's lens: radius, f-stop, focus distance, blades, blade rotation (after the camera).
void readLens(const PackedSection& s, Scene& scene) {
    s.fixedSize(kLensBytes);
    if (!scene.camera) s.fail("section " + s.tag + ": a lens without a camera");
    ByteReader in = s.reader();
    CameraSpec& c = *scene.camera;
    c.lensRadius = in.f32();
    c.fstop = in.f32();
    c.focusDistance = in.f32();
    c.blades = int(std::min(in.u32(), 1000u));
    c.bladeRotation = in.f32();
    if (!(c.lensRadius >= 0.0f && c.fstop >= 0.0f && c.focusDistance >= 0.0f && std::isfinite(c.lensRadius) &&
          std::isfinite(c.fstop) && std::isfinite(c.focusDistance) && std::isfinite(c.bladeRotation)) ||
        c.blades == 1 || c.blades == 2 || c.blades > 64)
        s.fail("section " + s.tag + ": not a lens (radius, f-stop and focus distance >= 0, blades 0 or 3 to 64)");
}

void writeLens(ByteWriter& out, const CameraSpec& c) {
    out.f32(c.lensRadius);
    out.f32(c.fstop);
    out.f32(c.focusDistance);
    out.u32(uint32_t(c.blades));
    out.f32(c.bladeRotation);
}

// The keys (count, then each key's time and camera), then the frame rate.
void readAnimation(const PackedSection& s, Scene& scene) {
    if (s.size() < 12) s.fail("section " + s.tag + ": " + std::to_string(s.size()) + " bytes, too short");
    ByteReader in = s.reader();
    const uint64_t n = in.u64();
    if (n < 1 || n > kMaxAnimationKeys || 12 + n * kAnimationKeyBytes != s.size())
        s.fail("section " + s.tag + ": " + std::to_string(n) + " keys of " + std::to_string(kAnimationKeyBytes) +
             " bytes do not fill its " + std::to_string(s.size()) + " bytes");
    CameraAnimation a;
    a.keys.resize(size_t(n));
    for (CameraKey& key : a.keys) {
        key.time = in.f32();
        key.camera.eye = in.vec3();
        key.camera.target = in.vec3();
        key.camera.up = in.vec3();
        key.camera.fovy = in.f32();
    }
    a.fps = in.f32();
    scene.animation = std::move(a);
}

void writeAnimation(ByteWriter& out, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    out.u64(scene.animation->keys.size());
    for (const CameraKey& key : scene.animation->keys) {
        out.f32(key.time);
        writeCamera(out, key.camera);
    }
    out.f32(scene.animation->fps);
}

void readBackground(const PackedSection& s, Scene& scene) {
    s.fixedSize(kBackgroundBytes);
    ByteReader in = s.reader();
    scene.background = in.vec3();
}

void readRender(const PackedSection& s, LoadedScene& loaded) {
    s.fixedSize(kRenderBytes);
    ByteReader in = s.reader();
    const uint32_t bounces = in.u32();
    const uint32_t hasSize = in.u32();
    const uint32_t width = in.u32(), height = in.u32();
    if (bounces > kMaxBounces)
        s.fail("max bounces " + std::to_string(bounces) + " outside 0.." +
             std::to_string(kMaxBounces));
    loaded.scene.maxBounces = int(bounces);
    if (hasSize > 1)
        s.fail("section " + s.tag + ": image size flag " + std::to_string(hasSize) +
             " is not 0 or 1");
    if (hasSize) {
        if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide)
            s.fail("image size " + std::to_string(width) + "x" + std::to_string(height) +
                 " outside 1.." + std::to_string(kMaxImageSide) + " per side");
        loaded.size = glm::ivec2(int(width), int(height));
    } else if (width != 0 || height != 0) {
        s.fail("section " + s.tag + ": an image size without the flag that says it is set");
    }
}

void writeRender(ByteWriter& out, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    const std::optional<glm::ivec2>& size = loaded.size;
    out.u32(static_cast<uint32_t>(scene.maxBounces));
    out.u32(size ? 1 : 0);
    out.u32(size ? static_cast<uint32_t>(size->x) : 0);
    out.u32(size ? static_cast<uint32_t>(size->y) : 0);
}

}  // namespace

const SceneSection kCameraSection{"CAMR", [](const LoadedScene& l) { return bool(l.scene.camera); }, false,
                                   [](ByteWriter& out, const LoadedScene& l) { writeCamera(out, *l.scene.camera); },
                                   [](const PackedSection& s, LoadedScene& l) { readCamera(s, l.scene); }};
// Only for a camera with a lens: other files stay as they were before the section existed.
const SceneSection kLensSection{"LENS", [](const LoadedScene& l) { return l.scene.camera && l.scene.camera->hasLens(); },
                                 false, [](ByteWriter& out, const LoadedScene& l) { writeLens(out, *l.scene.camera); },
                                 [](const PackedSection& s, LoadedScene& l) { readLens(s, l.scene); }};
const SceneSection kAnimationSection{"ANIM", [](const LoadedScene& l) { return bool(l.scene.animation); }, false,
                                      writeAnimation,
                                      [](const PackedSection& s, LoadedScene& l) { readAnimation(s, l.scene); }};
const SceneSection kBackgroundSection{"BKGD", [](const LoadedScene&) { return true; }, true,
                                       [](ByteWriter& out, const LoadedScene& l) { out.vec3(l.scene.background); },
                                       [](const PackedSection& s, LoadedScene& l) { readBackground(s, l.scene); }};
const SceneSection kRenderSection{"RNDR", [](const LoadedScene&) { return true; }, true, writeRender, readRender};

// The checks of a JSON scene's camera (`what` names it): the contract's basis must exist.
static void checkCamera(const FileLoc& file, const CameraSpec& c, const std::string& what) {
    if (!isFinite(c.eye) || !isFinite(c.target) || !isFinite(c.up)) failAt(file, what + ": values are not finite");
    if (!(c.fovy > 0.0f && c.fovy < 180.0f))
        failAt(file, what + ": fovy " + formatFloat(c.fovy) + " is outside (0, 180)");
    const glm::vec3 forward = c.target - c.eye;
    const float forwardLength2 = glm::dot(forward, forward);
    if (!(forwardLength2 > 0.0f) || !std::isfinite(forwardLength2))
        failAt(file, what + ": target - eye must be a non-zero vector of finite length");
    const glm::vec3 right = glm::cross(forward / std::sqrt(forwardLength2), c.up);
    const float rightLength2 = glm::dot(right, right);
    if (!(rightLength2 > 0.0f) || !std::isfinite(rightLength2))
        failAt(file, what + ": up must be non-zero and not parallel to target - eye");
}

// The camera and the animation's keys, each a camera at a later time than the one before.
void checkCameras(const FileLoc& file, const Scene& scene) {
    if (scene.camera) checkCamera(file, *scene.camera, "camera");
    if (const std::optional<CameraAnimation>& a = scene.animation) {
        if (!(a->fps > 0.0f && a->fps <= 1000.0f)) failAt(file, "animation: fps " + formatFloat(a->fps) + " is outside (0, 1000]");
        if (a->keys.empty()) failAt(file, "animation: no keys");
        for (size_t k = 0; k < a->keys.size(); ++k) {
            const std::string what = "animation key " + std::to_string(k);
            if (!std::isfinite(a->keys[k].time)) failAt(file, what + ": time is not finite");
            if (k > 0 && !(a->keys[k].time > a->keys[k - 1].time)) failAt(file, what + ": time is not after the key before");
            checkCamera(file, a->keys[k].camera, what);
        }
    }
}

// The background, the bounce limit and the image size, in a JSON scene's ranges.
void checkRenderSettings(const FileLoc& file, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    if (!isFinite(scene.background)) failAt(file, "background colour is not finite");
    if (!nonNegative(scene.background)) failAt(file, "background colour must be >= 0");
    if (scene.maxBounces < 0 || uint32_t(scene.maxBounces) > kMaxBounces)
        failAt(file, "max bounces " + std::to_string(scene.maxBounces) + " outside 0.." +
                         std::to_string(kMaxBounces));
    if (loaded.size) {
        const glm::ivec2 s = *loaded.size;
        if (s.x < 1 || s.y < 1 || uint32_t(s.x) > kMaxImageSide || uint32_t(s.y) > kMaxImageSide)
            failAt(file, "image size " + std::to_string(s.x) + "x" + std::to_string(s.y) + " outside 1.." +
                             std::to_string(kMaxImageSide) + " per side");
    }
}

}  // namespace gpurt::packed
