// OBJ loading: the contract's triangle numbering (file order, polygon fans), MTL materials, and
// one InputError naming file and line for each kind of bad input tinyobjloader would accept.
#include "scene/ObjLoader.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include "image/ImageIO.h"
#include "image/InputError.h"

namespace gpurt {
namespace {

namespace fs = std::filesystem;

class ObjLoaderTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("gpurt-obj-" + std::string(info->name()) + "-" + std::to_string(getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path write(const std::string& name, const std::string& text) {
        const fs::path path = dir_ / name;
        std::ofstream(path, std::ios::binary) << text;
        return path;
    }

    // Loads `text` and expects an InputError whose message starts with "FILE:LINE:".
    void expectError(const std::string& text, int line, const std::string& mentions) {
        const fs::path path = write("bad.obj", text);
        try {
            loadObj(path);
            ADD_FAILURE() << "no error for:\n" << text;
        } catch (const InputError& e) {
            const std::string what = e.what();
            const std::string prefix = path.string() + ":" + std::to_string(line) + ": ";
            EXPECT_EQ(what.rfind(prefix, 0), 0u)
                << "message: " << what << "\nexpected prefix: " << prefix;
            EXPECT_NE(what.find(mentions), std::string::npos) << "message: " << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << "message is not one line: " << what;
        }
    }

    fs::path dir_;
};

const std::string kThreeVertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

void expectTriangle(const Triangle& t, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    EXPECT_EQ(t.v0, a);
    EXPECT_EQ(t.v1, b);
    EXPECT_EQ(t.v2, c);
}

TEST_F(ObjLoaderTest, NumbersTrianglesInFileOrderWithPolygonFans) {
    // The quad's shorter diagonal is B-D, so a "shortest diagonal" split would differ from the
    // contract's fan (A,B,C), (A,C,D).
    const fs::path path = write("fan.obj",
                                "# comment\n"
                                "v 0 0 0\n"   // 1 A
                                "v 10 0 0\n"  // 2 B
                                "v 11 1 0\n"  // 3 C
                                "v 1 1 0\n"   // 4 D
                                "v 5 7 1\n"   // 5 E
                                "v 2 2 2\n"   // 6 F
                                "vt 0 0\nvn 0 0 1\n"
                                "f 1 2 3\n"
                                "f 1 2 3 4\n"
                                "g second\n"
                                "o object\n"
                                "f 1/1 2/1/1 3//1 4 5\n"
                                "f -1 -2 -3\n"
                                "\tf  2 6 4 \n");
    const Scene scene = loadObj(path);
    const glm::vec3 A(0, 0, 0), B(10, 0, 0), C(11, 1, 0), D(1, 1, 0), E(5, 7, 1), F(2, 2, 2);
    ASSERT_EQ(scene.triangles.size(), 1u + 2u + 3u + 1u + 1u);
    expectTriangle(scene.triangles[0], A, B, C);
    expectTriangle(scene.triangles[1], A, B, C);
    expectTriangle(scene.triangles[2], A, C, D);
    expectTriangle(scene.triangles[3], A, B, C);
    expectTriangle(scene.triangles[4], A, C, D);
    expectTriangle(scene.triangles[5], A, D, E);
    expectTriangle(scene.triangles[6], F, E, D);  // -1 is the last vertex so far
    expectTriangle(scene.triangles[7], B, F, D);
    ASSERT_EQ(scene.materialIds.size(), scene.triangles.size());
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].name, "default");
    for (uint32_t id : scene.materialIds) EXPECT_EQ(id, 0u);
    EXPECT_FALSE(scene.camera.has_value());
}

TEST_F(ObjLoaderTest, ReadsExactFloatCoordinates) {
    const fs::path path =
        write("exact.obj", "v 0.1 -16.070313 1e-3\nv +3 .5 -0.0E-3\nv 1. 2.5e+2 7\nf 1 2 3\n");
    const Scene scene = loadObj(path);
    ASSERT_EQ(scene.triangles.size(), 1u);
    expectTriangle(scene.triangles[0], {0.1f, -16.070313f, 1e-3f}, {3.0f, 0.5f, 0.0f},
                   {1.0f, 250.0f, 7.0f});
}

TEST_F(ObjLoaderTest, AcceptsForwardReferencesAndOtherLineEndings) {
    const Scene forward = loadObj(write("forward.obj", "f 1 2 3\n" + kThreeVertices));
    ASSERT_EQ(forward.triangles.size(), 1u);
    expectTriangle(forward.triangles[0], {0, 0, 0}, {1, 0, 0}, {0, 1, 0});

    const Scene crlf = loadObj(write("crlf.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n"));
    EXPECT_EQ(crlf.triangles.size(), 1u);
    const Scene cr = loadObj(write("cr.obj", "v 0 0 0\rv 1 0 0\rv 0 1 0\rf 3 2 1"));
    ASSERT_EQ(cr.triangles.size(), 1u);
    expectTriangle(cr.triangles[0], {0, 1, 0}, {1, 0, 0}, {0, 0, 0});
    const Scene bom = loadObj(write("bom.obj", "\xEF\xBB\xBF" + kThreeVertices + "f 1 2 3\n"));
    EXPECT_EQ(bom.triangles.size(), 1u);
}

TEST_F(ObjLoaderTest, EmptyFileHasNoTriangles) {
    const Scene scene = loadObj(write("empty.obj", ""));
    EXPECT_TRUE(scene.triangles.empty());
    EXPECT_EQ(scene.materials.size(), 1u);
    EXPECT_TRUE(scene.bounds().empty());
    EXPECT_TRUE(
        loadObj(write("comments.obj", "# nothing\n\n   \n" + kThreeVertices)).triangles.empty());
}

TEST_F(ObjLoaderTest, ReadsMtlMaterials) {
    write("scene.mtl",
          "newmtl red\nKd 1 0 0\nKs 0.5 0.25 0.125\nNs 32\nillum 2\n"
          "newmtl mirror\nKd 0.1 0.2 0.3\nKs 0.9 0.8 0.7\nNs 100\nillum 3\n");
    const fs::path path = write("scene.obj", "mtllib scene.mtl\n" + kThreeVertices +
                                                 "f 1 2 3\n"  // no usemtl yet: default
                                                 "usemtl red\nf 1 2 3\nf 3 2 1\n"
                                                 "usemtl mirror\nf 1 2 3\n"
                                                 "usemtl nosuch\nf 1 2 3\n");
    const Scene scene = loadObj(path);
    ASSERT_EQ(scene.triangles.size(), 5u);
    ASSERT_EQ(scene.materials.size(), 3u);  // red, mirror, default
    const Material& red = scene.materials[scene.materialIds[1]];
    EXPECT_EQ(red.name, "red");
    EXPECT_EQ(red.diffuse, glm::vec3(1, 0, 0));
    EXPECT_EQ(red.specular, glm::vec3(0.5f, 0.25f, 0.125f));
    EXPECT_EQ(red.shininess, 32.0f);
    EXPECT_EQ(red.reflectivity, glm::vec3(0.0f));
    EXPECT_EQ(scene.materialIds[2], scene.materialIds[1]);
    const Material& mirror = scene.materials[scene.materialIds[3]];
    EXPECT_EQ(mirror.name, "mirror");
    EXPECT_EQ(mirror.reflectivity, glm::vec3(0.9f, 0.8f, 0.7f));
    EXPECT_EQ(mirror.shininess, 100.0f);
    EXPECT_EQ(scene.materials[scene.materialIds[0]].name, "default");
    EXPECT_EQ(scene.materials[scene.materialIds[4]].name, "default");
    EXPECT_EQ(scene.materialIds[0], scene.materialIds[4]);
}

TEST_F(ObjLoaderTest, MissingMtlIsAWarning) {
    const fs::path path =
        write("nomtl.obj", "mtllib missing.mtl\n" + kThreeVertices + "usemtl red\nf 1 2 3\n");
    ::testing::internal::CaptureStderr();
    const Scene scene = loadObj(path);
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find("warning"), std::string::npos) << err;
    EXPECT_NE(err.find("missing.mtl"), std::string::npos) << err;
    ASSERT_EQ(scene.triangles.size(), 1u);
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].name, "default");
}

// The glass rule of CONTRACT.md: illum 4, 6, 7 and 9 are glass only where Ni is not 1 or d is
// below 1. Maya writes illum 4, Ni 1, Tf 1 1 1 on opaque materials: those keep Kd and Ks.
TEST_F(ObjLoaderTest, GlassIllumModelsAreGlassOnlyWhereLightBendsOrPasses) {
    write("maya.mtl",
          "newmtl maya\nillum 4\nKd 0.5 0.4 0.3\nKa 0 0 0\nTf 1 1 1\nNi 1\nKs 0.2 0.2 0.2\n"
          "newmtl glass\nillum 4\nKd 0 0 0\nNi 1.5\nTf 0.9 1 0.8\n"
          "newmtl sheet\nillum 9\nKd 0.2 0.2 0.2\nNi 1\nd 0.5\n"
          "newmtl fresnel\nillum 7\nKd 0.1 0.1 0.1\nKs 0.6 0.6 0.6\nNi 1.0\n"
          "newmtl classic\nillum 6\nKd 0 0 0\n"
          "newmtl nine\nillum 9\nNi 1.33\n");
    std::string faces = "mtllib maya.mtl\n" + kThreeVertices;
    for (const char* m : {"maya", "glass", "sheet", "fresnel", "classic", "nine"}) faces += "usemtl " + std::string(m) + "\nf 1 2 3\n";
    const Scene scene = loadObj(write("maya.obj", faces));
    ASSERT_EQ(scene.triangles.size(), 6u);
    auto material = [&](size_t t) { return scene.materials[scene.materialIds[t]]; };
    EXPECT_EQ(material(0).ior, 0.0f) << "Maya's illum 4, Ni 1, Tf 1 1 1 is opaque";
    EXPECT_EQ(material(0).diffuse, glm::vec3(0.5f, 0.4f, 0.3f));
    EXPECT_EQ(material(0).specular, glm::vec3(0.2f));
    EXPECT_EQ(material(1).ior, 1.5f);
    EXPECT_EQ(material(1).transmission, glm::vec3(0.9f, 1.0f, 0.8f));
    EXPECT_EQ(material(2).ior, 1.0f) << "d below 1 lets light through";
    EXPECT_EQ(material(3).ior, 0.0f) << "illum 7 with Ni 1: a Fresnel mirror, not glass";
    EXPECT_EQ(material(3).reflectivity, glm::vec3(0.6f));
    EXPECT_EQ(material(4).ior, 1.5f) << "no Ni: common glass, as before";
    EXPECT_EQ(material(5).ior, 1.33f);
}

// d and map_d are alpha coverage (BLEND: rays pass with probability 1 - alpha), Tr is 1 - d; glass
// (illum 4 with Ni other than 1) stays glass. map_d is a scalar texture: R of a grey mask, A of an
// image with alpha.
TEST_F(ObjLoaderTest, DissolveTrAndMapDAreAlphaCoverage) {
    writePngRgb8(dir_ / "grey.png", 2, 1, std::vector<unsigned char>{0, 0, 0, 255, 255, 255});
    // A 2 x 1 RGBA TGA (uncompressed true colour, 32 bits, top-left origin): alpha 0 and 255.
    const unsigned char tga[18 + 8] = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 1, 0, 32, 0x28,
                                       10, 20, 30, 0, 40, 50, 60, 255};
    std::ofstream(dir_ / "cut.tga", std::ios::binary).write(reinterpret_cast<const char*>(tga), sizeof(tga));
    write("alpha.mtl",
          "newmtl half\nKd 0.5 0.5 0.5\nd 0.5\n"
          "newmtl tr\nKd 0.5 0.5 0.5\nTr 0.25\n"
          "newmtl opaque\nKd 0.5 0.5 0.5\nd 1\n"
          "newmtl mask\nKd 0.5 0.5 0.5\nmap_d grey.png\n"
          "newmtl cut\nKd 0.5 0.5 0.5\nd 0.8\nmap_d cut.tga\n"
          "newmtl glass\nillum 4\nNi 1.5\nd 0.5\n");
    std::string faces = "mtllib alpha.mtl\n" + kThreeVertices + "vt 0 0\nvt 1 0\nvt 0 1\n";
    for (const char* m : {"half", "tr", "opaque", "mask", "cut", "glass"}) faces += "usemtl " + std::string(m) + "\nf 1/1 2/2 3/3\n";
    const Scene scene = loadObj(write("alpha.obj", faces));
    ASSERT_EQ(scene.triangles.size(), 6u);
    auto material = [&](size_t t) { return scene.materials[scene.materialIds[t]]; };
    EXPECT_EQ(material(0).alphaMode, 2);  // GPURT_ALPHA_BLEND
    EXPECT_EQ(material(0).alphaFactor, 0.5f);
    EXPECT_FALSE(material(0).alphaTexture.given());
    EXPECT_EQ(material(1).alphaMode, 2);
    EXPECT_EQ(material(1).alphaFactor, 0.75f);
    EXPECT_EQ(material(2).alphaMode, 0);
    EXPECT_EQ(material(3).alphaMode, 2);
    EXPECT_EQ(material(3).alphaFactor, 1.0f);
    ASSERT_TRUE(material(3).alphaTexture.given());
    EXPECT_EQ(material(3).alphaTexture.channel, 0) << "a grey mask: its R";
    EXPECT_EQ(material(4).alphaFactor, 0.8f);
    ASSERT_TRUE(material(4).alphaTexture.given());
    EXPECT_EQ(material(4).alphaTexture.channel, 3) << "an image with alpha: its A";
    EXPECT_EQ(material(5).alphaMode, 0) << "glass is not alpha";
    EXPECT_EQ(material(5).ior, 1.5f);
}

// A reflective material's Ks above 1 is kept as specular colour but clamped to 1 as reflectivity
// (a mirror cannot add light), with a warning naming the file and the material.
TEST_F(ObjLoaderTest, ReflectivityAboveOneIsClampedWithAWarning) {
    write("bright.mtl", "newmtl odd\nKd 0.5 0.5 2\nKs 1.5 0.25 1\nNs 8\nillum 3\n");
    const fs::path path = write("odd.obj", "mtllib bright.mtl\n" + kThreeVertices + "usemtl odd\nf 1 2 3\n");
    ::testing::internal::CaptureStderr();
    const Scene scene = loadObj(path);
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find("odd.obj: warning: material 'odd'"), std::string::npos) << err;
    ASSERT_GE(scene.materials.size(), 1u);
    const Material& m = scene.materials[0];
    EXPECT_EQ(m.diffuse, glm::vec3(0.5f, 0.5f, 2.0f));
    EXPECT_EQ(m.specular, glm::vec3(1.5f, 0.25f, 1.0f));
    EXPECT_EQ(m.reflectivity, glm::vec3(1.0f, 0.25f, 1.0f));
}

TEST_F(ObjLoaderTest, MissingOrUnreadableFile) {
    for (const fs::path& path : {dir_ / "does_not_exist.obj", dir_}) {
        try {
            loadObj(path);
            ADD_FAILURE() << "no error for " << path;
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()).rfind(path.string() + ": ", 0), 0u) << e.what();
        }
    }
}

TEST_F(ObjLoaderTest, BinaryGarbage) {
    std::string garbage =
        "\x7f"
        "ELF\x02\x01\x01";
    garbage += std::string(1, '\0');
    for (int k = 0; k < 200; ++k) garbage += static_cast<char>((k * 73 + 11) % 256);
    expectError(garbage, 1, "binary");
    expectError(kThreeVertices + "f 1 2 3\n" + garbage, 5, "binary");
}

TEST_F(ObjLoaderTest, BadFaceIndices) {
    expectError(kThreeVertices + "f 0 1 2\n", 4, "index 0");
    expectError(kThreeVertices + "f 1 2 4\n", 4, "out of range");
    expectError(kThreeVertices + "f 1 2 3\nf 1 2 40\n", 5, "out of range");
    expectError(kThreeVertices + "f -1 -2 -4\n", 4, "out of range");
    expectError("v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n", 3,
                "out of range");  // relative to line 3
    expectError(kThreeVertices + "f 1 2 99999999999999999999\n", 4, "out of range");
    expectError(kThreeVertices + "f 1 2 x\n", 4, "'x'");
    expectError(kThreeVertices + "f 1 2 3.5\n", 4, "'3.5'");
    expectError(kThreeVertices + "vt 0 0\nf 1/0 2/1 3/1\n", 5, "index 0");
    expectError(kThreeVertices + "vt 0 0\nf 1/2 2/1 3/1\n", 5, "texture coordinate index 2");
    expectError(kThreeVertices + "f 1// 2 3\n", 4, "'1//'");
    expectError(kThreeVertices + "f 1/1/1/1 2 3\n", 4, "'1/1/1/1'");
}

TEST_F(ObjLoaderTest, FacesWithFewerThanThreeVertices) {
    expectError(kThreeVertices + "f 1 2\n", 4, "2 vertices");
    expectError(kThreeVertices + "f\n", 4, "0 vertices");
}

TEST_F(ObjLoaderTest, BadVertices) {
    expectError("v 0 zero 0\n", 1, "'zero'");
    expectError("v 0 0\n", 1, "2 coordinates");
    expectError("v 0 0 1.5abc\n", 1, "'1.5abc'");
    expectError("v 0 1e 0\n", 1, "'1e'");
    expectError("v 0 0 0\nv nan 0 0\n", 2, "'nan' is not a finite number");
    expectError("v 0 -inf 0\n", 1, "'-inf' is not a finite number");
    expectError("v 0 0 1e39\n", 1, "'1e39'");      // overflows float
    expectError("v -1e400 0 0\n", 1, "'-1e400'");  // overflows double
    expectError("vn 0 x 1\n", 1, "'x'");
}

TEST_F(ObjLoaderTest, TrailingCommentsAreComments) {
    // Exporters write "f 1 2 3 # note"; the comment runs to the end of the line.
    const Scene scene =
        loadObj(write("c.obj", "v 0 0 0 # origin\nv 1 0 0\nv 0 1 0\nf 1 2 3 # one\nf 3 2 1#two\n"));
    ASSERT_EQ(scene.triangles.size(), 2u);
    EXPECT_EQ(scene.triangles[1].v0, glm::vec3(0, 1, 0));
}

TEST_F(ObjLoaderTest, CommentsEndAtALoneCarriageReturn) {
    // Old Mac line ends: a comment must not swallow the lines after it.
    const Scene scene =
        loadObj(write("cr.obj", "# comment\rv 0 0 0 # origin\rv 1 0 0\rv 0 1 0\rf 1 2 3 # one\r"));
    ASSERT_EQ(scene.triangles.size(), 1u);
    expectTriangle(scene.triangles[0], {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    expectError("# comment\rv 0 0\r", 2, "2 coordinates");
}

TEST_F(ObjLoaderTest, CoordinatesAreCorrectlyRoundedFloats) {
    // What strtof gives, also for spellings tinyobjloader's own parser gets wrong: a long
    // mantissa, an exponent with leading zeros, the limits of the float range.
    const std::string longMantissa = "0." + std::string(60, '0') + "123456789e61";
    const Scene scene = loadObj(write("exact.obj", "v " + longMantissa + " 1e-0000000045 -0.0\n" +
                                                       "v 3.4028234e38 1.17549435e-38 1e-46\n" +
                                                       "v 0.1 16777217 -7e-39\nf 1 2 3\n"));
    ASSERT_EQ(scene.triangles.size(), 1u);
    const Triangle& t = scene.triangles[0];
    EXPECT_EQ(t.v0, glm::vec3(std::strtof(longMantissa.c_str(), nullptr), 1e-45f, 0.0f));
    EXPECT_EQ(t.v0.x, 1.23456789f);
    EXPECT_EQ(t.v1, glm::vec3(3.4028234e38f, 1.17549435e-38f, 0.0f));
    EXPECT_EQ(t.v2, glm::vec3(0.1f, 16777216.0f, -7e-39f));
}

TEST_F(ObjLoaderTest, ExponentsBeyondTinyobjloadersIntAreRefused) {
    expectError("v 0 0 1e-2147483648\n", 1, "exponent out of range");
    expectError("v 0 0 1e+0000000002147483649\n", 1, "exponent out of range");
    // Nine digits are fine (and zero or infinity decide).
    EXPECT_EQ(loadObj(write("e9.obj", "v 1e-999999999 0 0\n")).triangles.size(), 0u);
    expectError("v 1e+999999999 0 0\n", 1, "does not fit in a 32-bit float");
}

TEST_F(ObjLoaderTest, ExtensionsTheRendererDoesNotUseAreIgnored) {
    // tinyobjloader's skin weights (vw) and tags (t) are not read, nor are lines, points and
    // smoothing groups: the triangles are those of the faces alone.
    const std::string text = kThreeVertices + "vw 1 2e30 1 3e30 0.5\n" + std::string(2000, 't') +
                             "\n" + "t crease 8192/8192/8192 1 2\n" +
                             "s 99999999999\nl 1 2\np 3\nvp 0.5 0.5\nf 1 2 3\n";
    const Scene scene = loadObj(write("ext.obj", text));
    ASSERT_EQ(scene.triangles.size(), 1u);
    expectTriangle(scene.triangles[0], {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    // Lines and points are still checked: a bad index is an error wherever it is.
    expectError(kThreeVertices + "l 1 9\n", 4, "out of range");
}

TEST_F(ObjLoaderTest, MaterialLibraryNamedManyTimesIsReadOnce) {
    write("m.mtl", "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n");
    std::string text;
    for (int k = 0; k < 500; ++k) text += "mtllib m.mtl\nmtllib nosuch.mtl\n";
    ::testing::internal::CaptureStderr();
    const Scene scene =
        loadObj(write("many.obj", text + kThreeVertices + "usemtl blue\nf 1 2 3\n"));
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(scene.materials.size(), 2u);
    EXPECT_EQ(scene.materials[scene.materialIds[0]].name, "blue");
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;  // one warning
}

TEST_F(ObjLoaderTest, DevicesAreRefusedAndUnreadableLibrariesAreWarnings) {
    try {
        loadObj("/dev/zero");
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/dev/zero: is a device"), std::string::npos)
            << e.what();
    }
    std::filesystem::create_directories(dir_ / "folder.mtl");
    for (const char* library : {"/dev/zero", "folder.mtl"}) {
        ::testing::internal::CaptureStderr();
        const Scene scene = loadObj(write(
            "lib.obj", "mtllib " + std::string(library) + "\n" + kThreeVertices + "f 1 2 3\n"));
        const std::string err = ::testing::internal::GetCapturedStderr();
        EXPECT_NE(err.find("warning"), std::string::npos) << library;
        EXPECT_EQ(scene.materials.size(), 1u);
    }
}

}  // namespace
}  // namespace gpurt
