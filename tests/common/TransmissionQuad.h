// A glTF written here for the tests of KHR_materials_transmission's transmissionTexture
// (GltfMaterials.TransmissionTextureScalesTheFactorPerHit, the packed CLI test): one quad of the
// glTF model in the plane z = 0 from (-1, -1) to (1, 1), facing +z, base colour kBase, metallic 0,
// roughness 0, KHR_materials_ior 1 (F0 = 0: Schlick's Fd = (1 - cos)^5), transmissionFactor
// `factor` times a texture's R in three bands. The texture is read through texCoord 1 and a
// KHR_texture_transform: TEXCOORD_0 is all zeros (the texel at the image's corner, R 0),
// TEXCOORD_1 is ((x + 1) / 2, (1 - y) / 2), turned by rotation pi/2 and offset (0, 1) into
// u' = (1 - y) / 2, v' = (1 - x) / 2. The image (a BMP beside the file) is kColumns x 1 texels,
// clamped: columns 8 b to 8 b + 7 have R = kBandR[b], G and B 255 - R. So the bands run across the
// quad: top (y near 1) R 0, then R 128, bottom R 255.
#pragma once

#include <string>
#include <vector>

#include "../scene/GltfDocument.h"
#include "ImageFiles.h"

namespace gpurt::test {

struct TransmissionQuad {
    static constexpr int kColumns = 24;
    static constexpr unsigned char kBandR[3] = {0, 128, 255};
    static constexpr double kBase[3] = {0.9, 0.6, 0.3};

    // The band (0, 1, 2) of the quad's point at height y, or -1 within `margin` (in u') of a band's
    // edge, where bilinear filtering blends two bands' texels.
    static int band(double y, double margin) {
        const double u = (1.0 - y) / 2.0;
        for (int b = 0; b < 3; ++b)
            if (u >= (8.0 * b + 0.5) / kColumns + margin && u <= (8.0 * b + 7.5) / kColumns - margin) return b;
        return -1;
    }

    // The texture as a 24-bit BMP.
    static std::string image() {
        std::vector<unsigned char> rgba;
        for (int x = 0; x < kColumns; ++x) {
            const unsigned char r = kBandR[x / 8];
            rgba.insert(rgba.end(), {r, static_cast<unsigned char>(255 - r), static_cast<unsigned char>(255 - r), 255});
        }
        return bmpOf(kColumns, 1, 24, rgba);
    }

    // The document; its image is `imageUri`. `lights` adds an emitting quad of radiance 2 at
    // z = -1 behind it (glTF model, base colour black) and a point light in front
    // (KHR_lights_punctual) for the command-line test; `textured` false leaves the
    // transmissionTexture out (the factor alone).
    static std::string gltf(double factor, const std::string& imageUri, bool lights = false, bool textured = true) {
        Gltf g;
        const int p = g.positions({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0});
        const int t0 = g.accessor(g.view(std::vector<float>(8, 0.0f)), 5126, 4, "VEC2");
        const int t1 = g.accessor(g.view(std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0}), 5126, 4, "VEC2");
        const int i = g.indices(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, 5123);
        const int e = g.positions({-4, -4, -1, 4, -4, -1, 4, 4, -1, -4, 4, -1});
        const std::string n = std::to_string(factor);
        const std::string texture =
            textured ? ", \"transmissionTexture\": {\"index\": 0, \"texCoord\": 1, \"extensions\": {\"KHR_texture_transform\": "
                       "{\"rotation\": 1.5707963267948966, \"offset\": [0, 1]}}}"
                     : "";
        std::string rest =
            "\"extensionsUsed\": [\"KHR_materials_ior\", \"KHR_materials_transmission\", \"KHR_texture_transform\", "
            "\"KHR_lights_punctual\", \"KHR_materials_emissive_strength\"], "
            "\"materials\": [{\"name\": \"window\", \"doubleSided\": true, \"pbrMetallicRoughness\": {\"baseColorFactor\": [" +
            std::to_string(kBase[0]) + ", " + std::to_string(kBase[1]) + ", " + std::to_string(kBase[2]) +
            ", 1], \"metallicFactor\": 0, \"roughnessFactor\": 0}, \"extensions\": {\"KHR_materials_ior\": {\"ior\": 1}, "
            "\"KHR_materials_transmission\": {\"transmissionFactor\": " + n + texture + "}}}, "
            "{\"name\": \"light\", \"doubleSided\": true, \"pbrMetallicRoughness\": {\"baseColorFactor\": [0, 0, 0, 1]}, "
            "\"emissiveFactor\": [1, 1, 1], \"extensions\": {\"KHR_materials_emissive_strength\": {\"emissiveStrength\": 2}}}], "
            "\"textures\": [{\"source\": 0, \"sampler\": 0}], \"samplers\": [{\"wrapS\": 33071, \"wrapT\": 33071}], "
            "\"images\": [{\"uri\": \"" + imageUri + "\"}], "
            "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(p) + ", \"TEXCOORD_0\": " +
            std::to_string(t0) + ", \"TEXCOORD_1\": " + std::to_string(t1) + "}, \"indices\": " + std::to_string(i) +
            ", \"material\": 0}]}, {\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(e) +
            "}, \"indices\": " + std::to_string(i) + ", \"material\": 1}]}], ";
        if (lights)
            rest += "\"extensions\": {\"KHR_lights_punctual\": {\"lights\": [{\"type\": \"point\", \"intensity\": 4}]}}, "
                    "\"scenes\": [{\"nodes\": [0, 1, 2]}], \"nodes\": [{\"mesh\": 0}, {\"mesh\": 1}, "
                    "{\"translation\": [0.5, 1, 2], \"extensions\": {\"KHR_lights_punctual\": {\"light\": 0}}}]";
        else
            rest += "\"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0}]";
        return g.json(rest);
    }
};

}  // namespace gpurt::test
