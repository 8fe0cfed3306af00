// Files as Blender reads them (CONTRACT.md, "Commands" and "Lights"): glTF known by its content
// whatever its name says, and glTF emission that glows without switching the default light off.
#include "CliRunner.h"
#include "PngPixels.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "image/ImageIO.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace gpurt::test {
namespace {

class SceneFiles : public GpurtTest {
  protected:
    // Renders `scene` (64 x 64, its default camera) to NAME.png; returns stderr.
    std::string render(const std::string& scene, const std::string& name, const std::string& options = "") {
        const GpurtRun r = gpurt("render " + shellQuote(scene) + " -o " + quoted(name + ".png") + " --size 64x64 " + options);
        EXPECT_EQ(r.code, 0) << scene << "\n" << r.err;
        return r.err;
    }
    std::string png(const std::string& name) const { return readFile(dir / (name + ".png")); }
};

// A JSON glTF named .glb or .json, and a binary one named .gltf: the same picture as under their
// own names, with one warning naming the mismatch.
TEST_F(SceneFiles, GltfLoadsByItsContentWhateverItsName) {
    const fs::path assets = fs::absolute("tests/assets/gltf");
    fs::copy_file(assets / "teapot.bin", dir / "teapot.bin");
    fs::copy_file(assets / "teapot.gltf", dir / "json-named.glb");
    fs::copy_file(assets / "teapot.gltf", dir / "json-named.json");
    fs::copy_file(assets / "cornell_box.glb", dir / "binary-named.gltf");
    EXPECT_EQ(render((assets / "teapot.gltf").string(), "teapot").find("named"), std::string::npos);
    const std::string glb = render(path("json-named.glb"), "glb");
    EXPECT_NE(glb.find("json-named.glb: warning: named .glb but a JSON glTF"), std::string::npos) << glb;
    EXPECT_EQ(png("glb"), png("teapot"));
    const std::string json = render(path("json-named.json"), "json");
    EXPECT_NE(json.find("json-named.json: warning: a glTF file"), std::string::npos) << json;
    EXPECT_EQ(png("json"), png("teapot"));
    render((assets / "cornell_box.glb").string(), "cornell");
    const std::string gltf = render(path("binary-named.gltf"), "gltf");
    EXPECT_NE(gltf.find("binary-named.gltf: warning: named .gltf but a binary glTF"), std::string::npos) << gltf;
    EXPECT_EQ(png("gltf"), png("cornell"));
}

// EXT_meshopt_compression as gltfpack writes it (tests/assets/gltf, scripts/make-test-assets.sh):
// the vertex and index codecs decode to the same teapot (its triangles reordered for the vertex
// cache; the .gltf's positions quantized to 14 bits), without a warning; data that does not
// decode is refused naming the buffer view.
TEST_F(SceneFiles, MeshoptCompressedGltfRendersAsItsSource) {
    const fs::path assets = fs::absolute("tests/assets/gltf");
    render((assets / "teapot.gltf").string(), "teapot");
    int w = 0, h = 0;
    const std::vector<unsigned char> source = pngPixels(png("teapot"), w, h);
    for (const char* file : {"teapot_meshopt.glb", "teapot_meshopt_q.gltf"}) {
        SCOPED_TRACE(file);
        const std::string err = render((assets / file).string(), "meshopt");
        EXPECT_EQ(err.find("EXT_meshopt_compression"), std::string::npos) << err;
        int mw = 0, mh = 0;
        const std::vector<unsigned char> decoded = pngPixels(png("meshopt"), mw, mh);
        ASSERT_EQ(decoded.size(), source.size());
        size_t close = 0;
        for (size_t i = 0; i < source.size(); ++i) close += std::abs(int(decoded[i]) - int(source[i])) <= 2;
        EXPECT_GE(double(close) / double(source.size()), 0.99);  // quantization moves an edge pixel or two
    }
    // The header byte of the compressed indices (buffer view 1's data in the binary chunk) zeroed.
    std::string glb = readFile(assets / "teapot_meshopt.glb");
    uint32_t jsonLength = 0;
    std::memcpy(&jsonLength, glb.data() + 12, 4);
    const nlohmann::json gltf = nlohmann::json::parse(glb.substr(20, jsonLength));
    const size_t indices = gltf["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["byteOffset"].get<size_t>();
    ASSERT_EQ(gltf["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["mode"], "TRIANGLES");
    glb[20 + jsonLength + 8 + indices] = '\0';
    std::ofstream(dir / "damaged.glb", std::ios::binary) << glb;
    const GpurtRun r = gpurt("render " + quoted("damaged.glb") + " -o " + quoted("out.png"));
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find("damaged.glb: bufferView"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("does not decode"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

// --fstop N as CONTRACT.md defines it: the same picture as --lens-radius f / (2 N), f the focal
// length of a 36 mm sensor across the image's larger side (square images here: the scene's fovy
// of 32 degrees spans it).
TEST_F(SceneFiles, AnFStopIsItsLensRadius) {
    const std::string scene = fs::absolute("scenes/depth_of_field.json").string();
    const double f = 0.018 / std::tan(16.0 * std::numbers::pi / 180.0);
    char radius[32];
    std::snprintf(radius, sizeof radius, "%.9g", f / (2.0 * 1.4));
    render(scene, "fstop", "--spp 8 --fstop 1.4");
    render(scene, "radius", std::string("--spp 8 --lens-radius ") + radius);
    render(scene, "pinhole", "--spp 8 --lens-radius 0");
    EXPECT_EQ(png("fstop"), png("radius"));
    EXPECT_NE(png("fstop"), png("pinhole"));  // the scene's own lens_radius 0.25 replaced, not kept
}

// The DamagedHelmet's case: a model whose only light is its material's emission still gets the
// default light, so it is brighter than with --env none (where its glow is all there is), and
// the emission glows on top of the default light's picture.
TEST_F(SceneFiles, GltfEmissionKeepsTheDefaultLight) {
    const fs::path assets = fs::absolute("tests/assets/gltf");
    fs::copy_file(assets / "teapot.bin", dir / "teapot.bin");
    nlohmann::json gltf = nlohmann::json::parse(readFile(assets / "teapot.gltf"));
    ASSERT_TRUE(gltf.contains("materials") && !gltf["materials"].empty());
    for (auto& m : gltf["materials"]) m["emissiveFactor"] = {0.1, 0.05, 0.0};
    std::ofstream(dir / "glowing.gltf") << gltf.dump();
    for (const std::string integrator : {"whitted", "path"}) {
        SCOPED_TRACE(integrator);
        const std::string options = "--integrator " + integrator + " --spp 4";
        render(path("glowing.gltf"), "lit", options + " --aov prim=" + quoted("lit.pfm"));
        render(path("glowing.gltf"), "dark", options + " --env none --aov prim=" + quoted("dark.pfm"));
        render((assets / "teapot.gltf").string(), "plain", options + " --aov prim=" + quoted("plain.pfm"));
        // The mean PNG level over the pixels that show the teapot (the prim AOV; PFM rows bottom first).
        auto mean = [&](const std::string& name) {
            int w = 0, h = 0, aw = 0, ah = 0, channels = 0;
            const std::vector<unsigned char> p = pngPixels(png(name), w, h);
            const std::vector<float> prim = gpurt::readPfm(dir / (name + ".pfm"), aw, ah, channels);
            double sum = 0.0, count = 0.0;
            for (int j = 0; j < h && aw == w && ah == h; ++j)
                for (int i = 0; i < w; ++i)
                    if (prim[size_t(h - 1 - j) * size_t(w) + size_t(i)] >= 0.0f) {
                        for (int c = 0; c < 3; ++c) sum += p[(size_t(j) * size_t(w) + size_t(i)) * 3 + size_t(c)];
                        count += 3.0;
                    }
            EXPECT_GT(count, 300.0) << name << ": the teapot is not in view";
            return sum / std::max(count, 1.0);
        };
        // Were the emission a light of the scene's, the two would be the same picture.
        EXPECT_GT(mean("lit"), 1.2 * mean("dark")) << "the default light is off";
        EXPECT_GT(mean("lit"), mean("plain")) << "the emission does not glow";
    }
}

}  // namespace
}  // namespace gpurt::test
