// Packed scene encoding and decoding. The writer lays the sections out in a fixed order with
// zero padding, so the bytes depend only on the scene and the grid. The reader checks in the
// order that lets each check trust the previous ones: magic, version, header size, file size,
// CRC-32 (zlib), section table, each section's size against its counts (before allocating), and
// last the contents (validateScene, which the writer runs too so that it never writes a file
// the reader would refuse).
#include "raytrace/scene/PackedScene.h"

#include <algorithm>
#include <tuple>
#include <array>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>

#include <zlib.h>

#include "image/AtomicFile.h"
#include "image/InputError.h"
#include "raytrace/common/PackedBytes.h"
#include "raytrace/common/RayMath.h"
#include "raytrace/textures/SceneTextureLayout.h"
#include "scene/SceneFile.h"

namespace gpurt {
namespace {

// Section tags: four ASCII characters, stored as they read.
constexpr char kTriangles[] = "TRIS";
constexpr char kMaterials[] = "MATS";
constexpr char kLights[] = "LGTS";
constexpr char kCamera[] = "CAMR";
constexpr char kAnimation[] = "ANIM";
constexpr char kBackground[] = "BKGD";
constexpr char kRender[] = "RNDR";
constexpr char kNormals[] = "NRML";
constexpr char kTexcoords[] = "TXCO";
constexpr char kTextures[] = "TEXS";
constexpr char kModels[] = "MODL";
constexpr char kPbr[] = "PBRM";
constexpr char kEnvironment[] = "ENVM";
constexpr char kColors[] = "VCOL";
constexpr char kAlpha[] = "ALPH";
constexpr char kTangents[] = "TANG";
constexpr char kSided[] = "SIDE";
constexpr char kTransmissionMaps[] = "TRNS";
constexpr char kLens[] = "LENS";
constexpr char kGlow[] = "GLOW";
constexpr char kLightKinds[] = "LGTX";
// The scene's sections in the order the writer stores them; the acceleration structure's (its
// accelerator's, accel/Accelerator.h) follow RNDR. All but the camera, its animation, the normals,
// the texture coordinates, the textures, the material models, the environment, the vertex
// colours, the alpha coverage, the vertex tangents, the sides, the transmission maps, the lens,
// the glow flags and the light kinds are required, and one accelerator's sections, whole.
constexpr const char* kSectionOrder[] = {kTriangles, kMaterials, kLights,   kCamera,    kBackground, kRender,
                                         kNormals,   kAnimation, kTexcoords, kTextures, kModels,     kPbr,
                                         kEnvironment, kColors,  kAlpha,    kTangents,  kSided,      kTransmissionMaps,
                                         kLens,      kGlow,      kLightKinds};
// Where the structure's sections go: after this one.
constexpr std::string_view kStructureAfter = kRender;
constexpr bool optionalSection(std::string_view tag) {
    return tag == kCamera || tag == kNormals || tag == kAnimation || tag == kTexcoords || tag == kTextures ||
           tag == kModels || tag == kPbr || tag == kEnvironment || tag == kColors || tag == kAlpha || tag == kTangents ||
           tag == kSided || tag == kTransmissionMaps || tag == kLens || tag == kGlow || tag == kLightKinds;
}
bool hasSection(const LoadedScene& loaded, std::string_view tag) {
    if (tag == kCamera) return bool(loaded.scene.camera);
    // Only for a camera with a lens: other files stay as they were before the section existed.
    if (tag == kLens) return loaded.scene.camera && loaded.scene.camera->hasLens();
    if (tag == kNormals) return !loaded.scene.normals.empty();
    if (tag == kAnimation) return bool(loaded.scene.animation);
    if (tag == kTexcoords) return !loaded.scene.texcoords.empty();
    // Only for a scene with vertex colours: other files stay as they were before the section existed.
    if (tag == kColors) return !loaded.scene.colors.empty();
    // Only for a scene with vertex tangents (glTF TANGENT): other files stay as they were before
    // the section existed.
    if (tag == kTangents) return !loaded.scene.tangents.empty();
    if (tag == kTextures) return !loaded.scene.textures.empty();
    // Only for a scene with an environment or a background of its own: other files stay as they
    // were before the section existed.
    if (tag == kEnvironment) return loaded.scene.environment || loaded.scene.backgroundGiven;
    // Only when some material is not of the classic model: files of classic scenes stay as they
    // were before the section existed.
    if (tag == kModels)
        return std::any_of(loaded.scene.materials.begin(), loaded.scene.materials.end(),
                           [](const Material& m) { return m.model != 0; });
    // PBRM also carries the maps a classic material may have (MTL `norm`, `map_Ke`).
    if (tag == kPbr)
        return std::any_of(loaded.scene.materials.begin(), loaded.scene.materials.end(), [](const Material& m) {
            return m.model == GPURT_MODEL_GLTF || m.normalTexture >= 0 || m.emissiveTexture >= 0 ||
                   m.occlusionTexture.given() || m.roughnessTexture.given() || m.metallicTexture.given();
        });
    // Only when some material has alpha: other files stay as they were before the section existed.
    if (tag == kAlpha)
        return std::any_of(loaded.scene.materials.begin(), loaded.scene.materials.end(),
                           [](const Material& m) { return m.hasAlpha(); });
    // Only when some material is single-sided (glTF doubleSided false): likewise.
    if (tag == kSided)
        return std::any_of(loaded.scene.materials.begin(), loaded.scene.materials.end(),
                           [](const Material& m) { return !m.doubleSided; });
    // Only when some material's emission only glows (glTF's): likewise.
    if (tag == kGlow)
        return std::any_of(loaded.scene.materials.begin(), loaded.scene.materials.end(),
                           [](const Material& m) { return !m.emissionIsLight; });
    // Only when some light is not a plain point light: likewise.
    if (tag == kLightKinds)
        return std::any_of(loaded.scene.lights.begin(), loaded.scene.lights.end(),
                           [](const Light& l) { return !l.plainPoint(); });
    // Only when some material has a transmission map (glTF transmissionTexture): likewise.
    if (tag == kTransmissionMaps)
        return std::any_of(loaded.scene.materials.begin(), loaded.scene.materials.end(),
                           [](const Material& m) { return m.transmissionTexture.given(); });
    return true;
}
constexpr size_t kNormalsBytes = 9 * 4;
constexpr size_t kTexcoordsBytes = 6 * 4;
constexpr size_t kColorsBytes = 9 * 4;
constexpr size_t kTangentsBytes = 12 * 4;
constexpr size_t kTextureMinBytes = 5 * 4;  // width, height, wrapS, wrapT, the name's length
constexpr uint64_t kMaxTextures = 1 << 16;
constexpr size_t kModelBytes = 4;
// PBRM per material: metallic, roughness, normal scale, occlusion strength (f32), then the
// roughness, metallic and occlusion channels (texture, channel) and the normal and emissive
// textures (i32, -1: none).
constexpr size_t kPbrBytes = 4 * 4 + 8 * 4;
// ALPH per material: alpha mode (u32), factor, cutoff (f32), the alpha channel (texture, channel).
constexpr size_t kAlphaBytes = 5 * 4;
// SIDE per material: u32 1 double-sided, 0 single-sided (back faces culled).
constexpr size_t kSidedBytes = 4;
constexpr size_t kGlowBytes = 4;
constexpr size_t kLightKindBytes = 7 * 4;
// TRNS per material: the transmission map's channel (texture, channel; -1: none).
constexpr size_t kTransmissionMapBytes = 2 * 4;
constexpr size_t kEnvironmentMinBytes = 6 * 4;  // flags, strength, rotation, width, height, the name's length
// The last material model a packed file may give (glsl/common/material.h GPURT_MODEL_*).
constexpr uint32_t kLastMaterialModel = GPURT_MODEL_COUNT - 1;

constexpr size_t kTriangleBytes = 9 * 4 + 4;      // three vertices, then (separately) the id
constexpr size_t kMaterialMinBytes = 17 * 4 + 4;  // seventeen floats and the name's length
constexpr size_t kLightBytes = 7 * 4;
constexpr size_t kCameraBytes = 10 * 4;
constexpr size_t kLensBytes = 5 * 4;
constexpr size_t kAnimationKeyBytes = 11 * 4;  // the time, then a camera
constexpr uint64_t kMaxAnimationKeys = 1 << 20;
constexpr size_t kBackgroundBytes = 3 * 4;
constexpr size_t kRenderBytes = 4 * 4;
// More sections than a version-1 file can hold is a damaged table, not a big scene.
constexpr uint32_t kMaxSections = 64;
// What a JSON scene may say (docs/SCENE_FORMAT.md): render.size and render.max_bounces.
constexpr uint32_t kMaxImageSide = 16384;
constexpr uint32_t kMaxBounces = 64;

std::string hex32(uint32_t value) {
    char text[16];
    std::snprintf(text, sizeof text, "0x%08x", value);
    return text;
}

std::string formatFloat(float value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", double(value));
    return text;
}

std::string unknownModel(size_t material, int64_t model) {
    return "material " + std::to_string(material) + ": unknown material model " + std::to_string(model) +
           " (this gpurt knows 0.." + std::to_string(kLastMaterialModel) + ")";
}

uint32_t crc32Of(std::span<const unsigned char> bytes) {
    return static_cast<uint32_t>(
        crc32_z(crc32_z(0L, Z_NULL, 0), bytes.data(), static_cast<z_size_t>(bytes.size())));
}

bool isFinite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool nonNegative(const glm::vec3& v) { return v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f; }

// The checks of validateScene, in its order; `file` names the scene in each message.

// The triangle and material counts the GL backend can carry, and each triangle's vertices and
// material id.
void checkTriangles(const FileLoc& file, const Scene& scene) {
    const size_t n = scene.triangles.size();
    if (n > kMaxTextureTriangles)
        failAt(file, std::to_string(n) + " triangles; at most " + std::to_string(kMaxTextureTriangles) +
                         " fit the GL backend (triangle ids travel as float32, exact below 2^24)");
    if (scene.materials.empty()) failAt(file, "no materials (a scene has at least the default material)");
    if (scene.materials.size() > kMaxTextureMaterials)
        failAt(file, std::to_string(scene.materials.size()) + " materials; at most " +
                         std::to_string(kMaxTextureMaterials) +
                         " fit the GL backend (material ids travel as float32, exact below 2^24)");
    if (scene.materialIds.size() != n)
        failAt(file, std::to_string(scene.materialIds.size()) + " material ids for " + std::to_string(n) +
                         " triangles");
    for (size_t t = 0; t < n; ++t) {
        const Triangle& tri = scene.triangles[t];
        if (!isFinite(tri.v0) || !isFinite(tri.v1) || !isFinite(tri.v2))
            failAt(file, "triangle " + std::to_string(t) + ": vertex coordinates are not finite");
        if (scene.materialIds[t] >= scene.materials.size())
            failAt(file, "triangle " + std::to_string(t) + ": material id " +
                             std::to_string(scene.materialIds[t]) + " out of range (" +
                             std::to_string(scene.materials.size()) + " materials)");
    }
}

// Every material's values (finite, in the ranges a JSON scene allows: the shading relies on
// them) and model, then every material's texture.
void checkMaterials(const FileLoc& file, const Scene& scene) {
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& mat = scene.materials[m];
        if (!isFinite(mat.diffuse) || !isFinite(mat.specular) || !std::isfinite(mat.shininess) ||
            !isFinite(mat.reflectivity) || !isFinite(mat.emission) || !std::isfinite(mat.ior) ||
            !isFinite(mat.transmission))
            failAt(file, "material " + std::to_string(m) + ": values are not finite");
        if (!nonNegative(mat.diffuse) || !nonNegative(mat.specular) || !(mat.shininess >= 0.0f) ||
            !nonNegative(mat.reflectivity) || glm::any(glm::greaterThan(mat.reflectivity, glm::vec3(1.0f))) ||
            !nonNegative(mat.emission) || !(mat.ior >= 0.0f) || !nonNegative(mat.transmission) ||
            glm::any(glm::greaterThan(mat.transmission, glm::vec3(1.0f))))
            failAt(file, "material " + std::to_string(m) +
                             ": colours, emission, shininess and ior must be >= 0, reflectivity and transmission in [0, 1]");
        if (mat.model < 0 || uint32_t(mat.model) > kLastMaterialModel) failAt(file, unknownModel(m, mat.model));
    }
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& mat = scene.materials[m];
        for (int texture : {mat.diffuseTexture, mat.roughnessTexture.texture, mat.metallicTexture.texture, mat.normalTexture,
                            mat.emissiveTexture, mat.occlusionTexture.texture, mat.alphaTexture.texture,
                            mat.transmissionTexture.texture})
            if (texture < -1 || texture >= int(scene.textures.size()))
                failAt(file, "material " + std::to_string(m) + ": texture " + std::to_string(texture) + " out of range (" +
                                 std::to_string(scene.textures.size()) + " textures)");
        for (TextureChannel c : {mat.roughnessTexture, mat.metallicTexture, mat.occlusionTexture, mat.alphaTexture,
                                 mat.transmissionTexture})
            if (c.channel < 0 || c.channel > 3) failAt(file, "material " + std::to_string(m) + ": texture channel " + std::to_string(c.channel));
        if (!(mat.metallic >= 0.0f && mat.metallic <= 1.0f) || !(mat.roughness >= 0.0f && mat.roughness <= 1.0f) ||
            !std::isfinite(mat.normalScale) || !(mat.occlusionStrength >= 0.0f && mat.occlusionStrength <= 1.0f))
            failAt(file, "material " + std::to_string(m) + ": metallic, roughness and occlusion strength must be in [0, 1], the normal scale finite");
        if (mat.alphaMode < 0 || mat.alphaMode > GPURT_ALPHA_BLEND || !(mat.alphaFactor >= 0.0f && mat.alphaFactor <= 1.0f) ||
            !(mat.alphaCutoff >= 0.0f && mat.alphaCutoff <= 1.0f))
            failAt(file, "material " + std::to_string(m) + ": alpha mode " + std::to_string(mat.alphaMode) +
                             " (0 to 2), alpha factor and cutoff must be in [0, 1]");
    }
}

// The texture coordinates' count, and each texture's size and wrap modes.
void checkTextures(const FileLoc& file, const Scene& scene) {
    const size_t n = scene.triangles.size();
    if (!scene.texcoords.empty() && scene.texcoords.size() != n)
        failAt(file, std::to_string(scene.texcoords.size()) + " texture coordinates for " + std::to_string(n) + " triangles");
    uint64_t texels = 0;
    for (size_t k = 0; k < scene.textures.size(); ++k) {
        const Texture& t = scene.textures[k];
        const Rgba8Image& image = t.image;
        if (image.width < 1 || image.height < 1 || image.width > kMaxTextureSide || image.height > kMaxTextureSide ||
            uint64_t(image.width) * uint64_t(image.height) > kMaxTextureTexels ||
            image.texels.size() != size_t(image.width) * size_t(image.height))
            failAt(file, "texture " + std::to_string(k) + ": size " + std::to_string(image.width) + "x" +
                             std::to_string(image.height) + " is not 1.." + std::to_string(kMaxTextureSide) + " a side, " + std::to_string(kMaxTextureTexels) + " texels");
        if (t.wrapS > kWrapMirror || t.wrapT > kWrapMirror)
            failAt(file, "texture " + std::to_string(k) + ": wrap modes " + std::to_string(t.wrapS) + ", " +
                             std::to_string(t.wrapT) + " are not 0 (repeat), 1 (clamp) or 2 (mirror)");
        texels += image.texels.size();
    }
    if (texels > kMaxTextureTexels * 2)
        failAt(file, std::to_string(texels) + " texels in all textures; at most " + std::to_string(2 * kMaxTextureTexels));
}

// One colour record per triangle, each corner's linear RGB finite and in [0, 1].
void checkColors(const FileLoc& file, const Scene& scene) {
    const size_t n = scene.triangles.size();
    if (!scene.colors.empty() && scene.colors.size() != n)
        failAt(file, std::to_string(scene.colors.size()) + " vertex colours for " + std::to_string(n) + " triangles");
    for (size_t t = 0; t < scene.colors.size(); ++t)
        for (const glm::vec3 c : {scene.colors[t].c0, scene.colors[t].c1, scene.colors[t].c2})
            if (!isFinite(c) || !nonNegative(c) || glm::any(glm::greaterThan(c, glm::vec3(1.0f))))
                failAt(file, "triangle " + std::to_string(t) + ": vertex colours must be finite and in [0, 1]");
}

// One tangent record per triangle, each corner's four numbers finite and its handedness w -1, 0
// (a corner without a tangent) or 1. The tangent's length is not checked: a zero or tiny one
// falls back to the generated frame where it is used (glsl/common/shading.h normalMappedTangent).
void checkTangents(const FileLoc& file, const Scene& scene) {
    const size_t n = scene.triangles.size();
    if (!scene.tangents.empty() && scene.tangents.size() != n)
        failAt(file, std::to_string(scene.tangents.size()) + " vertex tangents for " + std::to_string(n) + " triangles");
    for (size_t t = 0; t < scene.tangents.size(); ++t)
        for (const glm::vec4 c : {scene.tangents[t].t0, scene.tangents[t].t1, scene.tangents[t].t2})
            if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z) ||
                (c.w != -1.0f && c.w != 0.0f && c.w != 1.0f))
                failAt(file, "triangle " + std::to_string(t) + ": vertex tangents must be finite with w -1, 0 or 1");
}

void checkLights(const FileLoc& file, const Scene& scene) {
    for (size_t l = 0; l < scene.lights.size(); ++l) {
        const Light& light = scene.lights[l];
        if (!isFinite(light.position) || !isFinite(light.color) || !std::isfinite(light.intensity))
            failAt(file, "light " + std::to_string(l) + ": values are not finite");
        if (!nonNegative(light.color) || !(light.intensity >= 0.0f))
            failAt(file, "light " + std::to_string(l) + ": colour and intensity must be >= 0");
    }
}

// The checks of a JSON scene's camera (`what` names it): the contract's basis must exist.
void checkCamera(const FileLoc& file, const CameraSpec& c, const std::string& what) {
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

// Everything about the contents that rendering relies on; `name` prefixes each message. Shared by
// the writer (name = the source scene) and the reader (name = the packed file).
void validateScene(const std::string& name, const LoadedScene& loaded) {
    const FileLoc file{name};
    const Scene& scene = loaded.scene;
    checkTriangles(file, scene);
    checkMaterials(file, scene);
    checkTextures(file, scene);
    checkColors(file, scene);
    checkTangents(file, scene);
    checkLights(file, scene);
    checkCameras(file, scene);
    checkRenderSettings(file, loaded);
}

struct Section {
    std::string tag;
    uint64_t offset = 0, size = 0;
};

// Decodes the sections of a file whose header, size and checksum were checked.
class SectionDecoder {
  public:
    SectionDecoder(std::span<const unsigned char> file, const std::string& name)
        : file_(file), name_(name) {}

    [[noreturn]] void fail(const std::string& what) const { failAt(FileLoc{name_}, what); }

    // The section's bytes, as the accelerators read theirs.
    PackedSection packed(const Section& s) const {
        return PackedSection{s.tag, file_.subspan(size_t(s.offset), size_t(s.size)), FileLoc{name_}};
    }
    ByteReader reader(const Section& s) const { return packed(s).reader(); }
    // PackedSection::count of section s.
    uint64_t count(ByteReader& in, const Section& s, uint64_t recordBytes, bool exact, uint64_t limit,
                   const char* what) const {
        return packed(s).count(in, recordBytes, exact, limit, what);
    }

    void triangles(const Section& s, Scene& scene) const {
        ByteReader in = reader(s);
        const uint64_t n = count(in, s, kTriangleBytes, true, kMaxTextureTriangles, "triangles");
        scene.triangles.resize(size_t(n));
        for (Triangle& t : scene.triangles) {
            t.v0 = in.vec3();
            t.v1 = in.vec3();
            t.v2 = in.vec3();
        }
        scene.materialIds.resize(size_t(n));
        for (uint32_t& id : scene.materialIds) id = in.u32();
    }

    void materials(const Section& s, Scene& scene) const {
        ByteReader in = reader(s);
        const uint64_t n =
            count(in, s, kMaterialMinBytes, false, kMaxTextureMaterials, "materials");
        scene.materials.resize(size_t(n));
        for (uint64_t m = 0; m < n; ++m) {
            Material& mat = scene.materials[size_t(m)];
            mat.diffuse = in.vec3();
            mat.specular = in.vec3();
            mat.shininess = in.f32();
            mat.reflectivity = in.vec3();
            mat.emission = in.vec3();
            mat.ior = in.f32();
            mat.transmission = in.vec3();
            const uint32_t length = in.u32();
            const size_t padded = (size_t(length) + 3) / 4 * 4;
            if (length > in.remaining() || padded > in.remaining())
                fail("section " + s.tag + ": the name of material " + std::to_string(m) + " (" +
                     std::to_string(length) + " bytes) runs past the section's end");
            const unsigned char* text = in.take(padded);
            mat.name.assign(reinterpret_cast<const char*>(text), length);
        }
        if (in.remaining() != 0)
            fail("section " + s.tag + ": " + std::to_string(in.remaining()) +
                 " bytes after the last material");
    }

    void lights(const Section& s, Scene& scene) const {
        ByteReader in = reader(s);
        const uint64_t n = count(in, s, kLightBytes, true, UINT64_MAX, "lights");
        scene.lights.resize(size_t(n));
        for (Light& light : scene.lights) {
            light.position = in.vec3();
            light.color = in.vec3();
            light.intensity = in.f32();
        }
    }

    // The leading count of a section of one record per triangle or per material (read after
    // those), which must be `expected`, the count of `of`; `limit` as for count.
    uint64_t oneEach(ByteReader& in, const Section& s, uint64_t recordBytes, const char* what, uint64_t limit,
                     uint64_t expected, const char* of) const {
        const uint64_t n = count(in, s, recordBytes, true, limit, what);
        if (n != expected)
            fail("section " + s.tag + ": " + std::to_string(n) + " " + what + " for " + std::to_string(expected) +
                 " " + of);
        return n;
    }

    uint64_t perTriangle(ByteReader& in, const Section& s, uint64_t recordBytes, const char* what,
                         const Scene& scene) const {
        return oneEach(in, s, recordBytes, what, kMaxTextureTriangles, scene.triangles.size(), "triangles");
    }

    void normals(const Section& s, Scene& scene) const {
        ByteReader in = reader(s);
        const uint64_t n = perTriangle(in, s, kNormalsBytes, "normals", scene);
        scene.normals.resize(size_t(n));
        for (TriangleNormals& t : scene.normals) {
            t.n0 = in.vec3();
            t.n1 = in.vec3();
            t.n2 = in.vec3();
        }
    }

    // Per triangle c0, c1, c2.
    void colors(const Section& s, Scene& scene) const {
        ByteReader in = reader(s);
        const uint64_t n = perTriangle(in, s, kColorsBytes, "vertex colours", scene);
        scene.colors.resize(size_t(n));
        for (TriangleColors& t : scene.colors) {
            t.c0 = in.vec3();
            t.c1 = in.vec3();
            t.c2 = in.vec3();
        }
    }

    // Per triangle t0, t1, t2, each (x, y, z, w).
    void tangents(const Section& s, Scene& scene) const {
        ByteReader in = reader(s);
        const uint64_t n = perTriangle(in, s, kTangentsBytes, "vertex tangents", scene);
        scene.tangents.resize(size_t(n));
        for (TriangleTangents& t : scene.tangents)
            for (glm::vec4* c : {&t.t0, &t.t1, &t.t2}) {
                const glm::vec3 xyz = in.vec3();
                *c = glm::vec4(xyz, in.f32());
            }
    }

    // Per triangle t0, t1, t2.
    void texcoords(const Section& s, Scene& scene) const {
        ByteReader in = reader(s);
        const uint64_t n = perTriangle(in, s, kTexcoordsBytes, "texture coordinates", scene);
        scene.texcoords.resize(size_t(n));
        for (TriangleTexcoords& t : scene.texcoords) {
            const glm::vec2 c[3] = {{in.f32(), in.f32()}, {in.f32(), in.f32()}, {in.f32(), in.f32()}};
            t = {c[0], c[1], c[2]};
        }
    }

    // The textures (count; then each: width, height, wrapS, wrapT, its name's length, the name
    // padded to 4 bytes, width x height texels), then each material's texture (count = the
    // materials', then an i32 each). Read after the materials.
    void textures(const Section& s, Scene& scene) const {
        ByteReader in = reader(s);
        const uint64_t n = count(in, s, kTextureMinBytes, false, kMaxTextures, "textures");
        scene.textures.resize(size_t(n));
        for (uint64_t k = 0; k < n; ++k) {
            Texture& t = scene.textures[size_t(k)];
            const uint32_t width = in.u32(), height = in.u32();
            t.wrapS = in.u32();
            t.wrapT = in.u32();
            if (width < 1 || height < 1 || width > uint32_t(kMaxTextureSide) || height > uint32_t(kMaxTextureSide) ||
                uint64_t(width) * height > kMaxTextureTexels)
                fail("texture " + std::to_string(k) + ": size " + std::to_string(width) + "x" + std::to_string(height) +
                     " is not 1.." + std::to_string(kMaxTextureSide) + " a side, " + std::to_string(kMaxTextureTexels) + " texels");
            const uint32_t length = in.u32();
            const uint64_t padded = (uint64_t(length) + 3) / 4 * 4;
            const uint64_t texels = uint64_t(width) * height;
            if (padded > in.remaining() || texels * 4 > in.remaining() - padded)
                fail("section " + s.tag + ": texture " + std::to_string(k) + " (" + std::to_string(width) + "x" +
                     std::to_string(height) + ") runs past the section's end");
            const unsigned char* text = in.take(size_t(padded));
            t.name.assign(reinterpret_cast<const char*>(text), length);
            t.image.width = int(width);
            t.image.height = int(height);
            t.image.texels.resize(size_t(texels));
            for (uint32_t& texel : t.image.texels) texel = in.u32();
        }
        if (in.remaining() < 8) fail("section " + s.tag + ": no material textures after the textures");
        const uint64_t materials = in.u64();
        if (materials != scene.materials.size() || in.remaining() != materials * 4)
            fail("section " + s.tag + ": " + std::to_string(materials) + " material textures in " +
                 std::to_string(in.remaining()) + " bytes for " + std::to_string(scene.materials.size()) + " materials");
        for (Material& m : scene.materials) m.diffuseTexture = int(int32_t(in.u32()));
    }

    // Each material's model (count = the materials', then a u32 each). Read after the materials.
    void models(const Section& s, Scene& scene) const {
        ByteReader in = reader(s);
        const uint64_t n = oneEach(in, s, kModelBytes, "material models", kMaxTextureMaterials,
                                   scene.materials.size(), "materials");
        for (uint64_t m = 0; m < n; ++m) {
            const uint32_t model = in.u32();
            if (model > kLastMaterialModel) fail("section " + s.tag + ": " + unknownModel(size_t(m), model));
            scene.materials[size_t(m)].model = int(model);
        }
    }

    // Each material's glTF fields (count = the materials', then kPbrBytes each). Read after the
    // materials.
    void pbr(const Section& s, Scene& scene) const {
        ByteReader in = reader(s);
        const uint64_t n = oneEach(in, s, kPbrBytes, "materials' glTF fields", kMaxTextureMaterials, scene.materials.size(),
                                   "materials");
        for (uint64_t k = 0; k < n; ++k) {
            Material& m = scene.materials[size_t(k)];
            m.metallic = in.f32();
            m.roughness = in.f32();
            m.normalScale = in.f32();
            m.occlusionStrength = in.f32();
            for (TextureChannel* c : {&m.roughnessTexture, &m.metallicTexture, &m.occlusionTexture}) {
                c->texture = int(int32_t(in.u32()));
                c->channel = int(int32_t(in.u32()));
            }
            m.normalTexture = int(int32_t(in.u32()));
            m.emissiveTexture = int(int32_t(in.u32()));
        }
    }

    // Each material's alpha coverage (count = the materials', then kAlphaBytes each). Read after
    // the materials.
    void alpha(const Section& s, Scene& scene) const {
        ByteReader in = reader(s);
        const uint64_t n = oneEach(in, s, kAlphaBytes, "materials' alpha", kMaxTextureMaterials, scene.materials.size(),
                                   "materials");
        for (uint64_t k = 0; k < n; ++k) {
            Material& m = scene.materials[size_t(k)];
            m.alphaMode = int(int32_t(in.u32()));
            m.alphaFactor = in.f32();
            m.alphaCutoff = in.f32();
            m.alphaTexture.texture = int(int32_t(in.u32()));
            m.alphaTexture.channel = int(int32_t(in.u32()));
        }
    }

    // Each material's sidedness (count = the materials', then kSidedBytes each: 1 double-sided, 0
    // single-sided, nothing else). Read after the materials.
    void sided(const Section& s, Scene& scene) const {
        ByteReader in = reader(s);
        const uint64_t n = oneEach(in, s, kSidedBytes, "materials' sides", kMaxTextureMaterials, scene.materials.size(),
                                   "materials");
        for (uint64_t k = 0; k < n; ++k) {
            const uint32_t doubleSided = in.u32();
            if (doubleSided > 1)
                fail("section " + s.tag + ": material " + std::to_string(k) + ": double-sided " +
                     std::to_string(doubleSided) + " (0 or 1)");
            scene.materials[size_t(k)].doubleSided = doubleSided == 1;
        }
    }

    // Whether each material's emission is a light of the scene (count = the materials', then
    // kGlowBytes each: 1 a light, 0 it only glows).
    void glow(const Section& s, Scene& scene) const {
        ByteReader in = reader(s);
        const uint64_t n = oneEach(in, s, kGlowBytes, "materials' emission", kMaxTextureMaterials, scene.materials.size(),
                                   "materials");
        for (uint64_t k = 0; k < n; ++k) {
            const uint32_t light = in.u32();
            if (light > 1)
                fail("section " + s.tag + ": material " + std::to_string(k) + ": emission light " + std::to_string(light) +
                     " (0 or 1)");
            scene.materials[size_t(k)].emissionIsLight = light == 1;
        }
    }

    // Each light's kind and what the kind needs (count = the lights', then kLightKindBytes each:
    // kind, direction, inner and outer cone angles, range). Read after the lights.
    void lightKinds(const Section& s, Scene& scene) const {
        ByteReader in = reader(s);
        const uint64_t n = oneEach(in, s, kLightKindBytes, "lights' kinds", UINT64_MAX, scene.lights.size(), "lights");
        for (uint64_t k = 0; k < n; ++k) {
            Light& l = scene.lights[size_t(k)];
            const uint32_t kind = in.u32();
            l.direction = in.vec3();
            l.innerCone = in.f32();
            l.outerCone = in.f32();
            l.range = in.f32();
            const std::string which = "section " + s.tag + ": light " + std::to_string(k);
            if (kind > 2) fail(which + ": kind " + std::to_string(kind) + " (0 point, 1 spot, 2 directional)");
            l.kind = LightKind(kind);
            const float length2 = glm::dot(l.direction, l.direction);
            if (!(std::abs(length2 - 1.0f) < 1e-3f)) fail(which + ": the direction is not a unit vector");
            if (!(l.innerCone >= 0.0f && l.innerCone < l.outerCone && l.outerCone <= 1.5707964f))
                fail(which + ": cone angles not 0 <= inner < outer <= pi / 2");
            if (!(l.range >= 0.0f && std::isfinite(l.range))) fail(which + ": range not finite and >= 0");
        }
    }

    // Each material's transmission map (count = the materials', then kTransmissionMapBytes each;
    // its texture and channel are checked with the other maps'). Read after the materials.
    void transmissionMaps(const Section& s, Scene& scene) const {
        ByteReader in = reader(s);
        const uint64_t n = oneEach(in, s, kTransmissionMapBytes, "materials' transmission maps", kMaxTextureMaterials,
                                   scene.materials.size(), "materials");
        for (uint64_t k = 0; k < n; ++k) {
            TextureChannel& c = scene.materials[size_t(k)].transmissionTexture;
            c.texture = int(int32_t(in.u32()));
            c.channel = int(int32_t(in.u32()));
        }
    }

    void environment(const Section& s, Scene& scene) const {
        ByteReader in = reader(s);
        if (s.size < 4) fail("section " + s.tag + ": " + std::to_string(s.size) + " bytes, too short");
        const uint32_t flags = in.u32();
        if (flags > 3) fail("section " + s.tag + ": unknown flags " + std::to_string(flags));
        scene.backgroundGiven = (flags & 1u) != 0;
        if (!(flags & 2u)) {
            if (in.remaining() != 0) fail("section " + s.tag + ": " + std::to_string(in.remaining()) + " bytes after the flags");
            return;
        }
        if (s.size < kEnvironmentMinBytes) fail("section " + s.tag + ": " + std::to_string(s.size) + " bytes, too short");
        Environment env;
        env.strength = in.f32();
        env.rotation = in.f32();
        if (!std::isfinite(env.strength) || env.strength < 0.0f || !std::isfinite(env.rotation))
            fail("section " + s.tag + ": strength " + formatFloat(env.strength) + " or rotation " + formatFloat(env.rotation) +
                 " is not valid");
        const uint64_t width = in.u32(), height = in.u32(), nameLength = in.u32();
        if (width < 1 || height < 1 || width > uint64_t(kMaxEnvironmentWidth) || height > uint64_t(kMaxEnvironmentHeight))
            fail("section " + s.tag + ": environment map of " + std::to_string(width) + "x" + std::to_string(height) +
                 " texels, not 1.." + std::to_string(kMaxEnvironmentWidth) + " x 1.." + std::to_string(kMaxEnvironmentHeight));
        if (in.remaining() != nameLength + width * height * 12)
            fail("section " + s.tag + ": " + std::to_string(in.remaining()) + " bytes for a " + std::to_string(nameLength) +
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
                fail("section " + s.tag + ": an environment texel is negative, above 1e30 or not finite");
        env.image = std::move(image);
        scene.environment = std::move(env);
    }

    void fixedSize(const Section& s, uint64_t bytes) const { packed(s).fixedSize(bytes); }

    void camera(const Section& s, Scene& scene) const {
        fixedSize(s, kCameraBytes);
        ByteReader in = reader(s);
        CameraSpec c;
        c.eye = in.vec3();
        c.target = in.vec3();
        c.up = in.vec3();
        c.fovy = in.f32();
        scene.camera = c;
    }

    // The camera's lens: radius, f-stop, focus distance, blades, blade rotation (after the camera).
    void lens(const Section& s, Scene& scene) const {
        fixedSize(s, kLensBytes);
        if (!scene.camera) fail("section " + s.tag + ": a lens without a camera");
        ByteReader in = reader(s);
        CameraSpec& c = *scene.camera;
        c.lensRadius = in.f32();
        c.fstop = in.f32();
        c.focusDistance = in.f32();
        c.blades = int(std::min(in.u32(), 1000u));
        c.bladeRotation = in.f32();
        if (!(c.lensRadius >= 0.0f && c.fstop >= 0.0f && c.focusDistance >= 0.0f && std::isfinite(c.lensRadius) &&
              std::isfinite(c.fstop) && std::isfinite(c.focusDistance) && std::isfinite(c.bladeRotation)) ||
            c.blades == 1 || c.blades == 2 || c.blades > 64)
            fail("section " + s.tag + ": not a lens (radius, f-stop and focus distance >= 0, blades 0 or 3 to 64)");
    }

    // The keys (count, then each key's time and camera), then the frame rate.
    void animation(const Section& s, Scene& scene) const {
        if (s.size < 12) fail("section " + s.tag + ": " + std::to_string(s.size) + " bytes, too short");
        ByteReader in = reader(s);
        const uint64_t n = in.u64();
        if (n < 1 || n > kMaxAnimationKeys || 12 + n * kAnimationKeyBytes != s.size)
            fail("section " + s.tag + ": " + std::to_string(n) + " keys of " + std::to_string(kAnimationKeyBytes) +
                 " bytes do not fill its " + std::to_string(s.size) + " bytes");
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

    void background(const Section& s, Scene& scene) const {
        fixedSize(s, kBackgroundBytes);
        ByteReader in = reader(s);
        scene.background = in.vec3();
    }

    void render(const Section& s, LoadedScene& loaded) const {
        fixedSize(s, kRenderBytes);
        ByteReader in = reader(s);
        const uint32_t bounces = in.u32();
        const uint32_t hasSize = in.u32();
        const uint32_t width = in.u32(), height = in.u32();
        if (bounces > kMaxBounces)
            fail("max bounces " + std::to_string(bounces) + " outside 0.." +
                 std::to_string(kMaxBounces));
        loaded.scene.maxBounces = int(bounces);
        if (hasSize > 1)
            fail("section " + s.tag + ": image size flag " + std::to_string(hasSize) +
                 " is not 0 or 1");
        if (hasSize) {
            if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide)
                fail("image size " + std::to_string(width) + "x" + std::to_string(height) +
                     " outside 1.." + std::to_string(kMaxImageSide) + " per side");
            loaded.size = glm::ivec2(int(width), int(height));
        } else if (width != 0 || height != 0) {
            fail("section " + s.tag + ": an image size without the flag that says it is set");
        }
    }


  private:
    std::span<const unsigned char> file_;
    std::string name_;
};

// Writes the sections of one scene and its grid, in the layout docs/PACKED_FORMAT.md gives.
class SectionEncoder {
  public:
    SectionEncoder(ByteWriter& out, const LoadedScene& loaded, const AccelStructure& accel, const std::string& name)
        : out_(out), loaded_(loaded), scene_(loaded.scene), accel_(accel), name_(name) {}

    void section(std::string_view tag) {
        if (tag == kTriangles) triangles();
        else if (tag == kMaterials) materials();
        else if (tag == kLights) lights();
        else if (tag == kCamera) camera(*scene_.camera);
        else if (tag == kLens) lens(*scene_.camera);
        else if (tag == kAnimation) animation();
        else if (tag == kBackground) out_.vec3(scene_.background);
        else if (tag == kRender) render();
        else if (tag == kNormals) normals();
        else if (tag == kTexcoords) texcoords();
        else if (tag == kColors) colors();
        else if (tag == kTextures) textures();
        else if (tag == kModels) models();
        else if (tag == kPbr) pbr();
        else if (tag == kAlpha) alpha();
        else if (tag == kTangents) tangents();
        else if (tag == kSided) sided();
        else if (tag == kGlow) glow();
        else if (tag == kLightKinds) lightKinds();
        else if (tag == kTransmissionMaps) transmissionMaps();
        else if (tag == kEnvironment) environment();
        else accel_.pack(tag, out_);  // one of the structure's
    }

  private:
    void u32s(const std::vector<uint32_t>& values) {
        for (uint32_t v : values) out_.u32(v);
    }

    void triangles() {
        out_.u64(scene_.triangles.size());
        for (const Triangle& t : scene_.triangles) {
            out_.vec3(t.v0);
            out_.vec3(t.v1);
            out_.vec3(t.v2);
        }
        u32s(scene_.materialIds);
    }

    // A name's length, then the name padded to 4 bytes.
    void name(const std::string& text, const char* what) {
        if (text.size() > UINT32_MAX) failAt(FileLoc{name_}, std::string("a ") + what + " name is too long");
        out_.u32(static_cast<uint32_t>(text.size()));
        out_.raw(text.data(), text.size());
        out_.padTo(4);
    }

    void materials() {
        out_.u64(scene_.materials.size());
        for (const Material& m : scene_.materials) {
            out_.vec3(m.diffuse);
            out_.vec3(m.specular);
            out_.f32(m.shininess);
            out_.vec3(m.reflectivity);
            out_.vec3(m.emission);
            out_.f32(m.ior);
            out_.vec3(m.transmission);
            name(m.name, "material");
        }
    }

    void lights() {
        out_.u64(scene_.lights.size());
        for (const Light& l : scene_.lights) {
            out_.vec3(l.position);
            out_.vec3(l.color);
            out_.f32(l.intensity);
        }
    }

    void camera(const CameraSpec& c) {
        out_.vec3(c.eye);
        out_.vec3(c.target);
        out_.vec3(c.up);
        out_.f32(c.fovy);
    }

    void lens(const CameraSpec& c) {
        out_.f32(c.lensRadius);
        out_.f32(c.fstop);
        out_.f32(c.focusDistance);
        out_.u32(uint32_t(c.blades));
        out_.f32(c.bladeRotation);
    }

    void animation() {
        out_.u64(scene_.animation->keys.size());
        for (const CameraKey& key : scene_.animation->keys) {
            out_.f32(key.time);
            camera(key.camera);
        }
        out_.f32(scene_.animation->fps);
    }

    void render() {
        const std::optional<glm::ivec2>& size = loaded_.size;
        out_.u32(static_cast<uint32_t>(scene_.maxBounces));
        out_.u32(size ? 1 : 0);
        out_.u32(size ? static_cast<uint32_t>(size->x) : 0);
        out_.u32(size ? static_cast<uint32_t>(size->y) : 0);
    }

    void normals() {
        out_.u64(scene_.normals.size());
        for (const TriangleNormals& n : scene_.normals) {
            out_.vec3(n.n0);
            out_.vec3(n.n1);
            out_.vec3(n.n2);
        }
    }

    void colors() {
        out_.u64(scene_.colors.size());
        for (const TriangleColors& c : scene_.colors) {
            out_.vec3(c.c0);
            out_.vec3(c.c1);
            out_.vec3(c.c2);
        }
    }

    void tangents() {
        out_.u64(scene_.tangents.size());
        for (const TriangleTangents& t : scene_.tangents)
            for (const glm::vec4 c : {t.t0, t.t1, t.t2}) {
                out_.vec3(glm::vec3(c));
                out_.f32(c.w);
            }
    }

    void texcoords() {
        out_.u64(scene_.texcoords.size());
        for (const TriangleTexcoords& t : scene_.texcoords)
            for (const glm::vec2 c : {t.t0, t.t1, t.t2}) {
                out_.f32(c.x);
                out_.f32(c.y);
            }
    }

    void textures() {
        out_.u64(scene_.textures.size());
        for (const Texture& t : scene_.textures) {
            out_.u32(uint32_t(t.image.width));
            out_.u32(uint32_t(t.image.height));
            out_.u32(t.wrapS);
            out_.u32(t.wrapT);
            name(t.name, "texture");
            for (uint32_t texel : t.image.texels) out_.u32(texel);
        }
        out_.u64(scene_.materials.size());
        for (const Material& m : scene_.materials) out_.u32(uint32_t(int32_t(m.diffuseTexture)));
    }

    void models() {
        out_.u64(scene_.materials.size());
        for (const Material& m : scene_.materials) out_.u32(uint32_t(m.model));
    }

    void pbr() {
        out_.u64(scene_.materials.size());
        for (const Material& m : scene_.materials) {
            out_.f32(m.metallic);
            out_.f32(m.roughness);
            out_.f32(m.normalScale);
            out_.f32(m.occlusionStrength);
            for (TextureChannel c : {m.roughnessTexture, m.metallicTexture, m.occlusionTexture}) {
                out_.u32(uint32_t(int32_t(c.texture)));
                out_.u32(uint32_t(int32_t(c.channel)));
            }
            out_.u32(uint32_t(int32_t(m.normalTexture)));
            out_.u32(uint32_t(int32_t(m.emissiveTexture)));
        }
    }

    void sided() {
        out_.u64(scene_.materials.size());
        for (const Material& m : scene_.materials) out_.u32(m.doubleSided ? 1u : 0u);
    }

    void glow() {
        out_.u64(scene_.materials.size());
        for (const Material& m : scene_.materials) out_.u32(m.emissionIsLight ? 1u : 0u);
    }

    void lightKinds() {
        out_.u64(scene_.lights.size());
        for (const Light& l : scene_.lights) {
            out_.u32(uint32_t(l.kind));
            out_.vec3(l.direction);
            out_.f32(l.innerCone);
            out_.f32(l.outerCone);
            out_.f32(l.range);
        }
    }

    void transmissionMaps() {
        out_.u64(scene_.materials.size());
        for (const Material& m : scene_.materials) {
            out_.u32(uint32_t(int32_t(m.transmissionTexture.texture)));
            out_.u32(uint32_t(int32_t(m.transmissionTexture.channel)));
        }
    }

    void alpha() {
        out_.u64(scene_.materials.size());
        for (const Material& m : scene_.materials) {
            out_.u32(uint32_t(m.alphaMode));
            out_.f32(m.alphaFactor);
            out_.f32(m.alphaCutoff);
            out_.u32(uint32_t(int32_t(m.alphaTexture.texture)));
            out_.u32(uint32_t(int32_t(m.alphaTexture.channel)));
        }
    }

    // Flags (1: the file set the background, 2: an environment follows), then the environment's
    // strength, rotation, width, height, file name and texels (linear RGB, top row first).
    void environment() {
        const std::optional<Environment>& env = scene_.environment;
        out_.u32((scene_.backgroundGiven ? 1u : 0u) | (env ? 2u : 0u));
        if (!env) return;
        out_.f32(env->strength);
        out_.f32(env->rotation);
        out_.u32(uint32_t(env->image->width));
        out_.u32(uint32_t(env->image->height));
        out_.u32(uint32_t(env->file.size()));
        out_.raw(env->file.data(), env->file.size());
        for (const glm::vec3& t : env->image->texels) out_.vec3(t);
    }

    ByteWriter& out_;
    const LoadedScene& loaded_;
    const Scene& scene_;
    const AccelStructure& accel_;
    std::string name_;
};

// The section table: each known scene section's entry, by its place in kSectionOrder, and the
// acceleration structure's, whole: its accelerator and its sections in that one's order.
struct SectionTable {
    std::array<std::optional<Section>, std::size(kSectionOrder)> scene;
    const AcceleratorInfo* accelerator = nullptr;
    std::vector<Section> structure;
};

size_t sectionIndex(std::string_view tag) {
    for (size_t k = 0; k < std::size(kSectionOrder); ++k)
        if (tag == kSectionOrder[k]) return k;
    return std::size(kSectionOrder);
}

// The accelerator a section tag is one of, or null.
const AcceleratorInfo* acceleratorOf(std::string_view tag) {
    for (const AcceleratorInfo* a : accelerators())
        if (std::find(a->sections.begin(), a->sections.end(), tag) != a->sections.end()) return a;
    return nullptr;
}

// "the grid's (GRID, CELL, LIST) or the bvh's (BVHN, BVHL)", from the registry.
std::string structureSections() {
    std::string text;
    for (const AcceleratorInfo* a : accelerators()) {
        if (!text.empty()) text += a == accelerators().back() ? " or " : ", ";
        text += "the " + std::string(a->name) + "'s (";
        for (size_t k = 0; k < a->sections.size(); ++k) text += (k ? ", " : "") + std::string(a->sections[k]);
        text += ")";
    }
    return text;
}

// Magic and version first: a later version may lay out (and checksum) the rest differently. Then
// the file's size against the header's and the checksum.
void checkHeader(std::span<const unsigned char> bytes, const FileLoc& file) {
    const size_t size = bytes.size();
    const size_t magicSize = sizeof kPackedSceneMagic - 1;
    if (size > 0 && std::memcmp(bytes.data(), kPackedSceneMagic, std::min(size, magicSize)) != 0)
        failAt(file, "not a packed gpurt scene (wrong magic '" +
                         printable(std::string_view(reinterpret_cast<const char*>(bytes.data()),
                                                    std::min(size, magicSize))) +
                         "', expected " + std::string(kPackedSceneMagic) + ")");
    if (size < 12)
        failAt(file, "truncated: " + std::to_string(size) + " bytes, less than the " +
                         std::to_string(kPackedHeaderBytes) + "-byte header");
    const uint32_t version = load32(bytes.data() + 8);
    if (version != kPackedSceneVersion)
        failAt(file, "unknown packed format version " + std::to_string(version) +
                         " (this gpurt reads version " + std::to_string(kPackedSceneVersion) + ")");
    if (size < kPackedHeaderBytes)
        failAt(file, "truncated: " + std::to_string(size) + " bytes, less than the " +
                         std::to_string(kPackedHeaderBytes) + "-byte header");
    const uint64_t declared = load64(bytes.data() + 16);
    if (declared > size)
        failAt(file, "truncated: " + std::to_string(size) + " of the " + std::to_string(declared) +
                         " bytes the header gives");
    if (declared < size)
        failAt(file, std::to_string(size) + " bytes, but the header gives " + std::to_string(declared) +
                         " (trailing data or a damaged header)");
    const uint32_t stored = load32(bytes.data() + 12);
    const uint32_t computed = crc32Of(bytes.subspan(16));
    if (stored != computed)
        failAt(file, "checksum mismatch (the contents have CRC-32 " + hex32(computed) +
                         ", the header says " + hex32(stored) + "): the file is damaged");
}

// The section table of a file whose header was checked: known tags, none twice, each section
// after the one before and inside the file, every required one present.
SectionTable readSectionTable(std::span<const unsigned char> bytes, const FileLoc& file) {
    const size_t size = bytes.size();
    const uint32_t sectionCount = load32(bytes.data() + 24);
    if (load32(bytes.data() + 28) != 0) failAt(file, "reserved header field is not 0");
    if (sectionCount > kMaxSections ||
        kPackedHeaderBytes + uint64_t(sectionCount) * kPackedSectionEntryBytes > size)
        failAt(file, "section table of " + std::to_string(sectionCount) + " entries does not fit the " +
                         std::to_string(size) + "-byte file");
    SectionTable sections;
    bool mixed = false;  // sections of two accelerators
    uint64_t end = kPackedHeaderBytes + uint64_t(sectionCount) * kPackedSectionEntryBytes;
    for (uint32_t k = 0; k < sectionCount; ++k) {
        const unsigned char* entry =
            bytes.data() + kPackedHeaderBytes + size_t(k) * kPackedSectionEntryBytes;
        Section s;
        s.tag.assign(reinterpret_cast<const char*>(entry), 4);
        s.offset = load64(entry + 8);
        s.size = load64(entry + 16);
        const size_t index = sectionIndex(s.tag);
        const AcceleratorInfo* accelerator = acceleratorOf(s.tag);
        if (index == sections.scene.size() && !accelerator)
            failAt(file, "unknown section '" + printable(s.tag) + "'");
        if (load32(entry + 4) != 0) failAt(file, "section " + s.tag + ": reserved field is not 0");
        const bool twice = accelerator ? std::any_of(sections.structure.begin(), sections.structure.end(),
                                                     [&](const Section& t) { return t.tag == s.tag; })
                                       : bool(sections.scene[index]);
        if (twice) failAt(file, "section " + s.tag + " appears twice");
        // Sections follow the table in table order, 8-byte aligned, without overlapping.
        if (s.offset % 8 != 0 || s.offset < end || s.offset > size || s.size > size - s.offset)
            failAt(file, "section " + s.tag + " (offset " + std::to_string(s.offset) + ", " +
                             std::to_string(s.size) + " bytes) does not fit the " + std::to_string(size) +
                             "-byte file");
        end = s.offset + s.size;
        if (!accelerator) {
            sections.scene[index] = s;
        } else {
            mixed = mixed || (sections.accelerator && sections.accelerator != accelerator);
            sections.accelerator = accelerator;
            sections.structure.push_back(s);
        }
    }
    for (size_t k = 0; k < std::size(kSectionOrder); ++k)
        if (!sections.scene[k] && !optionalSection(kSectionOrder[k]))
            failAt(file, std::string("section ") + kSectionOrder[k] + " is missing");
    // One acceleration structure, whole: one accelerator's sections, all of them; they are put in
    // its order for its reader.
    const AcceleratorInfo* a = sections.accelerator;
    std::vector<Section> ordered;
    if (a && !mixed)
        for (std::string_view tag : a->sections)
            for (const Section& s : sections.structure)
                if (s.tag == tag) ordered.push_back(s);
    if (!a || ordered.size() != a->sections.size())
        failAt(file, "the acceleration structure's sections are not one accelerator's, whole: " + structureSections());
    sections.structure = std::move(ordered);
    return sections;
}

}  // namespace

std::vector<unsigned char> encodePackedScene(const LoadedScene& loaded, const AccelStructure& accel,
                                             const std::string& name) {
    validateScene(name, loaded);
    accel.validate(FileLoc{name}, loaded.scene);

    ByteWriter out;
    out.raw(kPackedSceneMagic, sizeof kPackedSceneMagic - 1);
    out.u32(kPackedSceneVersion);
    out.u32(0);  // CRC-32, patched last
    out.u64(0);  // file size, patched last
    std::vector<std::string_view> tags;
    for (const char* tag : kSectionOrder) {
        if (hasSection(loaded, tag)) tags.push_back(tag);
        if (tag == kStructureAfter)
            tags.insert(tags.end(), accel.accelerator().sections.begin(), accel.accelerator().sections.end());
    }
    out.u32(static_cast<uint32_t>(tags.size()));
    out.u32(0);
    const size_t table = out.size();
    for (size_t k = 0; k < tags.size(); ++k) {
        out.raw(tags[k].data(), 4);
        out.u32(0);
        out.u64(0);  // offset, patched below
        out.u64(0);  // size, patched below
    }

    SectionEncoder encoder(out, loaded, accel, name);
    for (size_t k = 0; k < tags.size(); ++k) {
        out.padTo(8);
        const size_t start = out.size();
        encoder.section(tags[k]);
        const size_t entry = table + k * kPackedSectionEntryBytes;
        out.patch64(entry + 8, start);
        out.patch64(entry + 16, out.size() - start);
    }
    out.padTo(8);

    std::vector<unsigned char>& bytes = out.bytes();
    out.patch64(16, bytes.size());
    out.patch32(12, crc32Of(std::span(bytes).subspan(16)));
    return std::move(bytes);
}

void writePackedScene(const std::filesystem::path& path, std::span<const unsigned char> bytes) {
    writeFileAtomically(path, [&](std::FILE* file) {
        if (std::fwrite(bytes.data(), 1, bytes.size(), file) != bytes.size())
            failAt(FileLoc{path.string()}, std::string("cannot write file (") + std::strerror(errno) + ")");
    });
}

void writePackedScene(const std::filesystem::path& path, const LoadedScene& scene, const AccelStructure& accel,
                      const std::string& name) {
    writePackedScene(path, encodePackedScene(scene, accel, name));
}

LoadedScene decodePackedScene(std::span<const unsigned char> bytes, const std::string& name) {
    const FileLoc file{name};
    checkHeader(bytes, file);
    const SectionTable sections = readSectionTable(bytes, file);
    auto section = [&](const char* tag) -> const std::optional<Section>& { return sections.scene[sectionIndex(tag)]; };

    // The sections, each sized by its counts before anything is allocated.
    const SectionDecoder decoder(bytes, name);
    LoadedScene loaded;
    decoder.triangles(*section(kTriangles), loaded.scene);
    decoder.materials(*section(kMaterials), loaded.scene);
    decoder.lights(*section(kLights), loaded.scene);
    if (section(kCamera)) decoder.camera(*section(kCamera), loaded.scene);
    if (section(kLens)) decoder.lens(*section(kLens), loaded.scene);
    decoder.background(*section(kBackground), loaded.scene);
    decoder.render(*section(kRender), loaded);
    if (section(kNormals)) decoder.normals(*section(kNormals), loaded.scene);
    if (section(kAnimation)) decoder.animation(*section(kAnimation), loaded.scene);
    if (section(kTexcoords)) decoder.texcoords(*section(kTexcoords), loaded.scene);
    if (section(kColors)) decoder.colors(*section(kColors), loaded.scene);
    if (section(kTextures)) decoder.textures(*section(kTextures), loaded.scene);
    if (section(kModels)) decoder.models(*section(kModels), loaded.scene);
    if (section(kPbr)) decoder.pbr(*section(kPbr), loaded.scene);
    if (section(kAlpha)) decoder.alpha(*section(kAlpha), loaded.scene);
    if (section(kTangents)) decoder.tangents(*section(kTangents), loaded.scene);
    if (section(kSided)) decoder.sided(*section(kSided), loaded.scene);
    if (section(kGlow)) decoder.glow(*section(kGlow), loaded.scene);
    if (section(kLightKinds)) decoder.lightKinds(*section(kLightKinds), loaded.scene);
    if (section(kTransmissionMaps)) decoder.transmissionMaps(*section(kTransmissionMaps), loaded.scene);
    if (section(kEnvironment)) decoder.environment(*section(kEnvironment), loaded.scene);
    validateScene(name, loaded);

    // The structure last: its accelerator reads and checks it against the checked scene.
    std::vector<PackedSection> structure;
    for (const Section& s : sections.structure) structure.push_back(decoder.packed(s));
    loaded.accel = sections.accelerator->unpack(structure, loaded.scene);
    return loaded;
}

LoadedScene readPackedScene(const std::filesystem::path& path) {
    const std::string bytes = readSceneFile(path);
    return decodePackedScene(std::span(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()), path.string());
}

}  // namespace gpurt
