// Textured scenes through the gpurt program: where a texture lands (a flipped or mirrored texture
// fails), glTF files another tool made from textured OBJs render as the OBJ, both backends filter
// alike, a texture that cannot be read is a warning that keeps the material's colour, and packed
// scenes carry their textures.
#include <png.h>

#include <cmath>
#include <sstream>

#include "../common/ImageFiles.h"
#include "CliRunner.h"

namespace gpurt::test {
namespace {

const std::string kAssets = "tests/assets/textures/";

// A PFM as the contract writes it (float32 little endian, rows bottom first), top row first.
struct Pfm {
    int width = 0, height = 0, channels = 0;
    std::vector<float> topFirst;
    const float* at(int x, int y) const { return &topFirst[(size_t(y) * size_t(width) + size_t(x)) * size_t(channels)]; }
};
Pfm readPfm(const fs::path& p) {
    const std::string bytes = readFile(p);
    std::istringstream in(bytes);
    Pfm pfm;
    std::string kind, scale;
    in >> kind >> pfm.width >> pfm.height >> scale;
    in.get();
    pfm.channels = kind == "PF" ? 3 : 1;
    const size_t row = size_t(pfm.width) * size_t(pfm.channels);
    std::vector<float> bottomFirst(row * size_t(pfm.height));
    in.read(reinterpret_cast<char*>(bottomFirst.data()), std::streamsize(bottomFirst.size() * 4));
    EXPECT_TRUE(in) << p;
    pfm.topFirst.resize(bottomFirst.size());
    for (int y = 0; y < pfm.height; ++y)
        std::copy_n(&bottomFirst[size_t(pfm.height - 1 - y) * row], row, &pfm.topFirst[size_t(y) * row]);
    return pfm;
}

// An image file's texels as libpng reads them (RGB, top row first).
std::vector<unsigned char> pngTexels(const std::string& file, int& width, int& height) {
    const std::string bytes = readFile(file);
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    EXPECT_TRUE(png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) << file;
    image.format = PNG_FORMAT_RGB;
    std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(image));
    EXPECT_TRUE(png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr)) << file;
    width = int(image.width);
    height = int(image.height);
    return pixels;
}

// IEC 61966-2-1, in double: the linear value of an sRGB code.
double srgbToLinear(unsigned char code) {
    const double c = code / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

class Textures : public GpurtTest {
  protected:
    // Renders `scene` with the color and prim AOVs as `stem`.pfm, `stem`_prim.pfm; `options` are added.
    void render(const std::string& scene, const std::string& stem, const std::string& options) const {
        const GpurtRun r = gpurt("render " + scene + " " + options + " -o " + quoted(stem + ".png") + " --aov color=" +
                                 quoted(stem + ".pfm") + " --aov prim=" + quoted(stem + "_prim.pfm"));
        ASSERT_EQ(r.code, 0) << scene << "\n" << r.err;
    }
};

// The unit square of quad.obj faces the camera, its texture's four quadrants red (top left),
// green, blue and white (ImageMagick made it). At the centre of each quadrant's square the colour
// over the white one's, at the mirror-image pixel (the same light: the headlight sits on the axis),
// is the texel's linear colour as libpng reads it from the file. The glTF's material (metallic 0,
// roughness 1: glTF's model) adds the same specular light s to every quadrant whatever its
// colour: there (colour - s) / (white - s) is the texel's, s a channel's darkest quadrant (each
// channel is 0 in some quadrant). A texture flipped (OBJ's v axis
// up, glTF's down) or mirrored puts another quadrant there. The same for obj2gltf's glTF of the
// quad, embedded (GLB) and with its texture beside it (.gltf).
TEST_F(Textures, QuadrantsLandWhereTheImageHasThem) {
    int w = 0, h = 0;
    const std::vector<unsigned char> texels = pngTexels(kAssets + "quadrants.png", w, h);
    ASSERT_EQ(w, 4);
    ASSERT_EQ(h, 4);
    for (const char* scene : {"quad.obj", "quad.glb", "quad_separate.gltf"})
        for (const char* backend : {"gl", "cpu"}) {
            SCOPED_TRACE(std::string(scene) + " " + backend);
            render(kAssets + scene, "quad", std::string("--size 64x64 --eye 0,0,2.5 --target 0,0,0 --backend ") + backend);
            const Pfm color = readPfm(dir / "quad.pfm");
            const Pfm prim = readPfm(dir / "quad_prim.pfm");
            // Pixel 16 (centre 16.5) sees x = -0.5 of the square, pixel 47 x = +0.5.
            const int near = 16, far = 47;
            const float* white = color.at(far, far);
            for (int qy = 0; qy < 2; ++qy)
                for (int qx = 0; qx < 2; ++qx) {
                    const int px = qx ? far : near, py = qy ? far : near;
                    ASSERT_GE(*prim.at(px, py), 0.0f) << px << "," << py;
                    const unsigned char* texel = &texels[(size_t(2 * qy) * 4 + size_t(2 * qx)) * 3];
                    for (int c = 0; c < 3; ++c) {
                        float s = white[c];
                        for (int k = 0; k < 4; ++k) s = std::min(s, color.at(k & 1 ? far : near, k & 2 ? far : near)[c]);
                        if (std::string(scene) == "quad.obj") {
                            EXPECT_EQ(s, 0.0f) << "Lambert: black is black";
                        }
                        EXPECT_NEAR((color.at(px, py)[c] - s) / (white[c] - s), srgbToLinear(texel[c]), 1e-4)
                            << "quadrant " << qx << "," << qy << " channel " << c;
                    }
                }
        }
}

// glTF files obj2gltf made from the textured OBJs (the globe's JPEG and the quad's PNG embedded, or
// beside the file) hit the same triangles (the globe: the same ids) and give the same colours as
// the OBJ given the glTF's material through MTL's PBR extension (obj2gltf wrote metallic 0,
// roughness 1: the OBJ's MTL copied with `Pr 1`, `Pm 0` added), on both backends.
TEST_F(Textures, GltfFromObj2gltfRendersAsItsObj) {
    const std::pair<const char*, const char*> models[] = {
        {"globe.glb", "globe.obj"}, {"quad.glb", "quad.obj"}, {"quad_separate.gltf", "quad.obj"}};
    for (const auto& [gltf, obj] : models)
        for (const char* backend : {"gl", "cpu"}) {
            SCOPED_TRACE(std::string(gltf) + " " + backend);
            const std::string options = std::string("--size 80x60 --eye 0.6,0.7,2.6 --target 0,0,0 --backend ") + backend;
            render(kAssets + gltf, "gltf", options);
            // The OBJ beside an MTL of the same material plus Pr 1, Pm 0, its map_Kd the asset's.
            const std::string stem = fs::path(obj).stem().string();
            std::string mtl = readFile(fs::path(kAssets) / (stem + ".mtl"));
            const size_t map = mtl.find("map_Kd ");
            ASSERT_NE(map, std::string::npos);
            mtl.insert(map + 7, fs::absolute(fs::path(kAssets)).string() + "/");
            mtl += "Pr 1\nPm 0\n";
            write(stem + ".mtl", mtl);
            write(obj, readFile(fs::path(kAssets) / obj));
            render(path(obj), "obj", options);
            // obj2gltf splits the quad along its other diagonal: there the ids differ, not what is hit.
            const Pfm primA = readPfm(dir / "gltf_prim.pfm"), primB = readPfm(dir / "obj_prim.pfm");
            ASSERT_EQ(primA.topFirst.size(), primB.topFirst.size());
            for (size_t k = 0; k < primA.topFirst.size(); ++k)
                ASSERT_EQ(std::string(obj) == "quad.obj" ? float(primA.topFirst[k] >= 0.0f) : primA.topFirst[k],
                          std::string(obj) == "quad.obj" ? float(primB.topFirst[k] >= 0.0f) : primB.topFirst[k])
                    << "pixel " << k;
            const Pfm a = readPfm(dir / "gltf.pfm"), b = readPfm(dir / "obj.pfm");
            ASSERT_EQ(a.topFirst.size(), b.topFirst.size());
            size_t textured = 0;
            for (size_t k = 0; k < a.topFirst.size(); ++k) {
                // obj2gltf stores 1 - v in float: a texel boundary may move by a rounding.
                EXPECT_NEAR(a.topFirst[k], b.topFirst[k], 2e-3f + 2e-3f * b.topFirst[k]) << k;
                textured += std::abs(b.topFirst[k] - b.topFirst[k % 3]) > 0.05f;
            }
            EXPECT_GT(textured, a.topFirst.size() / 4) << "the image is not all one colour";
        }
}

// A quad whose texture coordinates run from -1.3 to 2.7 (each wrap mode of glTF's samplers), seen
// at an angle: both backends sample the same texels with the same weights (the filtering is one
// shared source), so the colours agree to float rounding everywhere.
TEST_F(Textures, BothBackendsFilterAndWrapAlike) {
    const std::string png = fs::absolute(kAssets + "checker.png").string();
    for (const char* wrap : {"10497", "33071", "33648"}) {
        SCOPED_TRACE(wrap);
        // Four corners, their (u, v), two triangles: written out as glTF JSON with a data-free
        // buffer in base64 would be long; an OBJ with a JSON-free MTL cannot say clamp, so a
        // glTF file with its buffer beside it.
        const float data[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0,  // positions
                              -1.3f, 2.7f, 2.7f, 2.7f, 2.7f, -1.3f, -1.3f, -1.3f};  // texcoords
        const uint16_t indices[] = {0, 1, 2, 0, 2, 3};
        std::string bin(reinterpret_cast<const char*>(data), sizeof data);
        bin += std::string(reinterpret_cast<const char*>(indices), sizeof indices);
        write("quad.bin", bin);
        fs::copy_file(png, dir / "checker.png", fs::copy_options::overwrite_existing);
        write("wrap.gltf", std::string(R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
  "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}}],
  "textures": [{"source": 0, "sampler": 0}], "images": [{"uri": "checker.png"}],
  "samplers": [{"wrapS": )") + wrap + R"(, "wrapT": )" + wrap + R"(}],
  "buffers": [{"uri": "quad.bin", "byteLength": 92}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                  {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
                {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]})");
        const std::string options = "--size 96x72 --eye 0.8,-0.5,2.2 --target 0,0,0 --spp 2";
        render(quoted("wrap.gltf"), "gl", options + " --backend gl");
        render(quoted("wrap.gltf"), "cpu", options + " --backend cpu");
        EXPECT_TRUE(readFile(dir / "gl_prim.pfm") == readFile(dir / "cpu_prim.pfm")) << "the triangles hit differ";
        const Pfm a = readPfm(dir / "gl.pfm"), b = readPfm(dir / "cpu.pfm");
        ASSERT_EQ(a.topFirst.size(), b.topFirst.size());
        double largest = 0.0;
        for (size_t k = 0; k < a.topFirst.size(); ++k) largest = std::max(largest, double(std::abs(a.topFirst[k] - b.topFirst[k])));
        EXPECT_LT(largest, 1e-4) << "largest difference between the backends";
    }
}

// A map_Kd that names a missing file, or a file that is not an image, is a warning naming it; the
// scene renders as if the material had no texture (its Kd alone).
TEST_F(Textures, UnreadableTextureWarnsAndKeepsTheColour) {
    const std::string obj = readFile(kAssets + "quad.obj");
    write("quad.obj", obj);
    write("broken.png", "\x89PNG\r\n\x1a\n not really");
    write("plain.mtl", "newmtl quadrants\nKd 0.7 0.5 0.3\n");
    for (const std::string texture : {"missing.png", "broken.png"}) {
        SCOPED_TRACE(texture);
        write("quad.mtl", "newmtl quadrants\nKd 0.7 0.5 0.3\nmap_Kd " + texture + "\n");
        const GpurtRun r = gpurt("render " + quoted("quad.obj") + " --size 32x32 --eye 0,0,2.5 --target 0,0,0 -o " +
                                 quoted("textured.png"));
        ASSERT_EQ(r.code, 0) << r.err;
        EXPECT_NE(r.err.find("warning"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(texture), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        write("quad.obj", "mtllib plain.mtl\n" + obj.substr(obj.find('\n') + 1));
        ASSERT_EQ(gpurt("render " + quoted("quad.obj") + " --size 32x32 --eye 0,0,2.5 --target 0,0,0 -o " + quoted("plain.png")).code, 0);
        EXPECT_TRUE(readFile(dir / "textured.png") == readFile(dir / "plain.png"));
        write("quad.obj", obj);
    }
}

// `gpurt pack` keeps the textures and texture coordinates: the packed globe renders as its OBJ,
// byte for byte, and `pack` names the texture and its size.
TEST_F(Textures, PackedScenesCarryTheirTextures) {
    const GpurtRun packed = gpurt("pack " + kAssets + "globe.obj -o " + quoted("globe.gpscene") + " --dump " + quoted("dump"));
    ASSERT_EQ(packed.code, 0) << packed.err;
    EXPECT_NE(packed.out.find("checker.jpg 256x128"), std::string::npos) << packed.out;
    for (const char* dumped : {"triangleTexcoords", "textureTexels", "textureTable"})
        EXPECT_NE(packed.out.find(dumped), std::string::npos) << dumped << " not in\n" << packed.out;
    for (const char* backend : {"gl", "cpu"}) {
        SCOPED_TRACE(backend);
        const std::string options = std::string("--size 64x48 --eye 0,0.5,2.8 --target 0,0,0 --backend ") + backend;
        render(kAssets + "globe.obj", "obj", options);
        render(quoted("globe.gpscene"), "packed", options);
        EXPECT_TRUE(readFile(dir / "obj.pfm") == readFile(dir / "packed.pfm"));
        EXPECT_TRUE(readFile(dir / "obj.png") == readFile(dir / "packed.png"));
    }
}

// The Maya-era OBJ files name BMP textures: the quad with its quadrants as a BMP (and as TGA,
// run-length encoded) renders byte for byte as with the PNG, on both backends.
TEST_F(Textures, BmpAndTgaTexturesRenderAsThePng) {
    int w = 0, h = 0;
    const std::vector<unsigned char> rgb = pngTexels(kAssets + "quadrants.png", w, h);
    std::vector<unsigned char> rgba;
    for (size_t k = 0; k < rgb.size(); k += 3) rgba.insert(rgba.end(), {rgb[k], rgb[k + 1], rgb[k + 2], 255});
    write("quadrants.png", readFile(kAssets + "quadrants.png"));
    write("quadrants.bmp", bmpOf(w, h, 24, rgba));
    write("quadrants.tga", tgaOf(w, h, 24, false, true, rgba));
    const std::string obj = readFile(kAssets + "quad.obj");
    for (const char* kind : {"png", "bmp", "tga"}) {
        write(std::string(kind) + ".mtl", std::string("newmtl quadrants\nKd 1 1 1\nmap_Kd quadrants.") + kind + "\n");
        std::string text = obj;
        text.replace(text.find("quad.mtl"), 8, std::string(kind) + ".mtl");
        write(std::string(kind) + ".obj", text);
    }
    for (const char* backend : {"gl", "cpu"}) {
        SCOPED_TRACE(backend);
        const std::string options = std::string("--size 64x64 --eye 0,0,2.5 --target 0,0,0 --backend ") + backend;
        for (const char* kind : {"png", "bmp", "tga"}) render(quoted(std::string(kind) + ".obj"), kind, options);
        EXPECT_TRUE(readFile(dir / "png.pfm") == readFile(dir / "bmp.pfm"));
        EXPECT_TRUE(readFile(dir / "png.pfm") == readFile(dir / "tga.pfm"));
        EXPECT_TRUE(readFile(dir / "png.png") == readFile(dir / "bmp.png"));
    }
}

}  // namespace
}  // namespace gpurt::test
