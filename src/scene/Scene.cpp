// Bounds helpers and the light list shared by both backends.
#include "scene/Scene.h"

#include <cmath>
#include <utility>

namespace gpurt {

void Bounds::extend(glm::vec3 p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
}

bool Bounds::empty() const { return !(min.x <= max.x && min.y <= max.y && min.z <= max.z); }

glm::vec3 Bounds::center() const { return (min + max) * 0.5f; }

glm::vec3 Bounds::halfExtent() const { return (max - min) * 0.5f; }

namespace {
constexpr std::pair<UpAxis, const char*> kUpAxisNames[] = {
    {UpAxis::PosX, "x"}, {UpAxis::NegX, "-x"}, {UpAxis::PosY, "y"},
    {UpAxis::NegY, "-y"}, {UpAxis::PosZ, "z"}, {UpAxis::NegZ, "-z"}};
}  // namespace

bool parseUpAxis(const std::string& text, UpAxis& axis) {
    for (const auto& [value, name] : kUpAxisNames)
        if (text == name) {
            axis = value;
            return true;
        }
    return false;
}

const char* upAxisName(UpAxis axis) {
    for (const auto& [value, name] : kUpAxisNames)
        if (value == axis) return name;
    return "y";
}

glm::vec3 upAxisToY(glm::vec3 v, UpAxis axis) {
    switch (axis) {
        case UpAxis::PosX: return {-v.y, v.x, v.z};
        case UpAxis::NegX: return {v.y, -v.x, v.z};
        case UpAxis::PosY: return v;
        case UpAxis::NegY: return {v.x, -v.y, -v.z};
        case UpAxis::PosZ: return {v.x, v.z, -v.y};
        case UpAxis::NegZ: return {v.x, -v.z, v.y};
    }
    return v;
}

void rotateUpToY(Scene& scene, UpAxis axis) {
    scene.upAxis = UpAxis::PosY;
    if (axis == UpAxis::PosY) return;
    auto turn = [axis](glm::vec3& v) { v = upAxisToY(v, axis); };
    for (Triangle& t : scene.triangles) {
        turn(t.v0);
        turn(t.v1);
        turn(t.v2);
    }
    for (TriangleNormals& n : scene.normals) {
        turn(n.n0);
        turn(n.n1);
        turn(n.n2);
    }
    for (PointLight& l : scene.lights) turn(l.position);
    auto turnCamera = [&](CameraSpec& c) {
        turn(c.eye);
        turn(c.target);
        turn(c.up);
    };
    if (scene.camera) turnCamera(*scene.camera);
    if (scene.animation)
        for (CameraKey& key : scene.animation->keys) turnCamera(key.camera);
}

CameraSpec CameraAnimation::at(int frame) const {
    const double t = timeOf(frame);
    if (t <= keys.front().time) return keys.front().camera;
    if (t >= keys.back().time) return keys.back().camera;
    size_t k = 1;
    while (keys[k].time < t) ++k;
    const CameraKey& a = keys[k - 1];
    const CameraKey& b = keys[k];
    const double s = (t - a.time) / (double(b.time) - a.time);
    auto mix = [s](glm::vec3 p, glm::vec3 q) { return glm::vec3(glm::dvec3(p) + (glm::dvec3(q) - glm::dvec3(p)) * s); };
    CameraSpec c;
    c.eye = mix(a.camera.eye, b.camera.eye);
    c.target = mix(a.camera.target, b.camera.target);
    c.up = mix(a.camera.up, b.camera.up);
    c.fovy = float(a.camera.fovy + (double(b.camera.fovy) - a.camera.fovy) * s);
    return c;
}

Bounds Scene::bounds() const {
    Bounds b;
    for (const Triangle& t : triangles) {
        b.extend(t.v0);
        b.extend(t.v1);
        b.extend(t.v2);
    }
    return b;
}

std::vector<PointLight> lightsOrHeadlight(const Scene& scene, glm::vec3 eye, bool backgroundLights) {
    if (!scene.lights.empty()) return scene.lights;
    if (backgroundLights && scene.background != glm::vec3(0.0f)) return {};  // lit by its background
    for (uint32_t m : scene.materialIds)
        if (scene.materials[m].emits()) return {};  // lit by its emitters
    PointLight headlight;
    headlight.position = eye;
    headlight.color = glm::vec3(1.0f);
    const Bounds b = scene.bounds();
    // An empty scene has no centre; nothing is lit there anyway.
    if (!b.empty()) {
        const glm::vec3 toCenter = eye - b.center();
        // Half of what would light a white surface facing it at the centre with radiance 1: kd 0.8
        // gives 0.4 + 0.08 ambient there (0.52 after the ACES tone map), so nearer parts of the
        // scene have room before they look white.
        headlight.intensity = 0.5f * glm::dot(toCenter, toCenter);
    }
    // A camera at the centre would give a light of intensity 0; keep the scene visible instead.
    if (!(headlight.intensity > 0.0f) || !std::isfinite(headlight.intensity))
        headlight.intensity = 1.0f;
    return {headlight};
}

}  // namespace gpurt
