// Packed sections of the materials: the classic values and names (MATS), the textures (TEXS), the
// models (MODL), the glTF fields and maps (PBRM), alpha (ALPH), sides (SIDE), glow (GLOW),
// transmission maps (TRNS), the layers of glTF's extensions (LAYR), the volumes (VOLM), the
// thin films (IRID), the anisotropy (ANIS), the thin walls (THIN) and the dispersion (DISP).
#include "raytrace/scene/packed/Sections.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "image/EnvironmentImage.h"
#include "raytrace/common/RayMath.h"
#include "raytrace/textures/SceneTextureLayout.h"
#include "scene/MaterialModels.h"

namespace gpurt::packed {

namespace {

constexpr size_t kTextureMinBytes = 5 * 4;  // width, height, wrapS, wrapT, the name's length
constexpr uint64_t kMaxTextures = 1 << 16;
constexpr size_t kModelBytes = 4;
// PBRM per material: metallic, roughness, normal scale, occlusion strength (f32), then the
// roughness, metallic and occlusion channels (texture, channel) and the normal and emissive
// textures (i32, -1: none).
constexpr size_t kPbrBytes = 4 * 4 + 8 * 4;
// ALPH per material: alpha mode (u32), factor, cutoff (f32), the alpha channel (texture, channel).
constexpr size_t kAlphaBytes = 5 * 4;
// SIDE, GLOW and THIN per material: u32 1 or 0 (double-sided or single-sided, back faces culled;
// the emission a light or only a glow; a thin wall, KHR_materials_transmission without a volume,
// or a solid).
constexpr size_t kFlagBytes = 4;
// TRNS per material: the transmission map's channel (texture, channel; -1: none).
constexpr size_t kTransmissionMapBytes = 2 * 4;
// LAYR per material: KHR_materials_specular's factor, colour (f32) and maps (the factor's channel:
// texture, channel; the colour's texture), KHR_materials_clearcoat's factor, roughness (f32), maps
// (two channels, the normal texture) and normal scale (f32), KHR_materials_sheen's colour,
// roughness (f32) and maps (the colour's texture, the roughness's channel).
constexpr size_t kLayerBytes = 4 * 4 + 3 * 4 + 2 * 4 + 5 * 4 + 4 + 4 * 4 + 3 * 4;
// VOLM per material: KHR_materials_volume's thickness, attenuation colour and distance (f32; the
// distance +inf: no absorption).
constexpr size_t kVolumeBytes = 5 * 4;
// IRID per material: KHR_materials_iridescence's factor, index, thickness minimum and maximum (f32)
// and maps (the factor's channel, the thickness's channel: texture, channel).
constexpr size_t kFilmBytes = 4 * 4 + 4 * 4;
// ANIS per material: KHR_materials_anisotropy's strength and rotation (f32) and texture (i32, -1: none).
constexpr size_t kAnisotropyBytes = 3 * 4;
// DISP per material: KHR_materials_dispersion's dispersion (f32, 20 / the Abbe number).
constexpr size_t kDispersionBytes = 4;
constexpr size_t kMaterialMinBytes = 17 * 4 + 4;  // seventeen floats and the name's length

std::string unknownModel(size_t material, int64_t model) {
    return "material " + std::to_string(material) + ": unknown material model " + std::to_string(model) +
           " (this gpurt knows " + materialModelList() + ")";
}

void readMaterials(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
    const uint64_t n =
        s.count(in, kMaterialMinBytes, false, kMaxTextureMaterials, "materials");
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
            s.fail("section " + s.tag + ": the name of material " + std::to_string(m) + " (" +
                 std::to_string(length) + " bytes) runs past the section's end");
        const unsigned char* text = in.take(padded);
        mat.name.assign(reinterpret_cast<const char*>(text), length);
    }
    if (in.remaining() != 0)
        s.fail("section " + s.tag + ": " + std::to_string(in.remaining()) +
             " bytes after the last material");
}

void writeMaterials(ByteWriter& out, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    out.u64(scene.materials.size());
    for (const Material& m : scene.materials) {
        out.vec3(m.diffuse);
        out.vec3(m.specular);
        out.f32(m.shininess);
        out.vec3(m.reflectivity);
        out.vec3(m.emission);
        out.f32(m.ior);
        out.vec3(m.transmission);
        writeName(out, m.name, "material");
    }
}

// The textures (count; then each: width, height, wrapS, wrapT, its name's length, the name
// padded to 4 bytes, width x height texels), then each material's texture (count = the
// materials', then an i32 each). Read after the materials.
void readTextures(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
    const uint64_t n = s.count(in, kTextureMinBytes, false, kMaxTextures, "textures");
    scene.textures.resize(size_t(n));
    for (uint64_t k = 0; k < n; ++k) {
        Texture& t = scene.textures[size_t(k)];
        const uint32_t width = in.u32(), height = in.u32();
        t.wrapS = in.u32();
        t.wrapT = in.u32();
        if (width < 1 || height < 1 || width > uint32_t(kMaxTextureSide) || height > uint32_t(kMaxTextureSide) ||
            uint64_t(width) * height > kMaxTextureTexels)
            s.fail("texture " + std::to_string(k) + ": size " + std::to_string(width) + "x" + std::to_string(height) +
                 " is not 1.." + std::to_string(kMaxTextureSide) + " a side, " + std::to_string(kMaxTextureTexels) + " texels");
        const uint32_t length = in.u32();
        const uint64_t padded = (uint64_t(length) + 3) / 4 * 4;
        const uint64_t texels = uint64_t(width) * height;
        if (padded > in.remaining() || texels * 4 > in.remaining() - padded)
            s.fail("section " + s.tag + ": texture " + std::to_string(k) + " (" + std::to_string(width) + "x" +
                 std::to_string(height) + ") runs past the section's end");
        const unsigned char* text = in.take(size_t(padded));
        t.name.assign(reinterpret_cast<const char*>(text), length);
        t.image.width = int(width);
        t.image.height = int(height);
        t.image.texels.resize(size_t(texels));
        for (uint32_t& texel : t.image.texels) texel = in.u32();
    }
    if (in.remaining() < 8) s.fail("section " + s.tag + ": no material textures after the textures");
    const uint64_t materials = in.u64();
    if (materials != scene.materials.size() || in.remaining() != materials * 4)
        s.fail("section " + s.tag + ": " + std::to_string(materials) + " material textures in " +
             std::to_string(in.remaining()) + " bytes for " + std::to_string(scene.materials.size()) + " materials");
    for (Material& m : scene.materials) m.diffuseTexture = int(int32_t(in.u32()));
}

void writeTextures(ByteWriter& out, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    out.u64(scene.textures.size());
    for (const Texture& t : scene.textures) {
        out.u32(uint32_t(t.image.width));
        out.u32(uint32_t(t.image.height));
        out.u32(t.wrapS);
        out.u32(t.wrapT);
        writeName(out, t.name, "texture");
        for (uint32_t texel : t.image.texels) out.u32(texel);
    }
    out.u64(scene.materials.size());
    for (const Material& m : scene.materials) out.u32(uint32_t(int32_t(m.diffuseTexture)));
}

// Each material's model (count = the materials', then a u32 each). Read after the materials.
void readModels(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
    const uint64_t n = oneEach(in, s, kModelBytes, "material models", kMaxTextureMaterials,
                               scene.materials.size(), "materials");
    for (uint64_t m = 0; m < n; ++m) {
        const uint32_t model = in.u32();
        if (!findMaterialModel(int(std::min<uint32_t>(model, INT32_MAX)))) s.fail("section " + s.tag + ": " + unknownModel(size_t(m), model));
        scene.materials[size_t(m)].model = int(model);
    }
}

void writeModels(ByteWriter& out, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    out.u64(scene.materials.size());
    for (const Material& m : scene.materials) out.u32(uint32_t(m.model));
}

// Each material's glTF fields (count = the materials', then kPbrBytes each). Read after the
// materials.
void readPbr(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
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

void writePbr(ByteWriter& out, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    out.u64(scene.materials.size());
    for (const Material& m : scene.materials) {
        out.f32(m.metallic);
        out.f32(m.roughness);
        out.f32(m.normalScale);
        out.f32(m.occlusionStrength);
        for (TextureChannel c : {m.roughnessTexture, m.metallicTexture, m.occlusionTexture}) {
            out.u32(uint32_t(int32_t(c.texture)));
            out.u32(uint32_t(int32_t(c.channel)));
        }
        out.u32(uint32_t(int32_t(m.normalTexture)));
        out.u32(uint32_t(int32_t(m.emissiveTexture)));
    }
}

// Each material's alpha coverage (count = the materials', then kAlphaBytes each). Read after
// the materials.
void readAlpha(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
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

void writeAlpha(ByteWriter& out, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    out.u64(scene.materials.size());
    for (const Material& m : scene.materials) {
        out.u32(uint32_t(m.alphaMode));
        out.f32(m.alphaFactor);
        out.f32(m.alphaCutoff);
        out.u32(uint32_t(int32_t(m.alphaTexture.texture)));
        out.u32(uint32_t(int32_t(m.alphaTexture.channel)));
    }
}

// A flag per material (SIDE, GLOW, THIN: count = the materials', then kFlagBytes each, 1 or 0,
// nothing else; `what` names the count, `flag` the value in a refusal). Read after the materials.
template <bool Material::*Flag>
void readFlags(const PackedSection& s, Scene& scene, const char* what, const char* flag) {
    ByteReader in = s.reader();
    const uint64_t n = oneEach(in, s, kFlagBytes, what, kMaxTextureMaterials, scene.materials.size(), "materials");
    for (uint64_t k = 0; k < n; ++k) {
        const uint32_t value = in.u32();
        if (value > 1)
            s.fail("section " + s.tag + ": material " + std::to_string(k) + ": " + flag + " " + std::to_string(value) +
                   " (0 or 1)");
        scene.materials[size_t(k)].*Flag = value == 1;
    }
}

template <bool Material::*Flag>
void writeFlags(ByteWriter& out, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    out.u64(scene.materials.size());
    for (const Material& m : scene.materials) out.u32(m.*Flag ? 1u : 0u);
}

// Each material's transmission map (count = the materials', then kTransmissionMapBytes each;
// its texture and channel are checked with the other maps'). Read after the materials.
void readTransmissionMaps(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
    const uint64_t n = oneEach(in, s, kTransmissionMapBytes, "materials' transmission maps", kMaxTextureMaterials,
                               scene.materials.size(), "materials");
    for (uint64_t k = 0; k < n; ++k) {
        TextureChannel& c = scene.materials[size_t(k)].transmissionTexture;
        c.texture = int(int32_t(in.u32()));
        c.channel = int(int32_t(in.u32()));
    }
}

void writeTransmissionMaps(ByteWriter& out, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    out.u64(scene.materials.size());
    for (const Material& m : scene.materials) {
        out.u32(uint32_t(int32_t(m.transmissionTexture.texture)));
        out.u32(uint32_t(int32_t(m.transmissionTexture.channel)));
    }
}

// Each material's layers of glTF's extensions (count = the materials', then kLayerBytes each).
void readLayers(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
    const uint64_t n = oneEach(in, s, kLayerBytes, "materials' layers", kMaxTextureMaterials, scene.materials.size(),
                               "materials");
    auto channel = [&in] {
        TextureChannel c;
        c.texture = int(int32_t(in.u32()));
        c.channel = int(int32_t(in.u32()));
        return c;
    };
    for (uint64_t k = 0; k < n; ++k) {
        Material& m = scene.materials[size_t(k)];
        m.specularFactor = in.f32();
        m.specularColor = in.vec3();
        m.specularTexture = channel();
        m.specularColorTexture = int(int32_t(in.u32()));
        m.clearcoat = in.f32();
        m.clearcoatRoughness = in.f32();
        m.clearcoatTexture = channel();
        m.clearcoatRoughnessTexture = channel();
        m.clearcoatNormalTexture = int(int32_t(in.u32()));
        m.clearcoatNormalScale = in.f32();
        m.sheenColor = in.vec3();
        m.sheenRoughness = in.f32();
        m.sheenColorTexture = int(int32_t(in.u32()));
        m.sheenRoughnessTexture = channel();
    }
}
void writeLayers(ByteWriter& out, const LoadedScene& loaded) {
    const Scene& scene = loaded.scene;
    out.u64(scene.materials.size());
    auto channel = [&out](TextureChannel c) {
        out.u32(uint32_t(int32_t(c.texture)));
        out.u32(uint32_t(int32_t(c.channel)));
    };
    for (const Material& m : scene.materials) {
        out.f32(m.specularFactor);
        out.vec3(m.specularColor);
        channel(m.specularTexture);
        out.u32(uint32_t(int32_t(m.specularColorTexture)));
        out.f32(m.clearcoat);
        out.f32(m.clearcoatRoughness);
        channel(m.clearcoatTexture);
        channel(m.clearcoatRoughnessTexture);
        out.u32(uint32_t(int32_t(m.clearcoatNormalTexture)));
        out.f32(m.clearcoatNormalScale);
        out.vec3(m.sheenColor);
        out.f32(m.sheenRoughness);
        out.u32(uint32_t(int32_t(m.sheenColorTexture)));
        channel(m.sheenRoughnessTexture);
    }
}

// Each material's volume (count = the materials', then kVolumeBytes each).
void readVolumes(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
    const uint64_t n = oneEach(in, s, kVolumeBytes, "materials' volumes", kMaxTextureMaterials, scene.materials.size(),
                               "materials");
    for (uint64_t k = 0; k < n; ++k) {
        Material& m = scene.materials[size_t(k)];
        m.thickness = in.f32();
        m.attenuationColor = in.vec3();
        m.attenuationDistance = in.f32();
    }
}
void writeVolumes(ByteWriter& out, const LoadedScene& loaded) {
    out.u64(loaded.scene.materials.size());
    for (const Material& m : loaded.scene.materials) {
        out.f32(m.thickness);
        out.vec3(m.attenuationColor);
        out.f32(m.attenuationDistance);
    }
}

// Each material's thin film (count = the materials', then kFilmBytes each).
void readFilms(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
    const uint64_t n = oneEach(in, s, kFilmBytes, "materials' thin films", kMaxTextureMaterials, scene.materials.size(),
                               "materials");
    for (uint64_t k = 0; k < n; ++k) {
        Material& m = scene.materials[size_t(k)];
        m.iridescenceFactor = in.f32();
        m.iridescenceIor = in.f32();
        m.iridescenceThicknessMin = in.f32();
        m.iridescenceThicknessMax = in.f32();
        for (TextureChannel* c : {&m.iridescenceTexture, &m.iridescenceThicknessTexture}) {
            c->texture = int(int32_t(in.u32()));
            c->channel = int(int32_t(in.u32()));
        }
    }
}
void writeFilms(ByteWriter& out, const LoadedScene& loaded) {
    out.u64(loaded.scene.materials.size());
    for (const Material& m : loaded.scene.materials) {
        out.f32(m.iridescenceFactor);
        out.f32(m.iridescenceIor);
        out.f32(m.iridescenceThicknessMin);
        out.f32(m.iridescenceThicknessMax);
        for (TextureChannel c : {m.iridescenceTexture, m.iridescenceThicknessTexture}) {
            out.u32(uint32_t(int32_t(c.texture)));
            out.u32(uint32_t(int32_t(c.channel)));
        }
    }
}

// Each material's anisotropy (count = the materials', then kAnisotropyBytes each).
void readAnisotropy(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
    const uint64_t n = oneEach(in, s, kAnisotropyBytes, "materials' anisotropy", kMaxTextureMaterials,
                               scene.materials.size(), "materials");
    for (uint64_t k = 0; k < n; ++k) {
        Material& m = scene.materials[size_t(k)];
        m.anisotropyStrength = in.f32();
        m.anisotropyRotation = in.f32();
        m.anisotropyTexture = int(int32_t(in.u32()));
    }
}
void writeAnisotropy(ByteWriter& out, const LoadedScene& loaded) {
    out.u64(loaded.scene.materials.size());
    for (const Material& m : loaded.scene.materials) {
        out.f32(m.anisotropyStrength);
        out.f32(m.anisotropyRotation);
        out.u32(uint32_t(int32_t(m.anisotropyTexture)));
    }
}

// Each material's dispersion (count = the materials', then kDispersionBytes each).
void readDispersion(const PackedSection& s, Scene& scene) {
    ByteReader in = s.reader();
    const uint64_t n = oneEach(in, s, kDispersionBytes, "materials' dispersion", kMaxTextureMaterials,
                               scene.materials.size(), "materials");
    for (uint64_t k = 0; k < n; ++k) scene.materials[size_t(k)].dispersion = in.f32();
}
void writeDispersion(ByteWriter& out, const LoadedScene& loaded) {
    out.u64(loaded.scene.materials.size());
    for (const Material& m : loaded.scene.materials) out.f32(m.dispersion);
}

// Whether some material has `has`.
template <class Has>
bool anyMaterial(const LoadedScene& l, Has has) {
    return std::any_of(l.scene.materials.begin(), l.scene.materials.end(), has);
}

}  // namespace

const SceneSection kMaterialSection{"MATS", [](const LoadedScene&) { return true; }, true, writeMaterials,
                                     [](const PackedSection& s, LoadedScene& l) { readMaterials(s, l.scene); }};
const SceneSection kTextureSection{"TEXS", [](const LoadedScene& l) { return !l.scene.textures.empty(); }, false,
                                    writeTextures, [](const PackedSection& s, LoadedScene& l) { readTextures(s, l.scene); }};
// Only when some material is not of the classic model: files of classic scenes stay as they were
// before the section existed.
const SceneSection kModelSection{
    "MODL", [](const LoadedScene& l) { return anyMaterial(l, [](const Material& m) { return m.model != 0; }); }, false,
    writeModels, [](const PackedSection& s, LoadedScene& l) { readModels(s, l.scene); }};
// PBRM also carries the maps a classic material may have (MTL `norm`, `map_Ke`).
const SceneSection kPbrSection{"PBRM",
                                [](const LoadedScene& l) {
                                    return anyMaterial(l, [](const Material& m) {
                                        return m.model == GPURT_MODEL_GLTF || m.normalTexture >= 0 ||
                                               m.emissiveTexture >= 0 || m.occlusionTexture.given() ||
                                               m.roughnessTexture.given() || m.metallicTexture.given();
                                    });
                                },
                                false, writePbr, [](const PackedSection& s, LoadedScene& l) { readPbr(s, l.scene); }};
// Only when some material has alpha: other files stay as they were before the section existed.
const SceneSection kAlphaSection{
    "ALPH", [](const LoadedScene& l) { return anyMaterial(l, [](const Material& m) { return m.hasAlpha(); }); }, false,
    writeAlpha, [](const PackedSection& s, LoadedScene& l) { readAlpha(s, l.scene); }};
// Only when some material is single-sided (glTF doubleSided false): likewise.
const SceneSection kSideSection{
    "SIDE", [](const LoadedScene& l) { return anyMaterial(l, [](const Material& m) { return !m.doubleSided; }); },
    false, writeFlags<&Material::doubleSided>, [](const PackedSection& s, LoadedScene& l) {
        readFlags<&Material::doubleSided>(s, l.scene, "materials' sides", "double-sided");
    }};
// Only when some material's emission only glows (glTF's): likewise.
const SceneSection kGlowSection{
    "GLOW", [](const LoadedScene& l) { return anyMaterial(l, [](const Material& m) { return !m.emissionIsLight; }); },
    false, writeFlags<&Material::emissionIsLight>, [](const PackedSection& s, LoadedScene& l) {
        readFlags<&Material::emissionIsLight>(s, l.scene, "materials' emission", "emission light");
    }};
// Only when some material has a transmission map (glTF transmissionTexture): likewise.
const SceneSection kTransmissionMapSection{
    "TRNS",
    [](const LoadedScene& l) { return anyMaterial(l, [](const Material& m) { return m.transmissionTexture.given(); }); },
    false, writeTransmissionMaps, [](const PackedSection& s, LoadedScene& l) { readTransmissionMaps(s, l.scene); }};

// Only when some material has a layer of glTF's extensions (KHR_materials_specular, _clearcoat,
// _sheen):
// likewise.
const SceneSection kLayerSection{
    "LAYR",
    [](const LoadedScene& l) {
        return anyMaterial(l, [](const Material& m) { return m.hasSpecularLayer() || m.hasClearcoat() || m.hasSheen(); });
    },
    false, writeLayers, [](const PackedSection& s, LoadedScene& l) { readLayers(s, l.scene); }};

// Only when some material's thickness is not 0 (KHR_materials_volume): likewise.
const SceneSection kVolumeSection{
    "VOLM", [](const LoadedScene& l) { return anyMaterial(l, [](const Material& m) { return m.thickness != 0.0f; }); },
    false, writeVolumes, [](const PackedSection& s, LoadedScene& l) { readVolumes(s, l.scene); }};

// Only when some material has a thin film (KHR_materials_iridescence): likewise.
const SceneSection kFilmSection{
    "IRID", [](const LoadedScene& l) { return anyMaterial(l, [](const Material& m) { return m.iridescenceFactor != 0.0f; }); },
    false, writeFilms, [](const PackedSection& s, LoadedScene& l) { readFilms(s, l.scene); }};

// Only when some material is a thin wall (KHR_materials_transmission without a volume): likewise
// (a file of an older gpurt, which had none, keeps its solids).
const SceneSection kThinSection{
    "THIN", [](const LoadedScene& l) { return anyMaterial(l, [](const Material& m) { return m.thinWalled; }); },
    false, writeFlags<&Material::thinWalled>, [](const PackedSection& s, LoadedScene& l) {
        readFlags<&Material::thinWalled>(s, l.scene, "materials' walls", "thin wall");
    }};

// Only when some material has anisotropy (KHR_materials_anisotropy): likewise.
const SceneSection kAnisotropySection{
    "ANIS", [](const LoadedScene& l) { return anyMaterial(l, [](const Material& m) { return m.anisotropyStrength != 0.0f; }); },
    false, writeAnisotropy, [](const PackedSection& s, LoadedScene& l) { readAnisotropy(s, l.scene); }};

// Only when some material disperses (KHR_materials_dispersion): likewise.
const SceneSection kDispersionSection{
    "DISP", [](const LoadedScene& l) { return anyMaterial(l, [](const Material& m) { return m.dispersion != 0.0f; }); },
    false, writeDispersion, [](const PackedSection& s, LoadedScene& l) { readDispersion(s, l.scene); }};

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
        if (!findMaterialModel(mat.model)) failAt(file, unknownModel(m, mat.model));
        if (mat.model == GPURT_MODEL_GLTF && mat.ior != 0.0f && mat.ior < 1.0f)  // as JSON and glTF: gltf.h divides by it
            failAt(file, "material " + std::to_string(m) + ": a glTF material's ior must be 0 or >= 1");
    }
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& mat = scene.materials[m];
        for (int texture : {mat.diffuseTexture, mat.roughnessTexture.texture, mat.metallicTexture.texture, mat.normalTexture,
                            mat.emissiveTexture, mat.occlusionTexture.texture, mat.alphaTexture.texture,
                            mat.transmissionTexture.texture, mat.specularTexture.texture, mat.specularColorTexture,
                            mat.clearcoatTexture.texture, mat.clearcoatRoughnessTexture.texture,
                            mat.clearcoatNormalTexture, mat.sheenColorTexture, mat.sheenRoughnessTexture.texture,
                            mat.iridescenceTexture.texture, mat.iridescenceThicknessTexture.texture,
                            mat.anisotropyTexture})
            if (texture < -1 || texture >= int(scene.textures.size()))
                failAt(file, "material " + std::to_string(m) + ": texture " + std::to_string(texture) + " out of range (" +
                                 std::to_string(scene.textures.size()) + " textures)");
        for (TextureChannel c : {mat.roughnessTexture, mat.metallicTexture, mat.occlusionTexture, mat.alphaTexture,
                                 mat.transmissionTexture, mat.specularTexture, mat.clearcoatTexture,
                                 mat.clearcoatRoughnessTexture, mat.sheenRoughnessTexture, mat.iridescenceTexture,
                                 mat.iridescenceThicknessTexture})
            if (c.channel < 0 || c.channel > 3) failAt(file, "material " + std::to_string(m) + ": texture channel " + std::to_string(c.channel));
        if (!(mat.metallic >= 0.0f && mat.metallic <= 1.0f) || !(mat.roughness >= 0.0f && mat.roughness <= 1.0f) ||
            !std::isfinite(mat.normalScale) || !(mat.occlusionStrength >= 0.0f && mat.occlusionStrength <= 1.0f))
            failAt(file, "material " + std::to_string(m) + ": metallic, roughness and occlusion strength must be in [0, 1], the normal scale finite");
        auto unit = [](float v) { return v >= 0.0f && v <= 1.0f; };
        if (!unit(mat.specularFactor) || !isFinite(mat.specularColor) || !nonNegative(mat.specularColor) ||
            !unit(mat.clearcoat) || !unit(mat.clearcoatRoughness) || !std::isfinite(mat.clearcoatNormalScale) ||
            !unit(mat.sheenColor.x) || !unit(mat.sheenColor.y) || !unit(mat.sheenColor.z) || !unit(mat.sheenRoughness))
            failAt(file, "material " + std::to_string(m) +
                             ": specular factor, clearcoat and its roughness, sheen colour and roughness must be in [0, 1], "
                             "the specular colour finite and >= 0, the clearcoat normal scale finite");
        if (!(mat.thickness >= 0.0f) || !std::isfinite(mat.thickness) || !unit(mat.attenuationColor.x) ||
            !unit(mat.attenuationColor.y) || !unit(mat.attenuationColor.z) || !(mat.attenuationDistance > 0.0f))
            failAt(file, "material " + std::to_string(m) +
                             ": the volume's thickness must be finite and >= 0, its attenuation colour in [0, 1], its "
                             "distance > 0");
        if (!unit(mat.iridescenceFactor) || !(mat.iridescenceIor >= 1.0f && mat.iridescenceIor <= 1000.0f) ||
            !(mat.iridescenceThicknessMin >= 0.0f && mat.iridescenceThicknessMin <= 1e6f) ||
            !(mat.iridescenceThicknessMax >= 0.0f && mat.iridescenceThicknessMax <= 1e6f))
            failAt(file, "material " + std::to_string(m) +
                             ": the iridescence factor must be in [0, 1], its index in [1, 1000], its thicknesses in [0, 1e6] nm");
        if (!unit(mat.anisotropyStrength) || !std::isfinite(mat.anisotropyRotation))
            failAt(file, "material " + std::to_string(m) + ": the anisotropy strength must be in [0, 1], its rotation finite");
        if (!(mat.dispersion >= 0.0f && mat.dispersion <= 1e3f))
            failAt(file, "material " + std::to_string(m) + ": the dispersion must be in [0, 1000]");
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

}  // namespace gpurt::packed
