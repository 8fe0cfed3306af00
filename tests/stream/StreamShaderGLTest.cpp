// GLSL sources: embedding, #include with #line mapping, compile errors naming file:line, loading
// from a folder (--glsl-dir), and glslangValidator on every kernel as assembled.
#include "../common/GLTest.h"

#include "stream/GPUKernel.h"
#include "stream/GPUMask.h"
#include "stream/GPUProgram.h"
#include "stream/StreamErrors.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace gpurt::test {
namespace {

namespace fs = std::filesystem;

fs::path makeTempDir(const std::string& tag) {
    fs::path dir = fs::temp_directory_path() / ("gpurt-" + tag + "-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

void writeFile(const fs::path& path, const std::string& text) {
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
}

TEST(ShaderLibraryTest, MapLogNamesFilesForMesaNvidiaAndGlslangFormats) {
    AssembledShader shader;
    shader.names = {"glsl/a.frag", "glsl/common/b.glsl"};
    EXPECT_EQ(shader.mapLog("0:12(3): error: x"), "glsl/a.frag:12(3): error: x");
    EXPECT_EQ(shader.mapLog("1(7) : error C0000: y"), "glsl/common/b.glsl:7 : error C0000: y");
    EXPECT_EQ(shader.mapLog("ERROR: 1:4: 'z' : undeclared"), "ERROR: glsl/common/b.glsl:4: 'z' : undeclared");
    EXPECT_EQ(shader.mapLog("warning 0.5 stays"), "warning 0.5 stays");
}

TEST(ShaderLibraryTest, IncludesOnceWithLineDirectives) {
    const fs::path dir = makeTempDir("include");
    writeFile(dir / "common/x.glsl", "// x\nfloat x() { return 1.0; }\n");
    writeFile(dir / "common/y.glsl", "#include \"x.glsl\"\nfloat y() { return x(); }\n");
    writeFile(dir / "k.frag", "#include \"common/x.glsl\"\n#include \"common/y.glsl\"\nvoid main() {}\n");
    ShaderLibrary library;
    library.setDirectory(dir);
    const AssembledShader s = library.assemble("k.frag", "#define V 1");
    EXPECT_EQ(s.source.rfind("#version 450 core\n", 0), 0u);
    size_t count = 0;
    for (size_t at = s.source.find("float x()"); at != std::string::npos; at = s.source.find("float x()", at + 1)) ++count;
    EXPECT_EQ(count, 1u) << s.source;
    EXPECT_NE(s.source.find("#define V 1"), std::string::npos);
    ASSERT_EQ(s.names.size(), 4u);  // preamble, k.frag, x.glsl, y.glsl
    EXPECT_EQ(s.names[1], "glsl/k.frag");
    EXPECT_EQ(s.names[2], "glsl/common/x.glsl");
    fs::remove_all(dir);
}

TEST(ShaderLibraryTest, MissingIncludeNamesTheIncludingFileAndLine) {
    const fs::path dir = makeTempDir("missing");
    writeFile(dir / "k.frag", "// kernel\n\n#include \"nowhere.glsl\"\nvoid main() {}\n");
    ShaderLibrary library;
    library.setDirectory(dir);
    try {
        library.assemble("k.frag");
        FAIL();
    } catch (const KernelBuildError& e) {
        EXPECT_NE(std::string(e.what()).find("glsl/k.frag:3"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

class ShaderCompile : public GLTest {};

TEST_F(ShaderCompile, ErrorInKernelNamesFileAndLine) {
    const fs::path dir = makeTempDir("broken");
    fs::copy(fs::path(GPURT_SOURCE_DIR) / "glsl", dir, fs::copy_options::recursive);
    writeFile(dir / "test/broken.frag",
              "// a kernel with an error on line 5\n#include \"../common/stream.glsl\"\n"
              "layout(location = 0) out float result;\nvoid main() {\n    result = undefinedThing;\n}\n");
    ShaderLibrary::global().setDirectory(dir);
    GPUKernel kernel("broken", "test/broken.frag");
    try {
        kernel.build();
        FAIL() << "the broken kernel compiled";
    } catch (const KernelBuildError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("glsl/test/broken.frag:5"), std::string::npos) << message;
        EXPECT_NE(message.find("broken"), std::string::npos) << message;
    }
    fs::remove_all(dir);
}

TEST_F(ShaderCompile, ErrorInIncludedFileNamesThatFile) {
    const fs::path dir = makeTempDir("broken-include");
    fs::copy(fs::path(GPURT_SOURCE_DIR) / "glsl", dir, fs::copy_options::recursive);
    writeFile(dir / "test/lib.glsl", "// helper\n\nfloat helper() { return nonsense(); }\n");
    writeFile(dir / "test/uses_lib.frag",
              "#include \"lib.glsl\"\nlayout(location = 0) out float result;\nvoid main() { result = helper(); }\n");
    ShaderLibrary::global().setDirectory(dir);
    try {
        GPUProgram program("usesLib", "test/uses_lib.frag");
        FAIL();
    } catch (const KernelBuildError& e) {
        EXPECT_NE(std::string(e.what()).find("glsl/test/lib.glsl:3"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

TEST_F(ShaderCompile, GlslDirLoadsKernelsFromDisk) {
    const fs::path dir = makeTempDir("glsldir");
    fs::copy(fs::path(GPURT_SOURCE_DIR) / "glsl", dir, fs::copy_options::recursive);
    // The disk copy's kernel differs from the embedded one: the result shows which ran.
    writeFile(dir / "test/affine.frag",
              "#include \"../common/stream.glsl\"\nuniform sampler2D values;\nuniform float scale;\n"
              "uniform float offset;\nlayout(location = 0) out float result;\n"
              "void main() { result = readStream(values).x * scale + offset + 100.0; }\n");
    ShaderLibrary::global().setDirectory(dir);
    GPUFloatArray in(4, 4, 1), out(4, 4, 1);
    in.fill(1.0f);
    GPUKernel kernel("affine", "test/affine.frag");
    kernel.addInput(in, "values").addOutput(out).setUniform("scale", 2.0f).setUniform("offset", 0.0f);
    kernel.execute();
    for (float v : out.download()) ASSERT_EQ(v, 102.0f);
    fs::remove_all(dir);
}

// Every kernel under glsl/ as assembled (with the tracer's define variants, and the early-exit
// masked variant) passes glslangValidator. (The files alone are include fragments without #version.)
TEST(ShaderValidation, EveryKernelPassesGlslangValidator) {
    ShaderLibrary::global().setDirectory({});  // the embedded sources
    const fs::path dir = makeTempDir("validate");
    int validated = 0;
    const ShaderLibrary& library = ShaderLibrary::global();
    for (const EmbeddedFile& file : embeddedGlslFiles()) {
        const std::string path = file.path;
        const bool fragment = path.size() > 5 && path.substr(path.size() - 5) == ".frag";
        const bool vertex = path.size() > 5 && path.substr(path.size() - 5) == ".vert";
        if (!fragment && !vertex) continue;
        // The megakernels trace inside: they need the define naming the accelerator (bindTrace).
        const bool megakernel = path.find("megakernel.frag") != std::string::npos || path == "integrators/aovs.frag";
        std::vector<AssembledShader> variants;
        if (!megakernel) variants.push_back(library.assemble(path));
        if (megakernel) {
            for (const char* defines :
                 {"#define ACCEL_GRID\n", "#define ACCEL_BVH\n#define CAMERA\n#define PIXEL_CENTRE\n#define AOVS\n",
                  "#define ACCEL_GRID\n#define CAMERA\n#define SCENE_ALPHA\n#define SCENE_CULL_BACK\n#define SCENE_TEXTURES\n"
                  "#define SCENE_EMITTERS\n#define SCENE_ENVIRONMENT\n#define ENVIRONMENT_LIGHT\n",
                  "#define ACCEL_BVH\n#define SCENE_ALPHA\n#define SCENE_TEXTURES\n#define SCENE_NORMAL_MAPS\n"
                  "#define SCENE_VERTEX_NORMALS\n#define SCENE_VERTEX_TANGENTS\n#define SCENE_VERTEX_COLORS\n"
                  "#define SCENE_TRANSMISSION\n#define SCENE_TRANSMISSION_MAPS\n#define SCENE_MODEL_1\n#define SCENE_MODEL_2\n"})
                variants.push_back(library.assemble(path, defines));
            // Masked by the early exit.
            variants.push_back(library.assemble(path, "#define ACCEL_GRID\n" + earlyExitWrapping().preamble,
                                                earlyExitWrapping().epilogue));
        }
        // The define variants the tracer builds (GpuPipeline, GridGl).
        if (path == "accel/grid/trace.frag")
            for (const char* defines : {"#define FROM_START\n#define TRACE_STEPS (1 << 30)\n", "#define ANY_HIT\n",
                                        "#define FROM_START\n#define ANY_HIT\n", "#define TRACE_STEPS 16\n",
                                        "#define FROM_START\n#define TRACE_STEPS (1 << 30)\n#define CAMERA\n"})
                variants.push_back(library.assemble(path, defines));
        if (path == "accel/grid/traverse.frag") variants.push_back(library.assemble(path, "#define TRAVERSE_STEPS 16\n"));
        // Alpha coverage in the accelerators' kernels (SceneTextures::bindCoverage defines SCENE_ALPHA).
        if (path == "accel/grid/trace.frag" || path == "accel/bvh/trace.frag")
            for (const char* defines : {"#define SCENE_ALPHA\n#define SCENE_TEXTURES\n#define FROM_START\n#define TRACE_STEPS (1 << 30)\n",
                                        "#define SCENE_ALPHA\n#define ANY_HIT\n#define TRACE_STEPS 16\n",
                                        "#define SCENE_ALPHA\n#define FROM_START\n#define TRACE_STEPS (1 << 30)\n#define CAMERA\n"})
                variants.push_back(library.assemble(path, defines));
        if (path == "accel/grid/intersect.frag") variants.push_back(library.assemble(path, "#define SCENE_ALPHA\n#define SCENE_TEXTURES\n"));
        // Back-face culling (SCENE_CULL_BACK), alone and with alpha.
        if (path == "accel/grid/trace.frag" || path == "accel/bvh/trace.frag")
            for (const char* defines : {"#define SCENE_CULL_BACK\n#define FROM_START\n#define TRACE_STEPS (1 << 30)\n",
                                        "#define SCENE_CULL_BACK\n#define ANY_HIT\n#define TRACE_STEPS 16\n",
                                        "#define SCENE_CULL_BACK\n#define FROM_START\n#define TRACE_STEPS (1 << 30)\n#define CAMERA\n",
                                        "#define SCENE_CULL_BACK\n#define SCENE_ALPHA\n#define SCENE_TEXTURES\n#define ANY_HIT\n"})
                variants.push_back(library.assemble(path, defines));
        if (path == "accel/grid/intersect.frag") {
            variants.push_back(library.assemble(path, "#define SCENE_CULL_BACK\n"));
            variants.push_back(library.assemble(path, "#define SCENE_CULL_BACK\n#define SCENE_ALPHA\n"));
        }
        if (path == "integrators/whitted/bounce.frag") variants.push_back(library.assemble(path, "#define LAST_ROUND\n"));
        if (path == "integrators/shadowgen.frag" || path == "integrators/light.frag") {
            variants.push_back(library.assemble(path, "#define EMITTER\n"));
            // The environment light's next-event estimation (SceneTextures defines SCENE_ENVIRONMENT).
            variants.push_back(library.assemble(path, "#define SCENE_ENVIRONMENT\n#define PATH\n#define ENVIRONMENT\n"));
        }
        if (path == "integrators/surface.frag")  // the environment on a miss and as Whitted's ambient term
            for (const char* defines : {"#define SCENE_ENVIRONMENT\n", "#define SCENE_ENVIRONMENT\n#define PATH\n"})
                variants.push_back(library.assemble(path, defines));
        // The scene's optional attributes (SceneTextures defines them): vertex colours and texture
        // coordinates in every kernel that fetches a material record.
        for (const char* fetching : {"integrators/surface.frag", "integrators/light.frag", "integrators/shadowgen.frag",
                                     "integrators/path/bounce.frag", "integrators/whitted/bounce.frag"})
            if (path == fetching)
                variants.push_back(library.assemble(path, "#define SCENE_VERTEX_COLORS\n#define SCENE_TEXTURES\n#define "
                                                          "SCENE_VERTEX_NORMALS\n#define PATH\n"));
        // Normal maps, in the generated tangent frame and in the vertex tangents' (glTF TANGENT).
        if (path == "integrators/surface.frag")
            for (const char* defines : {"#define SCENE_TEXTURES\n#define SCENE_NORMAL_MAPS\n#define SCENE_VERTEX_NORMALS\n",
                                        "#define SCENE_TEXTURES\n#define SCENE_NORMAL_MAPS\n#define SCENE_VERTEX_NORMALS\n"
                                        "#define SCENE_VERTEX_TANGENTS\n#define PATH\n"})
                variants.push_back(library.assemble(path, defines));
        if (fragment && path.rfind("stream/", 0) != 0 && !megakernel)  // the framework's own passes are never masked
            variants.push_back(library.assemble(path, earlyExitWrapping().preamble, earlyExitWrapping().epilogue));
        for (size_t v = 0; v < variants.size(); ++v) {
            const fs::path out = dir / (std::to_string(validated) + (fragment ? ".frag" : ".vert"));
            writeFile(out, variants[v].source);
            const std::string command = std::string(GPURT_GLSLANG_VALIDATOR) + " " + out.string() + " > " +
                                        (dir / "log.txt").string() + " 2>&1";
            const int rc = std::system(command.c_str());
            std::ifstream logFile(dir / "log.txt");
            std::string log((std::istreambuf_iterator<char>(logFile)), std::istreambuf_iterator<char>());
            EXPECT_EQ(rc, 0) << path << " (variant " << v << "):\n" << variants[v].mapLog(log);
            ++validated;
        }
    }
    EXPECT_GE(validated, 10);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace gpurt::test
