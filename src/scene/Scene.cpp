// Bounds helpers and the light list shared by both backends.
#include "scene/Scene.h"

#include <cmath>
#include <utility>
#include <algorithm>

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
    // A proper rotation keeps the tangents' handedness.
    for (TriangleTangents& t : scene.tangents)
        for (glm::vec4* c : {&t.t0, &t.t1, &t.t2}) *c = glm::vec4(upAxisToY(glm::vec3(*c), axis), c->w);
    for (Light& l : scene.lights) {
        turn(l.position);
        turn(l.direction);
    }
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
    CameraSpec c = a.camera;  // the lens of the key before
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

std::vector<Light> lightsOrHeadlight(const Scene& scene, glm::vec3 eye, bool backgroundLights) {
    if (!scene.lights.empty()) return scene.lights;
    if (scene.environment) return {};  // lit by its environment
    if (backgroundLights && scene.background != glm::vec3(0.0f)) return {};  // lit by its background
    for (uint32_t m : scene.materialIds)
        if (scene.materials[m].emits()) return {};  // lit by its emitters
    Light headlight;
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

namespace gpurt {

bool hasOwnLight(const Scene& scene) {
    if (!scene.lights.empty() || scene.environment || scene.backgroundGiven) return true;
    for (uint32_t m : scene.materialIds)
        if (scene.materials[m].emits() && scene.materials[m].emissionIsLight) return true;
    return false;
}

bool addDefaultLight(Scene& scene) {
    // A scene without triangles has nothing to light: it shows its background as before.
    if (hasOwnLight(scene) || scene.triangles.empty()) return false;
    scene.environment = defaultEnvironment();
    return true;
}

namespace {

// The default light's radiance in direction d (docs/SCENE_FORMAT.md): a soft studio sky, bright
// above, darker and warmer below, with a broad warm key light up and to the left of the default
// camera (which looks along -z) and a dimmer cool rim behind the model. The key's radiance (3.2)
// stays below where the ACES tone map clips, so a mirror that shows it does not burn out.
glm::vec3 defaultSky(glm::vec3 d) {
    const glm::vec3 zenith(0.105f, 0.115f, 0.135f), horizon(0.095f, 0.095f, 0.095f), ground(0.03f, 0.028f, 0.026f);
    glm::vec3 sky = d.y >= 0.0f ? glm::mix(horizon, zenith, std::sqrt(d.y))
                                : glm::mix(horizon, ground, std::min(1.0f, -3.0f * d.y));
    const glm::vec3 key = glm::normalize(glm::vec3(-0.55f, 0.65f, 0.55f));
    const glm::vec3 rim = glm::normalize(glm::vec3(0.6f, 0.35f, -0.7f));
    sky += glm::vec3(1.0f, 0.95f, 0.88f) * 3.2f * std::pow(std::max(0.0f, glm::dot(d, key)), 24.0f);
    sky += glm::vec3(0.85f, 0.9f, 1.0f) * 0.8f * std::pow(std::max(0.0f, glm::dot(d, rim)), 16.0f);
    return sky;
}

}  // namespace

Environment defaultEnvironment() {
    static const std::shared_ptr<const EnvironmentImage> image = [] {
        auto im = std::make_shared<EnvironmentImage>();
        im->width = 512;
        im->height = 256;
        im->texels.resize(size_t(im->width) * size_t(im->height));
        const double pi = 3.14159265358979323846;
        for (int j = 0; j < im->height; ++j)
            for (int i = 0; i < im->width; ++i) {
                // The texel centre's direction by the contract's convention (u, v -> d).
                const double phi = ((i + 0.5) / im->width - 0.5) * 2.0 * pi, theta = (j + 0.5) / im->height * pi;
                const glm::vec3 d(float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)),
                                  float(-std::sin(theta) * std::cos(phi)));
                im->texels[size_t(j) * size_t(im->width) + size_t(i)] = defaultSky(d);
            }
        return im;
    }();
    Environment env;
    env.image = image;
    env.file = "default";
    env.isDefault = true;
    return env;
}

}  // namespace gpurt
