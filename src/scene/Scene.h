// The scene as both backends see it: a flat triangle list in the contract's numbering (one
// material per triangle), point lights, an optional camera and a few render parameters.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "image/EnvironmentImage.h"
#include "image/TextureImage.h"
#include "scene/MaterialModels.h"

namespace gpurt {

// One channel (0 R, 1 G, 2 B, 3 A) of a texture of Scene::textures, read as linear numbers;
// texture -1: none.
struct TextureChannel {
    int texture = -1;
    int channel = 0;

    bool given() const { return texture >= 0; }
};

// Phong material from an MTL file (Kd, Ks, Ns); reflectivity is the mirror weight of a Whitted
// reflection (Ks when the MTL illumination model turns ray-traced reflection on, else 0).
struct Material {
    glm::vec3 diffuse{0.8f};
    glm::vec3 specular{0.0f};
    float shininess = 16.0f;
    glm::vec3 reflectivity{0.0f};
    std::string name = "default";
    // Radiance emitted from both sides (MTL Ke, JSON emission): its triangles are area lights.
    glm::vec3 emission{0.0f};
    // A dielectric (glass) when ior > 0: Fresnel reflection and refraction with this index of
    // refraction (MTL illum 4, 6, 7 with Ni; JSON ior), the refracted ray filtered by
    // transmission (Tf). reflectivity is then unused. The glTF model (below) reads them as
    // KHR_materials_ior (0: 1.5) and, where ior > 0, KHR_materials_transmission's factor
    // (transmission.x; 0: opaque).
    float ior = 0.0f;
    glm::vec3 transmission{1.0f};
    // Index into Scene::textures, or -1: the diffuse colour at a hit is diffuse times the
    // texture's linear colour at the hit's texture coordinates (glTF baseColorTexture, MTL map_Kd).
    int diffuseTexture = -1;
    // The material model (scene/MaterialModels.h; GPURT_MODEL_*): 0, the classic model of the
    // fields above (glsl/common/materials/classic.h); 2, glTF's metallic-roughness
    // (glsl/common/materials/gltf.h: diffuse is the base colour, with the fields below).
    int model = 0;
    // glTF model: metallic and roughness factors, each times a texture's channel where it has one
    // (glTF metallicRoughnessTexture: roughness G, metallic B; MTL map_Pr / map_Pm: R).
    float metallic = 0.0f;
    float roughness = 1.0f;
    TextureChannel roughnessTexture, metallicTexture;
    // Tangent-space normal map (glTF normalTexture, MTL norm) and its scale (x, y times it).
    int normalTexture = -1;
    float normalScale = 1.0f;
    // The emission is emission times this texture's colour (sRGB) where it has one (glTF
    // emissiveTexture, MTL map_Ke). Such emitters are not sampled as lights (found by rays only).
    int emissiveTexture = -1;
    // Ambient occlusion (glTF occlusionTexture, channel R): the ambient terms are times
    // 1 + strength (texel - 1).
    TextureChannel occlusionTexture;
    float occlusionStrength = 1.0f;
    // glTF KHR_materials_transmission's transmissionTexture (channel R, linear): where the
    // material transmits (transmits(): the factor transmission.x > 0), the factor at a hit is
    // times this channel there.
    TextureChannel transmissionTexture;
    // Alpha coverage (glsl/common/alpha.h GPURT_ALPHA_*): 0 opaque; 1 MASK, the surface is there
    // where alpha >= alphaCutoff; 2 BLEND, rays pass it with probability 1 - alpha. alpha is
    // alphaFactor times alphaTexture's channel where it has one (glTF baseColorFactor[3] times
    // baseColorTexture's A; MTL d times map_d's R).
    int alphaMode = 0;
    float alphaFactor = 1.0f;
    float alphaCutoff = 0.5f;
    TextureChannel alphaTexture;
    // Whether rays see the surface from behind (glTF doubleSided; OBJ, PLY and JSON surfaces are
    // always double-sided). A single-sided surface's back faces (where the ray meets the triangle's
    // winding clockwise: dot(d, cross(v1 - v0, v2 - v0)) > 0) are culled by every traversal, for
    // every ray, as alpha coverage is (glsl/common/alpha.h).
    bool doubleSided = true;
    // Whether its emission is a light the scene declares (OBJ Ke, JSON), which switches the default
    // light off (CONTRACT.md, "Lights"); glTF's emissive materials only glow (false).
    bool emissionIsLight = true;

    // glTF model, KHR_materials_specular: the dielectric's F0 colour is min(F0(ior) x
    // specularColor, 1) and its specular layer weighs specularFactor (its F90); specularTexture's
    // A times the factor, specularColorTexture's colour (sRGB) times the colour.
    float specularFactor = 1.0f;
    glm::vec3 specularColor{1.0f};
    TextureChannel specularTexture;
    int specularColorTexture = -1;
    // glTF model, KHR_materials_clearcoat: a smooth or GGX dielectric coat (ior 1.5) of weight
    // clearcoat (times clearcoatTexture's R) and roughness clearcoatRoughness (times
    // clearcoatRoughnessTexture's G) over the rest, with its own normal map (none: the
    // interpolated normal, not the base's map).
    float clearcoat = 0.0f;
    float clearcoatRoughness = 0.0f;
    TextureChannel clearcoatTexture, clearcoatRoughnessTexture;
    int clearcoatNormalTexture = -1;
    float clearcoatNormalScale = 1.0f;
    // glTF model, KHR_materials_sheen: the Charlie sheen of colour sheenColor (times
    // sheenColorTexture, sRGB) and roughness sheenRoughness (times sheenRoughnessTexture's A) over
    // the rest, which the sheen's albedo scales down; black: no sheen.
    glm::vec3 sheenColor{0.0f};
    float sheenRoughness = 0.0f;
    int sheenColorTexture = -1;
    TextureChannel sheenRoughnessTexture;
    // glTF model, KHR_materials_iridescence: a thin film of index iridescenceIor over the base, of
    // weight iridescenceFactor (times iridescenceTexture's R) and thickness (nm) from
    // iridescenceThicknessMin to iridescenceThicknessMax by iridescenceThicknessTexture's G (the
    // maximum without it); factor 0: no film.
    float iridescenceFactor = 0.0f;
    TextureChannel iridescenceTexture;
    float iridescenceIor = 1.3f;
    float iridescenceThicknessMin = 100.0f;
    float iridescenceThicknessMax = 400.0f;
    TextureChannel iridescenceThicknessTexture;
    // glTF model, KHR_materials_anisotropy: the base's specular lobe rougher along a direction in
    // the tangent frame (TANGENT, or the one the texture coordinates make), of strength
    // anisotropyStrength (times anisotropyTexture's B), anisotropyRotation radians counter-clockwise
    // from the tangent (turning the map's RG direction); strength 0: isotropic.
    float anisotropyStrength = 0.0f;
    float anisotropyRotation = 0.0f;
    int anisotropyTexture = -1;  // linear RGB
    // glTF model, KHR_materials_volume: behind a transmissive surface, a solid whose medium absorbs
    // (Beer-Lambert) so that light travelling attenuationDistance inside it (scene units; infinite:
    // nothing absorbed) keeps attenuationColor of itself. thickness 0 is the extension's thin wall
    // (no volume). The rays measure the distance they travel inside, so the thickness's value (and
    // thicknessTexture: the glTF reader warns) is needed only to tell a volume from a thin wall.
    float thickness = 0.0f;
    // glTF model, KHR_materials_transmission's thin wall (no KHR_materials_volume, or its
    // thicknessFactor 0): light passes the surface without bending, as through an infinitely thin
    // sheet (the reflection's lobe mirrored through the surface), and no medium lies behind it. A
    // JSON material's transmission is a solid unless "thin_walled" says so.
    bool thinWalled = false;
    glm::vec3 attenuationColor{1.0f};
    float attenuationDistance = std::numeric_limits<float>::infinity();
    // glTF model, KHR_materials_dispersion: 20 / the Abbe number of a transmissive solid's
    // medium; its index at each colour's wavelength under path tracing
    // (glsl/common/material.h dispersedIor); 0: the same index for every wavelength.
    float dispersion = 0.0f;

    bool hasAlpha() const { return alphaMode != 0; }
    // Whether it uses KHR_materials_specular's values (the kernels compile them in then).
    bool hasSpecularLayer() const {
        return specularFactor != 1.0f || specularColor != glm::vec3(1.0f) || specularTexture.given() ||
               specularColorTexture >= 0;
    }
    bool hasClearcoat() const { return clearcoat > 0.0f; }
    bool hasSheen() const { return sheenColor != glm::vec3(0.0f); }
    bool hasIridescence() const { return model == GPURT_MODEL_GLTF && iridescenceFactor > 0.0f; }
    bool hasAnisotropy() const { return model == GPURT_MODEL_GLTF && anisotropyStrength > 0.0f; }
    // Whether the index depends on the wavelength: a dispersion on a solid that light passes into
    // (the extension applies to volumes only, not to thin walls).
    bool disperses() const { return model == GPURT_MODEL_GLTF && dispersion > 0.0f && transmits() && !thinWalled; }
    // The rotation as (cos, sin), as both backends read it (glsl/common/materials/gltf.h gltfAnisotropyAt).
    glm::vec2 anisotropyTurn() const {
        return {float(std::cos(double(anisotropyRotation))), float(std::sin(double(anisotropyRotation)))};
    }
    // Whether the volume behind it absorbs: a glTF material that transmits (the extension needs
    // one that does), KHR_materials_volume's thickness > 0 and an attenuation.
    bool hasVolume() const {
        return model == GPURT_MODEL_GLTF && transmits() && !thinWalled && thickness > 0.0f && attenuationDistance < std::numeric_limits<float>::infinity() &&
               attenuationColor != glm::vec3(1.0f);
    }
    // The medium's absorption coefficient -ln(attenuationColor) / attenuationDistance per channel
    // (a black channel absorbs as if its colour were 1e-30); 0 without a volume.
    glm::vec3 absorption() const {
        if (!hasVolume()) return glm::vec3(0.0f);
        return -glm::log(glm::max(attenuationColor, glm::vec3(1e-30f))) / attenuationDistance;
    }
    // Whether rays pass into it: classic glass (ior > 0), the glTF model's transmission (ior > 0
    // and a factor transmission.x > 0; ior alone is KHR_materials_ior's F0).
    bool transmits() const { return ior > 0.0f && (model != GPURT_MODEL_GLTF || transmission.x > 0.0f); }
    // Whether it transmits through a thin wall (the kernels' record: thin).
    bool thin() const { return model == GPURT_MODEL_GLTF && thinWalled && transmits(); }
    // Whether the traversals cull the back faces: single-sided and not transmissive. A dielectric
    // is never culled, as the rays inside a solid meet its back faces.
    bool cullsBackFaces() const { return !doubleSided && !transmits(); }
    bool emits() const { return emission != glm::vec3(0.0f); }
    // Whether shadow rays pass it (glsl/common/alpha.h GPURT_COVER_SHADOWLESS): KHR_materials_unlit.
    bool castsNoShadow() const { return model == GPURT_MODEL_UNLIT; }
};

// Wrap modes of a texture's coordinates (the values of glsl/common/texture.h).
enum TextureWrap : uint32_t { kWrapRepeat = 0, kWrapClamp = 1, kWrapMirror = 2 };

// A decoded texture image and how coordinates outside [0, 1] wrap.
struct Texture {
    std::string name;  // where it came from (file, or glTF image), for messages and pack --dump
    Rgba8Image image;
    uint32_t wrapS = kWrapRepeat, wrapT = kWrapRepeat;
};

// Texture coordinates at a triangle's corners in image coordinates: (0, 0) the top-left corner of
// the image, (1, 1) the bottom-right one (glTF's TEXCOORD; OBJ's vt (u, v) are stored as (u, 1 - v)).
struct TriangleTexcoords {
    glm::vec2 t0{0.0f}, t1{0.0f}, t2{0.0f};
};

// A punctual light (CONTRACT.md, "Lights"; the kinds are glsl/common/shading.h GPURT_LIGHT_*).
// Units: a white Lambert surface facing a point or spot light of intensity I at distance d has
// radiance I / d^2 (its radiant intensity is pi I); facing a directional light of intensity I,
// radiance I (its irradiance is pi I). glTF's lights are pi times darker (GltfLoader divides).
enum class LightKind : uint32_t { Point = 0, Spot = 1, Directional = 2 };

struct Light {
    glm::vec3 position{0.0f};  // point, spot
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    LightKind kind = LightKind::Point;
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // spot, directional: the way the light travels (unit)
    float innerCone = 0.0f;                  // spot: the cone angles in radians (glTF's defaults)
    float outerCone = 0.78539816f;
    float range = 0.0f;  // point, spot: where the light ends (glTF's window); 0: nowhere

    // A point light as gpurt had it before the other kinds: packed scenes keep no more of it.
    bool plainPoint() const { return kind == LightKind::Point && range == 0.0f; }
};

// The environment light (CONTRACT.md): a latitude-longitude map around the scene that rays
// leaving it see, scaled by `strength` and turned by `rotation` degrees about +Y (positive:
// counter-clockwise seen from above). `file` names it ("default": the procedural default light).
struct Environment {
    std::shared_ptr<const EnvironmentImage> image;  // never null
    float strength = 1.0f;
    float rotation = 0.0f;
    std::string file;
    bool sampled = true;     // path: next-event estimation samples it (--env-sampling bsdf: only BSDF rays find it)
    bool isDefault = false;  // the default light of a scene without light (defaultEnvironment)
};

// The default light (docs/SCENE_FORMAT.md): a procedural studio sky, made once as a 512 x 256 map.
Environment defaultEnvironment();

// The contract's camera parameters (CONTRACT.md, camera convention); fovy in degrees.
struct CameraSpec {
    glm::vec3 eye{0.0f};
    glm::vec3 target{0.0f, 0.0f, -1.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovy = 45.0f;
    // Depth of field (CONTRACT.md, thin lens); none while lensRadius and fstop are 0, and then the
    // pixels are the pinhole camera's, exactly.
    float lensRadius = 0.0f;     // scene units
    float fstop = 0.0f;          // > 0: the lens radius is f / (2 fstop) metres (makeCamera), not lensRadius
    float focusDistance = 0.0f;  // along the view direction; 0: |target - eye|
    int blades = 0;              // 0: a round aperture; else a regular polygon of `blades` >= 3 corners
    float bladeRotation = 0.0f;  // degrees from right towards up of the first corner
    float metre = 1.0f;          // one metre in scene units (2^-e in a scene rescaled by 2^-e), for fstop

    bool hasLens() const { return lensRadius > 0.0f || fstop > 0.0f; }
};

// A camera animated by keyframes (a JSON scene's "animation"): frame f is at time f / fps seconds.
// Between two keys each of eye, target, up and fovy is interpolated linearly (in double, then
// rounded to float); before the first key and after the last the camera is that key's.
struct CameraKey {
    float time = 0.0f;
    CameraSpec camera;
};

struct CameraAnimation {
    float fps = 24.0f;
    std::vector<CameraKey> keys;  // at least one, times strictly increasing

    double timeOf(int frame) const { return double(frame) / double(fps); }
    CameraSpec at(int frame) const;
};

struct Triangle {
    glm::vec3 v0, v1, v2;
};

// The axis that points up in a scene file's coordinates (--up-axis, a JSON scene's "up_axis"): y
// in gpurt's own convention (and OBJ's, glTF's); z in most CAD and scanning data.
enum class UpAxis { PosX, NegX, PosY, NegY, PosZ, NegZ };

// "x", "-x", "y", "-y", "z", "-z" -> the axis; false for anything else.
bool parseUpAxis(const std::string& text, UpAxis& axis);
const char* upAxisName(UpAxis axis);
// The rotation that turns `axis` into +y, an axis permutation with signs (exact in float, and
// proper: no mirror image): z: (x, y, z) -> (x, z, -y); -z: (x, -z, y); x: (-y, x, z);
// -x: (y, -x, z); -y: (x, -y, -z).
glm::vec3 upAxisToY(glm::vec3 v, UpAxis axis);

// The shading normals at a triangle's vertices (OBJ vn, or made by smoothNormals). All zero: the
// triangle has none (it is shaded with its geometric normal until smoothNormals gives it some).
struct TriangleNormals {
    glm::vec3 n0{0.0f}, n1{0.0f}, n2{0.0f};

    bool given() const { return n0 != glm::vec3(0.0f) || n1 != glm::vec3(0.0f) || n2 != glm::vec3(0.0f); }
};

// The vertex colours at a triangle's corners, linear RGB in [0, 1] (PLY red/green/blue, glTF
// COLOR_0): the diffuse colour at a hit is multiplied by their interpolation
// (glsl/common/shading.h interpolateVertexColor). White (the default) changes nothing: the
// triangles of a scene that has colours elsewhere but none of their own.
struct TriangleColors {
    glm::vec3 c0{1.0f}, c1{1.0f}, c2{1.0f};
};

// The vertex tangents at a triangle's corners (glTF TANGENT): xyz a unit tangent in scene space, w
// its handedness, +1 or -1 (the bitangent is cross(normal, tangent) * w). All zero: the triangle
// has none, and its normal map uses tangents generated from its texture coordinates
// (glsl/common/shading.h normalMappedTangent); so does a hit where the interpolated tangent is
// zero, not finite or parallel to the normal.
struct TriangleTangents {
    glm::vec4 t0{0.0f}, t1{0.0f}, t2{0.0f};
};

// Axis-aligned box; starts empty (min = +inf, max = -inf) so that extend() needs no special case.
struct Bounds {
    glm::vec3 min{std::numeric_limits<float>::infinity()};
    glm::vec3 max{-std::numeric_limits<float>::infinity()};

    void extend(glm::vec3 p);
    bool empty() const;  // true until a point was added
    glm::vec3 center() const;
    glm::vec3 halfExtent() const;
};

struct Scene {
    // Contract numbering: the k-th triangle of the OBJ, polygons as fans (v0, vi, vi+1).
    std::vector<Triangle> triangles;
    std::vector<uint32_t> materialIds;  // one per triangle, index into materials
    // Empty (faceted), or one per triangle: the file's vertex normals, then smoothNormals'.
    std::vector<TriangleNormals> normals;
    // Empty (no textured material), or one per triangle (zeros where a file gave none).
    std::vector<TriangleTexcoords> texcoords;
    // Empty (no vertex colours), or one per triangle (white where a file gave none).
    std::vector<TriangleColors> colors;
    // Empty (no vertex tangents), or one per triangle (zeros where a file gave none): only for
    // triangles whose material has a normal map.
    std::vector<TriangleTangents> tangents;
    // Never empty (index 0 = the default material when the OBJ has none).
    std::vector<Material> materials;
    std::vector<Texture> textures;  // the materials' diffuseTexture indices refer to these
    // May be empty: renderers then add a headlight (lightsOrHeadlight).
    std::vector<Light> lights;
    std::optional<CameraSpec> camera;  // OBJ: none
    std::optional<CameraAnimation> animation;  // JSON "animation"; none elsewhere
    glm::vec3 background{0.05f, 0.05f, 0.08f};
    bool backgroundGiven = false;  // the file set the background (JSON "background")
    // The environment light (--env, JSON "environment", or the default light); rays that leave
    // the scene see it instead of the background.
    std::optional<Environment> environment;
    int maxBounces = 3;
    // The up axis the file says it has (JSON "up_axis"); the commands turn it up (rotateUpToY).
    UpAxis upAxis = UpAxis::PosY;

    // Box of all triangle vertices; empty() for a scene without triangles.
    Bounds bounds() const;
};

// The lights a renderer uses: the scene's point lights, or, when it has no light of any kind (no
// point light and no emitting triangle), one headlight at the camera eye
// with colour 1 and intensity |eye - centre|^2 / 2 of the scene's box, so that its 1/d^2 falloff
// gives 1/2 at the centre of the scene. Both backends call this, so they light identically.
// `backgroundLights`: the path integrator, under which a background that is not black is a light
// too (CONTRACT.md): it then adds no headlight.
// Rotates everything placed in the scene (triangles, shading normals and tangents, lights, camera, animation) by
// upAxisToY, so that `axis` points up, and sets upAxis to +y.
void rotateUpToY(Scene& scene, UpAxis axis);

// A scene with an environment gets no headlight: the environment lights it.
std::vector<Light> lightsOrHeadlight(const Scene& scene, glm::vec3 eye, bool backgroundLights = false);

// Whether the scene has a light of its own (CONTRACT.md): a point light, an emitting triangle, an
// environment, or a background the file set.
bool hasOwnLight(const Scene& scene);
// Gives a scene without a light of its own the default light (defaultEnvironment); true if it did.
// A scene without triangles gets none (nothing to light: its background shows, as before).
bool addDefaultLight(Scene& scene);

}  // namespace gpurt
