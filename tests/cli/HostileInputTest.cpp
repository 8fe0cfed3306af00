// Damaged scene files and hostile options through the gpurt program (CONTRACT.md, exit codes):
// exit 1 (2 where the environment decides), one line on stderr naming the file with its line or
// JSON pointer, or the option, and no output file; never a crash or a hang. Also what a failed
// render leaves behind (nothing) and what repeated renders give (the same bytes).
#include "CliRunner.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../scene/GltfDocument.h"

namespace gpurt::test {
namespace {

const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
const std::string kThreeVertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

// Renders SCENE (a file of the scratch folder) with every output a render can write.
class HostileInput : public GpurtTest {
  protected:
    std::string render(const std::string& scene, const std::string& options = "") const {
        return "render " + quoted(scene) + " -o " + quoted("out.png") +
               " --aov depth=" + quoted("depth.pfm") + " --aov prim=" + quoted("prim.pfm") +
               " --size 24x16 " + options;
    }
    // Writes `text` as NAME and expects the render of it to be refused, naming NAME:LINE.
    void expectObjRefused(const std::string& name, const std::string& text, int line,
                          const std::string& what) const {
        write(name, text);
        expectRefused(render(name), {path(name) + ":" + std::to_string(line) + ": ", what});
    }
};

using ObjErrors = HostileInput;
using ObjWarnings = HostileInput;
using JsonErrors = HostileInput;
using CliErrors = HostileInput;
using OutputFiles = HostileInput;

TEST_F(ObjErrors, BinaryGarbage) {
    std::string elf =
        "\x7f"
        "ELF\x02\x01\x01";
    elf += std::string(1, '\0');
    for (int k = 0; k < 300; ++k) elf += static_cast<char>((k * 73 + 11) % 256);
    expectObjRefused("elf.obj", elf, 1, "binary data");
    expectObjRefused("late.obj", kTriangle + "# fine so far\n" + elf, 6, "binary data");
}

TEST_F(ObjErrors, FaceIndexZero) {
    expectObjRefused("zero.obj", kThreeVertices + "f 0 1 2\n", 4, "index 0");
    expectObjRefused("zero-vt.obj", kThreeVertices + "vt 0 0\nf 1/0 2/1 3/1\n", 5, "index 0");
}

TEST_F(ObjErrors, FaceIndexBeyondVertexCount) {
    expectObjRefused("range.obj", kThreeVertices + "f 1 2 4\n", 4, "out of range");
    // A forward reference is fine until the end of the file shows it is not.
    expectObjRefused("forward.obj", "f 1 2 4\n" + kThreeVertices, 1, "out of range");
    expectObjRefused("huge.obj", kThreeVertices + "f 1 2 99999999999999999999\n", 4,
                     "out of range");
    expectObjRefused("normal.obj", kThreeVertices + "vn 0 0 1\nf 1//1 2//1 3//2\n", 5,
                     "normal index 2");
}

TEST_F(ObjErrors, NegativeFaceIndexBeyondVertexCount) {
    expectObjRefused("negative.obj", kThreeVertices + "f -1 -2 -4\n", 4, "out of range");
    // Relative to the vertices before the line, not to the whole file.
    expectObjRefused("relative.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n", 3, "out of range");
    expectObjRefused("minimum.obj", kThreeVertices + "f 1 2 -2147483649\n", 4, "out of range");
}

TEST_F(ObjErrors, FaceWithFewerThanThreeVertices) {
    expectObjRefused("two.obj", kThreeVertices + "f 1 2\n", 4, "2 vertices");
    expectObjRefused("one.obj", kThreeVertices + "f 3\n", 4, "1 vertices");
    expectObjRefused("none.obj", kThreeVertices + "f\n", 4, "0 vertices");
}

TEST_F(ObjErrors, NonNumberWhereANumberBelongs) {
    expectObjRefused("word.obj", "v 0 zero 0\n", 1, "'zero' is not a number");
    expectObjRefused("suffix.obj", "v 0 0 1.5abc\n", 1, "'1.5abc' is not a number");
    expectObjRefused("hex.obj", "v 0x10 0 0\n", 1, "'0x10' is not a number");
    expectObjRefused("comma.obj", "v 0,5 0 0\n", 1, "'0,5' is not a number");
    expectObjRefused("exponent.obj", "v 0 1e 0\n", 1, "'1e' is not a number");
    expectObjRefused("index.obj", kThreeVertices + "f 1 2 x\n", 4, "'x'");
    expectObjRefused("fraction.obj", kThreeVertices + "f 1 2 3.5\n", 4, "'3.5'");
    expectObjRefused("reference.obj", kThreeVertices + "f 1/1/1/1 2 3\n", 4, "'1/1/1/1'");
    expectObjRefused("vn.obj", "vn 0 x 1\n", 1, "'x'");
}

TEST_F(ObjErrors, VertexWithFewerThanThreeCoordinates) {
    expectObjRefused("two.obj", "v 0 0\n", 1, "2 coordinates");
    expectObjRefused("one.obj", "v 0 0 0\nv 1\n", 2, "1 coordinates");
    expectObjRefused("none.obj", "v\n", 1, "0 coordinates");
}

TEST_F(ObjErrors, NanAndInfiniteCoordinates) {
    expectObjRefused("nan.obj", kTriangle + "v nan 0 0\n", 5, "'nan' is not a finite number");
    expectObjRefused("inf.obj", "v 0 -inf 0\n", 1, "'-inf' is not a finite number");
    expectObjRefused("upper.obj", "v 0 0 INF\n", 1, "'INF' is not a finite number");
    expectObjRefused("long.obj", "v 0 0 +Infinity\n", 1, "not a finite number");
    expectObjRefused("payload.obj", "v NaN(123) 0 0\n", 1, "not a finite number");
}

TEST_F(ObjErrors, CoordinatesThatOverflowFloat) {
    expectObjRefused("float.obj", "v 0 0 1e39\n", 1, "'1e39' does not fit in a 32-bit float");
    expectObjRefused("negative.obj", "v -3.5e38 0 0\n", 1, "does not fit in a 32-bit float");
    expectObjRefused("double.obj", "v 0 1e400 0\n", 1, "does not fit in a 32-bit float");
    // The largest float is fine (see HardGeometry for what is done with it).
    expectObjRefused("exponent.obj", "v 0 0 1e-2147483648\n", 1, "exponent out of range");
}

TEST_F(ObjErrors, MissingFile) {
    expectRefused(render("missing.obj"), {path("missing.obj") + ": no such file"});
}

TEST_F(ObjErrors, FolderOrDeviceInsteadOfAFile) {
    fs::create_directories(dir / "folder.obj");
    expectRefused(render("folder.obj"), {path("folder.obj") + ": is a directory"});
    // Read to the end, /dev/zero would never end.
    expectRefused("render /dev/zero -o " + quoted("out.png"), {"/dev/zero: ", "device"});
}

TEST_F(ObjErrors, MaterialLibraryWithUnusableValues) {
    // tinyobjloader reads 1e39 as infinity; a negative colour or exponent means nothing either.
    const std::pair<const char*, const char*> cases[] = {
        {"Kd 1e39 0 0", "Kd"}, {"Kd 0.5 -0.1 0", "Kd"}, {"Ks 0 0 -1", "Ks"}, {"Ns -5", "Ns"},
        {"Ns 1e39", "Ns"}};
    for (const auto& [line, key] : cases) {
        write("bad.mtl", std::string("newmtl good\nKd 1 0 0\nnewmtl shiny\n") + line + "\n");
        write("scene.obj", "mtllib bad.mtl\nusemtl good\n" + kTriangle);
        expectRefused(render("scene.obj"),
                      {path("bad.mtl") + ": material 'shiny': ", std::string(key) + " must be"});
    }
}

TEST_F(ObjWarnings, MissingMtlIsAWarningAndTheDefaultMaterial) {
    write("plain.obj", kTriangle);
    write("nomtl.obj", "mtllib missing.mtl\nusemtl red\n" + kTriangle);
    const GpurtRun plain =
        gpurt("render " + quoted("plain.obj") + " -o " + quoted("plain.png") + " --size 24x16");
    ASSERT_EQ(plain.code, 0) << plain.err;
    const GpurtRun run = gpurt(render("nomtl.obj"));
    ASSERT_EQ(run.code, 0) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_NE(run.err.find("warning"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("missing.mtl"), std::string::npos) << run.err;
    // The default material: the same picture as the OBJ without a material library.
    EXPECT_EQ(readFile(dir / "out.png"), readFile(dir / "plain.png"));
}

// Files that are no scene of any kind: a text file without one OBJ statement, whatever its name,
// and files named .gpscene, .ply, .glb or .gltf that are not that format (truncated, foreign).
using NotScenes = HostileInput;

TEST_F(NotScenes, TextFilesAndForeignFilesAreRefusedNamingThem) {
    expectObjRefused("readme.txt", "\n# A comment\nThis is a README, not a scene.\nSecond line.\n", 3,
                     "not a scene file: no OBJ statement in it (this line starts with 'This')");
    expectObjRefused("notes.obj", "hello world\n", 1, "not a scene file");
    // Named as a binary format: that format's reader says what is wrong.
    write("cut.gpscene", "GPRTSC");
    expectRefused(render("cut.gpscene"), {path("cut.gpscene") + ": ", "truncated"});
    write("text.gpscene", kTriangle);
    expectRefused(render("text.gpscene"), {path("text.gpscene") + ": ", "not a packed gpurt scene"});
    write("mesh.ply", kTriangle);
    expectRefused(render("mesh.ply"), {path("mesh.ply") + ": ", "not a PLY file"});
    write("short.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                       "property float y\nproperty float z\nend_header\n" + std::string(35, '\0'));
    expectRefused(render("short.ply"), {path("short.ply") + ":3: ", "vertex elements of at least 12 bytes, but only 35"});
    write("model.glb", "glTF\x02\x00\x00\x00");
    expectRefused(render("model.glb"), {path("model.glb") + ": ", "glTF"});
    // An empty file, or one of comments only, is an empty OBJ (a scene of nothing), as before.
    write("empty.obj", "# nothing yet\n");
    EXPECT_EQ(gpurt(render("empty.obj")).code, 0);
}

// Statements OBJ has but gpurt does not use are read past silently; a line whose first word is no
// OBJ statement is a warning naming its line, and the rest of the file renders.
TEST_F(ObjWarnings, UnknownStatementsAreWarningsWithTheirLines) {
    write("plain.obj", kTriangle);
    ASSERT_EQ(gpurt("render " + quoted("plain.obj") + " -o " + quoted("plain.png") + " --size 24x16").code, 0);
    write("odd.obj", "s 1\nvp 0.5\n" + kTriangle + "frobnicate 3\ncstype bspline\n");
    const GpurtRun run = gpurt(render("odd.obj"));
    ASSERT_EQ(run.code, 0) << run.err;
    EXPECT_EQ(run.err, path("odd.obj") + ":7: warning: unknown statement 'frobnicate' ignored\n");
    EXPECT_EQ(readFile(dir / "out.png"), readFile(dir / "plain.png"));
    std::string many = kTriangle;
    for (int k = 0; k < 9; ++k) many += "bogus\n";
    write("many.obj", many);
    const GpurtRun flood = gpurt(render("many.obj"));
    ASSERT_EQ(flood.code, 0) << flood.err;
    EXPECT_EQ(std::count(flood.err.begin(), flood.err.end(), '\n'), 6) << flood.err;  // 5, then how many more
    EXPECT_NE(flood.err.find("4 more unknown statements ignored"), std::string::npos) << flood.err;
}

// glTF geometry that cannot be used: damaged Draco data, a skin whose joint index is out of range
// or whose inverseBindMatrices accessor does not exist. One line naming the file and the glTF path.
using GltfErrors = HostileInput;

TEST_F(GltfErrors, BrokenDracoDataAndSkinsNameTheFileAndThePath) {
    {
        Gltf g;
        const int view = g.view(std::string("DRACO") + std::string(60, '\x5a'));
        g.accessor(-1, 5123, 3, "SCALAR");
        g.accessor(-1, 5126, 3, "VEC3");
        write(
            "draco.gltf",
            g.json("\"extensionsUsed\": [\"KHR_draco_mesh_compression\"], \"extensionsRequired\": "
                   "[\"KHR_draco_mesh_compression\"], \"nodes\": [{\"mesh\": 0}], \"meshes\": "
                   "[{\"primitives\": [{"
                   "\"attributes\": {\"POSITION\": 1}, \"indices\": 0, \"extensions\": "
                   "{\"KHR_draco_mesh_compression\": "
                   "{\"bufferView\": " +
                   std::to_string(view) + ", \"attributes\": {\"POSITION\": 0}}}}]}]"));
        expectRefused(render("draco.gltf"),
                      {path("draco.gltf") + ": mesh 0 primitive 0: Draco data"});
    }
    // A triangle skinned by one joint (node 1); JOINTS_0 names joint `joint`.
    auto skinned = [&](int joint, int inverseBindMatrices) {
        Gltf g;
        g.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
        g.accessor(g.view(std::vector<uint8_t>{0, 0, 0, 0, uint8_t(joint), 0, 0, 0, 0, 0, 0, 0}),
                   5121, 3, "VEC4");
        g.accessor(g.view(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}), 5126, 3, "VEC4");
        g.accessor(g.view(std::vector<float>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}), 5126,
                   1, "MAT4");
        return g.json(
            "\"nodes\": [{\"mesh\": 0, \"skin\": 0}, {\"translation\": [0, 0, -1]}], \"skins\": "
            "[{\"joints\": [1], "
            "\"inverseBindMatrices\": " +
            std::to_string(inverseBindMatrices) +
            "}], \"meshes\": [{\"primitives\": [{"
            "\"attributes\": {\"POSITION\": 0, \"JOINTS_0\": 1, \"WEIGHTS_0\": 2}}]}]");
    };
    write("skinned.gltf", skinned(0, 3));
    const GpurtRun fine = gpurt(render("skinned.gltf"));
    EXPECT_EQ(fine.code, 0) << fine.err;
    write("joint.gltf", skinned(3, 3));
    expectRefused(
        render("joint.gltf"),
        {path("joint.gltf") +
         ": mesh 0 primitive 0: JOINTS_0 of vertex 1 names joint 3; skin 0 has 1 joints"});
    write("bind.gltf", skinned(0, 8));
    expectRefused(render("bind.gltf"),
                  {path("bind.gltf") + ": skin 0 inverseBindMatrices: accessor 8 does not exist"});
}

TEST_F(JsonErrors, SyntaxErrorsNameLineAndColumn) {
    write("comma.json", "{\n  \"meshes\": [\n    ,\n  ]\n}\n");
    expectRefused(render("comma.json"), {path("comma.json") + ":3:5: ", "syntax error"});
    write("truncated.json", "{\"meshes\": [{\"file\": \"tri.obj\"}],\n \"lights\": [{\"posi");
    expectRefused(render("truncated.json"), {path("truncated.json") + ":2:"});
    write("comment.json", "{\"meshes\": [] // none\n}");
    expectRefused(render("comment.json"), {path("comment.json") + ":1:"});
    write("trailing.json", "{\"meshes\": [],}");
    expectRefused(render("trailing.json"), {path("trailing.json") + ":1:"});
}

TEST_F(JsonErrors, WrongTypesNameTheJsonPointer) {
    write("tri.obj", kTriangle);
    write("meshes.json", R"({"meshes": {"file": "tri.obj"}})");
    expectRefused(render("meshes.json"), {path("meshes.json"), "/meshes: expected an array"});
    write("fovy.json", R"({"meshes": [], "camera": {"eye": [0, 0, 1], "target": [0, 0, 0],
                          "fovy": "wide"}})");
    expectRefused(render("fovy.json"), {path("fovy.json"), "/camera/fovy: expected a number"});
    write("size.json", R"({"meshes": [], "render": {"size": [256.5, 256]}})");
    expectRefused(render("size.json"), {path("size.json"), "/render/size/0: expected an integer"});
    write("file.json", R"({"meshes": [{"file": ["tri.obj"]}]})");
    expectRefused(render("file.json"), {path("file.json"), "/meshes/0/file: expected a string"});
}

TEST_F(JsonErrors, UnknownKeysNameTheJsonPointer) {
    write("tri.obj", kTriangle);
    write("top.json", R"({"meshes": [], "lihgts": []})");
    expectRefused(render("top.json"), {path("top.json"), "/lihgts: unknown key"});
    write("nested.json", R"({"meshes": [{"file": "tri.obj", "material": {"kd": [1, 0, 0]}}]})");
    expectRefused(render("nested.json"),
                  {path("nested.json"), "/meshes/0/material/kd: unknown key"});
}

TEST_F(JsonErrors, MissingMeshFiles) {
    write("tri.obj", kTriangle);
    write("scene.json", R"({"meshes": [{"file": "tri.obj"}, {"file": "nosuch.obj"}]})");
    expectRefused(render("scene.json"),
                  {path("scene.json"), "/meshes/1/file: no such file 'nosuch.obj'"});
    write("device.json", R"({"meshes": [{"file": "/dev/zero"}]})");
    expectRefused(render("device.json"), {path("device.json"), "/meshes/0/file: ", "device"});
}

TEST_F(JsonErrors, BadMeshFileNamesTheObjAndItsLine) {
    write("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
    write("scene.json", R"({"meshes": [{"file": "bad.obj"}]})");
    expectRefused(render("scene.json"), {path("bad.obj") + ":3: ", "2 vertices"});
}

TEST_F(JsonErrors, MissingKeysDuplicateKeysAndNumbersOutOfRange) {
    write("missing.json", R"({"lights": []})");
    expectRefused(render("missing.json"), {path("missing.json"), "/meshes: missing required key"});
    write("twice.json", R"({"meshes": [], "meshes": []})");
    expectRefused(render("twice.json"), {path("twice.json"), "/meshes: duplicate key"});
    write("float.json", R"({"meshes": [], "background": [1e39, 0, 0]})");
    expectRefused(render("float.json"), {path("float.json"), "/background/0: ", "32-bit float"});
    write("double.json", R"({"meshes": [], "background": [1e999, 0, 0]})");
    expectRefused(render("double.json"), {path("double.json") + ":1:", "1e999"});
    write("bounces.json", R"({"meshes": [], "render": {"max_bounces": 65}})");
    expectRefused(render("bounces.json"), {path("bounces.json"), "/render/max_bounces"});
}

TEST_F(JsonErrors, UnusableCamera) {
    const std::string head = R"({"meshes": [], "camera": {"eye": [0, 0, 1], "target": )";
    write("same.json", R"({"meshes": [], "camera": {"eye": [1, 2, 3], "target": [1, 2, 3]}})");
    expectRefused(render("same.json"), {path("same.json"), "/camera/target"});
    write("up.json", head + R"([0, 0, 0], "up": [0, 0, -3]}})");
    expectRefused(render("up.json"), {path("up.json"), "/camera/up"});
    write("fovy.json", head + R"([0, 0, 0], "fovy": 180}})");
    expectRefused(render("fovy.json"), {path("fovy.json"), "/camera/fovy"});
}

TEST_F(CliErrors, UnknownOrMissingSubcommandNamesTheSubcommands) {
    expectRefused("rendr scene.obj", {"unknown subcommand 'rendr'", "render", "pack", "bench", "info"});
    expectRefused("", {"subcommand is required", "render", "pack", "bench", "info"});
}

TEST_F(CliErrors, SizeZero) {
    write("tri.obj", kTriangle);
    for (const char* size : {"0x16", "16x0", "0x0"})
        expectRefused(render("tri.obj", std::string("--size ") + size), {"--size"});
}

TEST_F(CliErrors, SizeNegative) {
    write("tri.obj", kTriangle);
    for (const char* size : {"-4x16", "16x-4", "-1x-1"})
        expectRefused(render("tri.obj", std::string("--size=") + size), {"--size"});
}

TEST_F(CliErrors, SizeMalformed) {
    write("tri.obj", kTriangle);
    for (const char* size :
         {"abc", "16x", "x16", "16x16x16", "1.5x16", "16*16", "0x10x", "''", "1e3x16"})
        expectRefused(render("tri.obj", std::string("--size ") + size), {"--size"});
}

TEST_F(CliErrors, SizeBeyondWhatTheRendererCanHold) {
    write("tri.obj", kTriangle);
    for (const char* size : {"16385x16", "16x20000", "16384x16384", "99999999999x1"})
        expectRefused(render("tri.obj", std::string("--size ") + size), {"--size"});
}

TEST_F(CliErrors, SizeBeyondTheMemoryIsExit2) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "AddressSanitizer reserves more address space than the limit allows";
#endif
    // 8192x8192 is within the limits but needs about 3.7 GB on the CPU backend: under a 1.5 GB
    // address space limit the allocation fails, which is the environment's doing (exit 2).
    write("tri.obj", kTriangle);
    const std::set<std::string> before = files();
    const GpurtRun run =
        gpurt("render " + quoted("tri.obj") + " -o " + quoted("out.png") +
                  " --aov depth=" + quoted("depth.pfm") + " --size 8192x8192 --backend cpu",
              "ulimit -v 1500000 &&");
    EXPECT_EQ(run.code, 2) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_NE(run.err.find("memory"), std::string::npos) << run.err;
    EXPECT_EQ(files(), before);
}

TEST_F(CliErrors, FovyOutsideZeroTo180) {
    write("tri.obj", kTriangle);
    for (const char* fovy : {"0", "-5", "180", "180.5", "400", "1e9", "-0"})
        expectRefused(render("tri.obj", std::string("--fovy ") + fovy), {"--fovy"});
    for (const char* fovy : {"nan", "inf", "wide", "45deg", "''"})
        expectRefused(render("tri.obj", std::string("--fovy ") + fovy), {"--fovy"});
}

TEST_F(CliErrors, EyeEqualToTarget) {
    write("tri.obj", kTriangle);
    expectRefused(render("tri.obj", "--eye 1,2,3 --target 1,2,3"), {"--target", "--eye"});
    expectRefused(render("tri.obj", "--eye 0,0,0 --target -0,0,0"), {"--target"});
}

TEST_F(CliErrors, UpParallelToTheViewDirection) {
    write("tri.obj", kTriangle);
    expectRefused(render("tri.obj", "--eye 0,5,0 --target 0,0,0"), {"--up"});  // default up
    expectRefused(render("tri.obj", "--eye 0,0,5 --target 0,0,0 --up 0,0,-2"), {"--up"});
    expectRefused(render("tri.obj", "--eye 0,0,5 --target 0,0,0 --up 0,0,0"), {"--up"});
}

TEST_F(CliErrors, MalformedVectors) {
    write("tri.obj", kTriangle);
    for (const char* eye :
         {"1,2", "1,2,3,4", "a,b,c", "nan,0,0", "1,inf,0", "1e39,0,0", ",,", "''"})
        expectRefused(render("tri.obj", std::string("--target 0,0,0 --eye ") + eye), {"--eye"});
    expectRefused(render("tri.obj", "--up 0,1"), {"--up"});
}

TEST_F(CliErrors, UnknownAovNames) {
    write("tri.obj", kTriangle);
    expectRefused(render("tri.obj", "--aov colour=" + quoted("c.pfm")), {"--aov", "colour"});
    expectRefused(render("tri.obj", "--aov Depth=" + quoted("c.pfm")), {"--aov", "Depth"});
    expectRefused(render("tri.obj", "--aov normal"), {"--aov", "normal"});
    expectRefused(render("tri.obj", "--aov normal="), {"--aov"});
    expectRefused(
        render("tri.obj", "--aov normal=" + quoted("a.pfm") + " --aov normal=" + quoted("b.pfm")),
        {"--aov", "normal"});
}

TEST_F(CliErrors, UnknownBackends) {
    write("tri.obj", kTriangle);
    for (const char* backend : {"vulkan", "GL", "embree", "''"})
        expectRefused(render("tri.obj", std::string("--backend ") + backend), {"--backend"});
    expectRefused(render("tri.obj", "--gl glx"), {"--gl"});
    expectRefused(render("tri.obj", "--mask zbuffer"), {"--mask"});
    expectRefused(render("tri.obj", "--kernel both"), {"--kernel"});
}

TEST_F(CliErrors, OtherBadOptions) {
    write("tri.obj", kTriangle);
    expectRefused(render("tri.obj", "--bounces -1"), {"--bounces"});
    expectRefused(render("tri.obj", "--bounces 65"), {"--bounces"});
    expectRefused(render("tri.obj", "--lambda 0"), {"--lambda"});
    expectRefused(render("tri.obj", "--frobnicate"), {"--frobnicate"});
    expectRefused("render " + quoted("tri.obj"), {"--output"});
    expectRefused("render -o " + quoted("out.png"), {"scene"});
    expectRefused("paint " + quoted("tri.obj"), {"subcommand"});
    expectRefused(render("tri.obj", "--mask ''"), {"--mask"});
    expectRefused("render '' -o " + quoted("out.png"), {"scene"});
    expectRefused("render " + quoted("tri.obj") + " -o ''", {"--output"});
}

TEST_F(CliErrors, OutputsThatCannotBeWritten) {
    write("tri.obj", kTriangle);
    const std::string scene = "render " + quoted("tri.obj") + " --size 8x8 ";
    expectRefused(scene + "-o " + quoted("no/such/folder/out.png"),
                  {path("no/such/folder/out.png")});
    fs::create_directories(dir / "folder.png");
    expectRefused(scene + "-o " + quoted("folder.png"), {path("folder.png")});
    // The PNG would be fine, the AOV's folder is missing: nothing is written at all.
    expectRefused(scene + "-o " + quoted("out.png") + " --aov depth=" + quoted("none/d.pfm"),
                  {path("none/d.pfm")});
    // Two outputs in one file would leave only the last.
    expectRefused(scene + "-o " + quoted("out.png") + " --aov depth=" + quoted("out.png"),
                  {path("out.png"), "twice"});
}

TEST_F(OutputFiles, FailedRenderLeavesAnExistingOutputUntouched) {
    write("tri.obj", kTriangle);
    write("out.png", "an older picture");
    write("depth.pfm", "an older depth");
    expectRefused(render("tri.obj", "--fovy 0"), {"--fovy"});
    write("bad.obj", kThreeVertices + "f 1 2 4\n");
    expectRefused(render("bad.obj"), {path("bad.obj") + ":4:"});
    expectRefused(render("tri.obj", "--aov normal=" + quoted("none/n.pfm")), {"none/n.pfm"});
    EXPECT_EQ(readFile(dir / "out.png"), "an older picture");
    EXPECT_EQ(readFile(dir / "depth.pfm"), "an older depth");
}

// Repeated renders of the same input on the same driver give the same bytes, PNG and every AOV,
// on both backends (the CPU backend on several threads).
TEST_F(OutputFiles, RepeatedRendersAreBitIdentical) {
    write("scene.obj", readFile("scenes/boxes.obj"));
    write("boxes.mtl", readFile("scenes/boxes.mtl"));
    for (const char* backend : {"gl", "cpu"}) {
        SCOPED_TRACE(backend);
        std::string outputs[2];
        for (int run = 0; run < 2; ++run) {
            const std::string tag = std::string(backend) + std::to_string(run);
            std::string args = "render " + quoted("scene.obj") + " --size 40x30 --eye 3,4,9 " +
                               "--target 0,0.5,0 --backend " + backend + " -o " +
                               quoted(tag + ".png");
            for (const char* aov : {"depth", "prim", "normal", "steps"})
                args += std::string(" --aov ") + aov + "=" + quoted(tag + aov + ".pfm");
            const GpurtRun r = gpurt(args);
            ASSERT_EQ(r.code, 0) << r.err;
            outputs[run] = readFile(dir / (tag + ".png"));
            for (const char* aov : {"depth", "prim", "normal", "steps"})
                outputs[run] += readFile(dir / (tag + aov + ".pfm"));
        }
        EXPECT_GT(outputs[0].size(), 40u * 30u * 4u * 6u);
        EXPECT_TRUE(outputs[0] == outputs[1]);
    }
}

// The pictures' materials: an emission, index of refraction or filter that is negative or not
// finite is refused naming the library and material (a glass of index 0 too); an ordinary
// material may carry Ni 0, as exporters write it.
TEST_F(ObjErrors, MaterialLibraryWithUnusableLightOrGlass) {
    const std::pair<const char*, const char*> cases[] = {
        {"Ke -1 0 0", "Ke"}, {"Ke 1e39 1 1", "Ke"}, {"illum 7\nNi -1.5", "Ni"}, {"illum 4\nNi 0", "Ni"},
        {"Ni 1e39", "Ni"},   {"illum 6\nTf 1 -0.5 1", "Tf"}, {"Tf 1e39 1 1", "Tf"}};
    for (const auto& [line, key] : cases) {
        write("bad.mtl", std::string("newmtl good\nKd 1 0 0\nNi 0\nnewmtl shiny\n") + line + "\n");
        write("scene.obj", "mtllib bad.mtl\nusemtl good\n" + kTriangle);
        expectRefused(render("scene.obj"),
                      {path("bad.mtl") + ": material 'shiny': ", std::string(key) + " must be"});
    }
}

TEST_F(JsonErrors, UnusableLightAndGlassValuesNameTheJsonPointer) {
    write("tri.obj", kTriangle);
    const std::pair<const char*, const char*> cases[] = {
        {R"({"emission": [1, -1, 0]})", "/meshes/0/material/emission/1"},
        {R"({"ior": 0})", "/meshes/0/material/ior"},
        {R"({"ior": -1.5})", "/meshes/0/material/ior"},
        {R"({"ior": 1.5, "transmission": [1, 2, 1]})", "/meshes/0/material/transmission/1"},
        {R"({"transmission": [1, 1]})", "/meshes/0/material/transmission"}};
    for (const auto& [material, pointer] : cases) {
        write("glass.json", std::string(R"({"meshes": [{"file": "tri.obj", "material": )") + material + "}]}");
        expectRefused(render("glass.json"), {path("glass.json"), pointer});
    }
}

TEST_F(CliErrors, SamplesExposureToneMapSmoothingAndIntegrator) {
    write("tri.obj", kTriangle);
    for (const char* options :
         {"--spp 0", "--spp -1", "--spp 1.5", "--spp 16777217", "--spp 99999999999", "--spp ''", "--seed -1",
          "--seed 4294967296", "--exposure nan", "--exposure inf", "--exposure 65", "--exposure 1x",
          "--tonemap filmic", "--smooth -1", "--smooth 181", "--smooth nan", "--smooth on", "--integrator bdpt",
          "--integrator ''", "--integrator path --bounces 65", "--integrator path --bounces -2"}) {
        const std::string text(options);
        const size_t last = text.rfind("--");  // the option refused is the last one given
        expectRefused(render("tri.obj", options), {text.substr(last, text.find(' ', last) - last)});
    }
}

}  // namespace
}  // namespace gpurt::test
