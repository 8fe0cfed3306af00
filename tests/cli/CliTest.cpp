// The gpurt program as users and scripts run it (CONTRACT.md): exit codes, one-line errors that
// name the file or option, no output on failure, real PNG and PFM files, statistics as JSON.
#include <gtest/gtest.h>
#include <zlib.h>
#include <nlohmann/json.hpp>
#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <algorithm>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <tuple>
#include <string>
#include <vector>

#include "CliRunner.h"
#include "image/ImageIO.h"
#include "../common/TransmissionQuad.h"
#include "../../glsl/common/scene_layout.h"

namespace {

using gpurt::test::foreign;
using gpurt::test::gpurtKeepingPreloads;

namespace fs = std::filesystem;

struct Result {
    int code = -1;
    std::string out, err;
};

// Runs `gpurt ARGS` from the project root; stdout and stderr are captured separately.
Result gpurt(const std::string& args, const std::string& env = "") {
    // One folder for the process's captured streams, removed when the process ends.
    static const struct Scratch {
        fs::path dir = fs::temp_directory_path() / ("gpurt-cli-" + std::to_string(::getpid()));
        ~Scratch() {
            std::error_code ignored;
            fs::remove_all(dir, ignored);
        }
    } scratch;
    const fs::path& dir = scratch.dir;
    fs::create_directories(dir);
    const std::string command = env + " " + GPURT_BINARY + " " + args + " > " + (dir / "out").string() + " 2> " +
                                (dir / "err").string();
    const int status = std::system(command.c_str());
    Result r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    auto slurp = [](const fs::path& p) {
        std::ifstream in(p, std::ios::binary);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    r.out = slurp(dir / "out");
    r.err = slurp(dir / "err");
    return r;
}

class Cli : public ::testing::Test {
  protected:
    void SetUp() override {
        // The process id too: two runs of the suite at once (a sanitizer build beside the plain
        // one) must not share folders.
        dir = fs::temp_directory_path() / ("gpurt-cli-" + std::to_string(::getpid()) + "-" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    std::string path(const std::string& name) const { return (dir / name).string(); }
    void write(const std::string& name, const std::string& text) const { std::ofstream(dir / name) << text; }
    // Exit 1, one line on stderr containing `mention`, and no output file.
    void expectRefused(const std::string& args, const std::string& mention) const {
        const Result r = gpurt(args);
        EXPECT_EQ(r.code, 1) << args << "\n" << r.err;
        EXPECT_NE(r.err.find(mention), std::string::npos) << args << "\n" << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(fs::exists(dir / "out.png")) << args;
    }
    fs::path dir;
};

const std::string kTeapot = "../shared/models/teapot.obj";

TEST_F(Cli, InfoNamesTheRenderer) {
    const Result r = gpurt("info");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("renderer"), std::string::npos);
    EXPECT_NE(r.out.find("max_texture_size"), std::string::npos);
}

TEST_F(Cli, RenderWritesPngAndAovs) {
    const Result r = gpurt("render " + kTeapot + " -o " + path("out.png") + " --size 40x30 --aov depth=" +
                           path("d.pfm") + " --aov prim=" + path("p.pfm") + " --aov normal=" + path("n.pfm") +
                           " --aov steps=" + path("s.pfm"));
    ASSERT_EQ(r.code, 0) << r.err;
    std::ifstream png(dir / "out.png", std::ios::binary);
    std::array<char, 8> magic{};
    png.read(magic.data(), 8);
    EXPECT_EQ(std::string(magic.data(), 8), "\x89PNG\r\n\x1a\n");
    for (const auto& [name, channels] : {std::pair{"d.pfm", 1}, {"p.pfm", 1}, {"n.pfm", 3}, {"s.pfm", 1}}) {
        const std::string header = std::string(channels == 1 ? "Pf" : "PF") + "\n40 30\n-1.0\n";
        std::ifstream in(dir / name, std::ios::binary);
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        EXPECT_EQ(text.substr(0, header.size()), header) << name;
        EXPECT_EQ(text.size(), header.size() + size_t(40 * 30 * channels) * 4) << name;
    }
    // Nothing but the requested files: no temporaries left behind.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 5);
}

// Under each kernel form: the wavefront chain's first pass is raygen, the megakernel's its own.
TEST_F(Cli, StatsJsonHasTheContractFields) {
  for (const char* kernel : {"fused", "megakernel"}) {
    SCOPED_TRACE(kernel);
    const Result r = gpurt("render " + kTeapot + " -o " + path("out.png") + " --size 32x32 --stats=json --kernel " + kernel);
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    for (const char* key : {"width", "height", "triangles", "grid", "rays", "passes", "total_ms", "mrays_per_s"})
        EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j["width"], 32);
    EXPECT_EQ(j["triangles"], 992);
    EXPECT_EQ(j["rays"]["primary"], 32 * 32);
    EXPECT_EQ(j["grid"].size(), 3u);
    const char* first = std::string(kernel) == "fused" ? "raygen" : "whittedMegakernel";
    EXPECT_EQ(j["passes"][first]["calls"], 1);
    EXPECT_EQ(j["passes"][first]["fragments"], 32 * 32);
    // The phase breakdown: every phase, none negative; the passes' phases are the passes' times.
    double passes = 0.0, traced = 0.0;
    for (const auto& [name, p] : j["passes"].items()) {
        passes += p["ms"].get<double>();
        if (name.find("race") != std::string::npos) traced += p["ms"].get<double>();
    }
    const auto& ph = j["phases_ms"];
    for (const char* key : {"load", "normals", "grid", "context", "upload", "compile", "trace", "shade", "read_back", "other", "write"}) {
        ASSERT_TRUE(ph.contains(key)) << key;
        EXPECT_GE(ph[key].get<double>(), 0.0) << key;
    }
    EXPECT_NEAR(ph["trace"].get<double>() + ph["shade"].get<double>(), passes, 1e-6 * passes + 1e-9);
    EXPECT_NEAR(ph["trace"].get<double>(), traced, 1e-6 * traced + 1e-9);
    EXPECT_GT(ph["context"].get<double>(), 0.0);
    // The render's phases fit in its total.
    const double render = ph["compile"].get<double>() + ph["trace"].get<double>() + ph["shade"].get<double>() +
                          ph["read_back"].get<double>() + ph["other"].get<double>();
    EXPECT_LE(render + ph["grid"].get<double>(), j["total_ms"].get<double>() * 1.001 + 0.01);
  }
}

// The path integrator's statistics: samples, samples per second and the paths of each round,
// falling from the camera rays on.
TEST_F(Cli, PathStatsCountSamplesAndPathsPerBounce) {
    const Result r = gpurt("render scenes/cornell.json -o " + path("out.png") +
                           " --size 24x16 --spp 3 --integrator path --bounces 4 --stats=json");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["integrator"], "path");
    EXPECT_EQ(j["samples"], 24 * 16 * 3);
    EXPECT_GT(j["samples_per_s"].get<double>(), 0.0);
    const auto paths = j["paths_per_bounce"].get<std::vector<uint64_t>>();
    ASSERT_EQ(paths.size(), 5u);  // rounds 0..4
    EXPECT_EQ(paths[0], 24u * 16u * 3u);
    for (size_t b = 1; b < paths.size(); ++b) EXPECT_LE(paths[b], paths[b - 1]);
    uint64_t secondary = 0;
    for (size_t b = 1; b < paths.size(); ++b) secondary += paths[b];
    EXPECT_EQ(j["rays"]["secondary"], secondary);
}

TEST_F(Cli, BadOptionsAreRefusedWithExit1) {
    const std::string render = "render " + kTeapot + " -o " + path("out.png");
    expectRefused(render + " --size 0x10", "--size");
    expectRefused(render + " --size -4x10", "--size");
    expectRefused(render + " --size 20000x10", "--size");
    expectRefused(render + " --fovy 180", "--fovy");
    expectRefused(render + " --fovy 0", "--fovy");
    expectRefused(render + " --eye 1,2,3 --target 1,2,3", "--target");
    expectRefused(render + " --eye 0,5,0 --target 0,0,0 --up 0,1,0", "--up");
    expectRefused(render + " --aov colour=" + path("x.pfm"), "colour");
    expectRefused(render + " --backend vulkan", "--backend");
    expectRefused(render + " --eye 1,2", "--eye");
    expectRefused(render + " --lens-radius -0.1", "--lens-radius");
    expectRefused(render + " --fstop 0", "--fstop");
    expectRefused(render + " --fstop -2", "--fstop");
    expectRefused(render + " --lens-radius 0.1 --blades 2", "--blades");
    expectRefused(render + " --lens-radius 0.1 --blades 1", "--blades");
    expectRefused(render + " --lens-radius 0.1 --focus-distance 0", "--focus-distance");
    expectRefused(render + " --lens-radius 0.1 --fstop 2", "--fstop");
}

// Sampling options (CONTRACT.md "Sampling, adaptive sampling and denoising"): a threshold must be
// a number in [0, 1), needs the path integrator, and --min-spp at most --spp.
TEST_F(Cli, BadSamplingOptionsAreRefusedWithExit1) {
    const std::string render = "render " + kTeapot + " -o " + path("out.png") + " --size 8x8";
    expectRefused(render + " --integrator path --noise-threshold -0.01", "--noise-threshold");
    expectRefused(render + " --integrator path --noise-threshold nan", "--noise-threshold");
    expectRefused(render + " --integrator path --noise-threshold 2", "--noise-threshold");
    expectRefused(render + " --noise-threshold 0.01", "--noise-threshold");  // Whitted
    expectRefused(render + " --integrator path --spp 16 --noise-threshold 0.01 --min-spp 32", "--min-spp");
    expectRefused(render + " --integrator path --spp 16 --min-spp 8", "--min-spp");  // no threshold
    expectRefused(render + " --integrator path --sampler halton", "--sampler");
}

// An adaptive render's statistics: mean_spp, and the active pixels after each convergence pass,
// never rising; the spp AOV holds each pixel's count, whose mean is mean_spp.
TEST_F(Cli, AdaptiveStatsAndSppAov) {
    const Result r = gpurt("render scenes/cornell_blocks.json -o " + path("out.png") + " --size 24x20 --integrator path "
                           "--spp 64 --noise-threshold 0.05 --min-spp 16 --stats=json --aov spp=" + path("spp.pfm"));
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    ASSERT_TRUE(j.contains("adaptive")) << r.out;
    uint64_t last = 24 * 20;
    uint32_t samples = 0;
    for (const auto& round : j["adaptive"]) {
        EXPECT_GT(round["samples"].get<uint32_t>(), samples);
        EXPECT_LE(round["active"].get<uint64_t>(), last);
        samples = round["samples"];
        last = round["active"];
    }
    EXPECT_EQ(j["adaptive"][0]["samples"], 16);
    int width = 0, height = 0, channels = 0;
    const std::vector<float> spp = gpurt::readPfm(path("spp.pfm"), width, height, channels);
    ASSERT_EQ(spp.size(), size_t(24 * 20));
    double sum = 0.0;
    for (float n : spp) {
        EXPECT_GE(n, 16.0f);
        EXPECT_LE(n, 64.0f);
        sum += n;
    }
    EXPECT_NEAR(j["mean_spp"].get<double>(), sum / double(spp.size()), 1e-9);
    EXPECT_LT(j["mean_spp"].get<double>(), 64.0);
    EXPECT_EQ(j["sampler"], "sobol");
}

// render --denoise writes the denoised picture and keeps the raw mean in the color AOV; gpurt
// denoise on its AOV files gives the same picture, byte for byte (PNG), on either backend; the
// stats report the filter.
TEST_F(Cli, DenoiseOnFilesIsRenderDenoise) {
    const std::string aovs = " --aov color=" + path("c.pfm") + " --aov albedo=" + path("a.pfm") +
                             " --aov shading_normal=" + path("n.pfm") + " --aov depth=" + path("d.pfm") +
                             " --aov variance=" + path("v.pfm");
    const std::string files = path("c.pfm") + " --albedo " + path("a.pfm") + " --normal " + path("n.pfm") + " --depth " +
                              path("d.pfm") + " --variance " + path("v.pfm");
    for (const std::string backend : {"gl", "cpu"}) {
        const Result r = gpurt("render scenes/cornell_blocks.json --size 40x32 --integrator path --spp 8 --denoise "
                               "--stats=json --backend " + backend + " -o " + path("render.png") + aovs);
        ASSERT_EQ(r.code, 0) << r.err;
        const nlohmann::json j = nlohmann::json::parse(r.out);
        ASSERT_TRUE(j.contains("denoise")) << r.out;
        EXPECT_EQ(j["denoise"]["refused"], 0);
        const Result d = gpurt("denoise " + files + " -o " + path("file.png") + " --backend " + backend);
        ASSERT_EQ(d.code, 0) << d.err;
        EXPECT_EQ(gpurt::test::readFile(path("file.png")), gpurt::test::readFile(path("render.png"))) << backend;
        // The colour AOV is the raw mean: rendered to a PNG by gpurt denoise's own tone map it
        // differs from the denoised picture.
        const Result raw = gpurt("render scenes/cornell_blocks.json --size 40x32 --integrator path --spp 8 --backend " +
                                 backend + " -o " + path("raw.png"));
        ASSERT_EQ(raw.code, 0) << raw.err;
        EXPECT_NE(gpurt::test::readFile(path("raw.png")), gpurt::test::readFile(path("render.png")));
    }
    int w = 0, h = 0, channels = 0;
    const std::vector<float> albedo = gpurt::readPfm(path("a.pfm"), w, h, channels);
    EXPECT_EQ(channels, 3);
    for (float a : albedo) {
        EXPECT_GE(a, 0.0f);
        EXPECT_LE(a, 1.0f);
    }
    // EXR in and out.
    const Result exr = gpurt("render scenes/cornell_blocks.json --size 40x32 --integrator path --spp 8 -o " +
                             path("out.exr") + " --aov color=" + path("c.exr") + " --aov albedo=" + path("a.exr") +
                             " --aov shading_normal=" + path("n.exr"));
    ASSERT_EQ(exr.code, 0) << exr.err;
    const Result d = gpurt("denoise " + path("c.exr") + " --albedo " + path("a.exr") + " --normal " + path("n.exr") +
                           " -o " + path("den.exr"));
    EXPECT_EQ(d.code, 0) << d.err;
    EXPECT_TRUE(fs::exists(path("den.exr")));
}

// Bad inputs of the denoiser: exit 1 naming the file or option, nothing written.
TEST_F(Cli, BadDenoiseInputsAreRefused) {
    const Result r = gpurt("render scenes/cornell_blocks.json --size 20x16 --integrator path --spp 2 -o " + path("r.png") +
                           " --aov color=" + path("c.pfm") + " --aov albedo=" + path("a.pfm") +
                           " --aov shading_normal=" + path("n.pfm") + " --aov depth=" + path("d.pfm"));
    ASSERT_EQ(r.code, 0) << r.err;
    const Result small = gpurt("render scenes/cornell_blocks.json --size 10x8 --integrator path -o " + path("s.png") +
                               " --aov albedo=" + path("small.pfm"));
    ASSERT_EQ(small.code, 0) << small.err;
    const std::string normal = " --normal " + path("n.pfm") + " -o " + path("out.png");
    expectRefused("denoise " + path("c.pfm") + " --albedo " + path("small.pfm") + normal, "small.pfm");
    expectRefused("denoise " + path("c.pfm") + " --albedo " + path("missing.pfm") + normal, "missing.pfm");
    expectRefused("denoise " + path("c.pfm") + normal, "--albedo");
    expectRefused("denoise " + path("r.png") + " --albedo " + path("a.pfm") + normal, "r.png");
    expectRefused("denoise " + path("c.pfm") + " --albedo " + path("d.pfm") + normal, "d.pfm");  // one channel
    // A NaN in the colour.
    int w = 0, h = 0, channels = 0;
    std::vector<float> color = gpurt::readPfm(path("c.pfm"), w, h, channels);
    color[7] = std::nanf("");
    gpurt::writePfm(path("nan.pfm"), w, h, 3, color);
    expectRefused("denoise " + path("nan.pfm") + " --albedo " + path("a.pfm") + normal, "nan.pfm");
    expectRefused("render scenes/cornell_blocks.json --size 20x16 --spp 2 --denoise -o " + path("out.png"), "--denoise");
    expectRefused("render scenes/cornell_blocks.json --size 20x16 --integrator path --tile 0/2 --denoise -o " +
                      path("out.png"), "--denoise");
    expectRefused("render scenes/cornell_blocks.json --size 20x16 --aov albedo=" + path("x.pfm") + " -o " +
                      path("out.png"), "albedo");
}

TEST_F(Cli, BadSceneFilesAreRefusedWithExit1) {
    expectRefused("render " + path("missing.obj") + " -o " + path("out.png"), "missing.obj");
    write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    expectRefused("render " + path("range.obj") + " -o " + path("out.png"), "range.obj:4");
    write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
    expectRefused("render " + path("zero.obj") + " -o " + path("out.png"), "zero.obj:4");
}

TEST_F(Cli, NoGlContextIsExit2) {
    const Result r = gpurt("render " + kTeapot + " -o " + path("out.png"), "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("EGL"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

TEST_F(Cli, OsmesaAndEglGiveTheSamePrimAov) {
    const std::string common = "render " + kTeapot + " --size 48x40 --eye 20,15,40 --target 0,0,0 ";
    ASSERT_EQ(gpurt(common + "-o " + path("a.png") + " --aov prim=" + path("a.pfm")).code, 0);
    ASSERT_EQ(gpurt(common + "-o " + path("b.png") + " --gl osmesa --aov prim=" + path("b.pfm")).code, 0);
    std::ifstream a(dir / "a.pfm", std::ios::binary), b(dir / "b.pfm", std::ios::binary);
    EXPECT_TRUE(std::equal(std::istreambuf_iterator<char>(a), std::istreambuf_iterator<char>(),
                           std::istreambuf_iterator<char>(b)));
}

TEST_F(Cli, RepeatedRendersAreBitIdentical) {
    const std::string common = "render " + kTeapot + " --size 48x40 ";
    ASSERT_EQ(gpurt(common + "-o " + path("a.png") + " --aov depth=" + path("a.pfm")).code, 0);
    ASSERT_EQ(gpurt(common + "-o " + path("b.png") + " --aov depth=" + path("b.pfm")).code, 0);
    for (const auto& [x, y] : {std::pair{"a.png", "b.png"}, {"a.pfm", "b.pfm"}}) {
        std::ifstream a(dir / x, std::ios::binary), b(dir / y, std::ios::binary);
        EXPECT_TRUE(std::equal(std::istreambuf_iterator<char>(a), std::istreambuf_iterator<char>(),
                               std::istreambuf_iterator<char>(b))) << x;
    }
}

// --- gpurt pack and packed scenes ----------------------------------------------------------------

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void spit(const fs::path& p, const std::string& bytes) {
    std::ofstream(p, std::ios::binary) << bytes;
}

// Exit 1, one line on stderr containing each of `mentions`, and no `output` file.
void expectRefusedWithout(const std::string& args, const std::vector<std::string>& mentions,
                          const fs::path& output) {
    const Result r = gpurt(args);
    EXPECT_EQ(r.code, 1) << args << "\n" << r.err;
    for (const std::string& m : mentions)
        EXPECT_NE(r.err.find(m), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(output)) << args;
}

// The documented header: u32 version at 8, u32 CRC-32 of bytes 16.. at 12; the section table from
// 32: 24-byte entries (tag, reserved, u64 offset, u64 size), the count at 24.
uint32_t get32(const std::string& b, size_t at) {
    uint32_t v = 0;
    for (int k = 3; k >= 0; --k) v = v << 8 | static_cast<unsigned char>(b.at(at + size_t(k)));
    return v;
}
void put32(std::string& b, size_t at, uint32_t v) {
    for (int k = 0; k < 4; ++k) b.at(at + size_t(k)) = static_cast<char>(v >> (8 * k));
}
void reseal(std::string& b) {
    put32(b, 12,
          uint32_t(crc32(0L, reinterpret_cast<const Bytef*>(b.data()) + 16, uInt(b.size() - 16))));
}
size_t sectionOffset(const std::string& b, const std::string& tag) {
    for (uint32_t k = 0; k < get32(b, 24); ++k)
        if (b.substr(32 + 24 * size_t(k), 4) == tag) return get32(b, 32 + 24 * size_t(k) + 8);
    ADD_FAILURE() << "no section " << tag;
    return 0;
}

// A PFM as the contract writes it: header, then float32 little-endian scanlines bottom first.
struct Pfm {
    std::string kind;
    int width = 0, height = 0;
    std::vector<float> bottomFirst;
};
Pfm readPfm(const fs::path& p) {
    const std::string bytes = slurp(p);
    std::istringstream in(bytes);
    Pfm pfm;
    std::string scale;
    in >> pfm.kind >> pfm.width >> pfm.height >> scale;
    in.get();
    const size_t count = size_t(pfm.width) * size_t(pfm.height) * (pfm.kind == "PF" ? 3 : 1);
    pfm.bottomFirst.resize(count);
    in.read(reinterpret_cast<char*>(pfm.bottomFirst.data()), std::streamsize(count * 4));
    EXPECT_TRUE(in) << p;
    return pfm;
}

TEST_F(Cli, PackPrintsStatisticsAndIsTheSameForAnyThreadCount) {
    const Result one = gpurt("pack " + kTeapot + " -o " + path("one.gpscene") + " --threads 1");
    ASSERT_EQ(one.code, 0) << one.err;
    for (const char* key :
         {"triangles    992\n", "grid         ", "non-empty", "per triangle", "longest list",
          "voxelIndex", "cellTriangles", "triangles  ", "materials  ", "build time"})
        EXPECT_NE(one.out.find(key), std::string::npos) << key << " not in:\n" << one.out;
    ASSERT_EQ(gpurt("pack " + kTeapot + " -o " + path("three.gpscene") + " --threads 3").code, 0);
    ASSERT_EQ(gpurt("pack " + kTeapot + " -o " + path("all.gpscene")).code, 0);
    const std::string bytes = slurp(dir / "one.gpscene");
    EXPECT_EQ(bytes.substr(0, 8), "GPRTSCN1");
    EXPECT_EQ(bytes, slurp(dir / "three.gpscene"));
    EXPECT_EQ(bytes, slurp(dir / "all.gpscene"));
    // The statistics name the file's real size; nothing but the three files was left behind.
    EXPECT_NE(one.out.find(", " + std::to_string(bytes.size()) + " bytes"), std::string::npos)
        << one.out;
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 3);
}

// The OBJ, a JSON scene of it, and both packed: the same PNG and AOVs, byte for byte, per backend.
// PLY files written by another tool (Assimp, scripts/make-test-assets.sh: ASCII, binary little and
// big endian) render as the OBJ they were made from, on both backends: the same triangle hit at
// every pixel (the same ids: PLY faces keep the OBJ's order), and the same depths, normals and
// colours within float rounding. Not bit for bit: Assimp's OBJ parser rounds some coordinates to a
// neighbouring float (668 of the teapot's 2976 corners differ from strtof's by one ulp).
TEST_F(Cli, PlyModelsRenderAsTheirObj) {
    const std::pair<const char*, const char*> models[] = {
        {"teapot_ascii.ply", "teapot.obj"}, {"teapot_binary.ply", "teapot.obj"}, {"cornell_box_be.ply", "cornell_box.obj"}};
    for (const auto& [ply, obj] : models)
        for (const char* backend : {"gl", "cpu"}) {
            SCOPED_TRACE(std::string(ply) + " " + backend);
            const std::string options = std::string(" --size 48x40 --backend ") + backend;
            auto outputs = [&](const std::string& name) {
                return " -o " + path(name + ".png") + " --aov depth=" + path(name + "_depth.pfm") + " --aov prim=" +
                       path(name + "_prim.pfm") + " --aov normal=" + path(name + "_normal.pfm") + " --aov color=" +
                       path(name + "_color.pfm");
            };
            const Result a = gpurt("render tests/assets/ply/" + std::string(ply) + options + outputs("ply"));
            ASSERT_EQ(a.code, 0) << a.err;
            EXPECT_EQ(a.err, "");
            const Result b = gpurt("render ../shared/models/" + std::string(obj) + options + outputs("obj"));
            ASSERT_EQ(b.code, 0) << b.err;
            EXPECT_EQ(slurp(dir / "ply_prim.pfm"), slurp(dir / "obj_prim.pfm"));
            for (const char* aov : {"depth", "normal", "color"}) {
                const Pfm x = readPfm(dir / ("ply_" + std::string(aov) + ".pfm"));
                const Pfm y = readPfm(dir / ("obj_" + std::string(aov) + ".pfm"));
                ASSERT_EQ(x.bottomFirst.size(), y.bottomFirst.size());
                size_t bad = 0;
                for (size_t k = 0; k < x.bottomFirst.size(); ++k) {
                    const float p = x.bottomFirst[k], q = y.bottomFirst[k];
                    if (!(p == q || std::abs(p - q) <= 1e-4f * std::max(1.0f, std::abs(q)))) ++bad;
                }
                EXPECT_EQ(bad, 0u) << aov;
            }
        }
}

// A PLY whose only geometry is triangle strips renders them (it once gave an empty image and exit
// 0); one without any triangle says so, naming the file.
TEST_F(Cli, PlyTriangleStripsRenderAndAFileWithoutTrianglesIsNamed) {
    const std::string head = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n";
    write("strips.ply", head + "element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
                               "-1 -1 0\n1 -1 0\n-1 1 0\n1 1 0\n4 0 1 2 3\n");
    write("points.ply", head + "end_header\n-1 -1 0\n1 -1 0\n-1 1 0\n1 1 0\n");
    for (const char* backend : {"gl", "cpu"}) {
        SCOPED_TRACE(backend);
        const std::string options = std::string(" --size 32x32 --eye 0,0,3 --target 0,0,0 --backend ") + backend;
        const Result r = gpurt("render " + path("strips.ply") + options + " -o " + path("strips.png") + " --aov prim=" +
                               path("strips_prim.pfm"));
        ASSERT_EQ(r.code, 0) << r.err;
        EXPECT_EQ(r.err, "");
        const Pfm prim = readPfm(dir / "strips_prim.pfm");
        size_t hits[2] = {0, 0};
        for (float id : prim.bottomFirst)
            if (id == 0.0f || id == 1.0f) ++hits[size_t(id)];
        EXPECT_GT(hits[0], 100u);  // both triangles of the strip, each about a quarter of the image
        EXPECT_GT(hits[1], 100u);
        const Result p = gpurt("render " + path("points.ply") + options + " -o " + path("points.png"));
        EXPECT_NE(p.err.find(path("points.ply") + ": warning: no triangles"), std::string::npos) << p.err;
    }
}

// A PLY's vertex colours go through `gpurt pack` (VCOL): the packed file renders byte for byte as
// its source on both backends, and differs from the same mesh without colours.
TEST_F(Cli, PackedPlyKeepsItsVertexColours) {
    const std::string head = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n";
    const std::string colours = "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    const std::string faces = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    write("coloured.ply", head + colours + faces + "-1 -1 0 255 0 0\n1 -1 0 0 255 0\n1 1 0 0 0 255\n-1 1 0 255 255 255\n4 0 1 2 3\n");
    write("plain.ply", head + faces + "-1 -1 0\n1 -1 0\n1 1 0\n-1 1 0\n4 0 1 2 3\n");
    const Result pack = gpurt("pack " + path("coloured.ply") + " -o " + path("coloured.gpscene"));
    ASSERT_EQ(pack.code, 0) << pack.err;
    EXPECT_NE(pack.out.find("vertexColors"), std::string::npos) << pack.out;
    for (const char* backend : {"gl", "cpu"}) {
        SCOPED_TRACE(backend);
        const std::string options = std::string(" --size 32x32 --eye 0,0,3 --target 0,0,0 --backend ") + backend;
        for (const char* scene : {"coloured.ply", "coloured.gpscene", "plain.ply"}) {
            const Result r = gpurt("render " + path(scene) + options + " -o " + path(std::string(scene) + ".png") + " --aov color=" +
                                   path(std::string(scene) + ".pfm"));
            ASSERT_EQ(r.code, 0) << scene << "\n" << r.err;
        }
        EXPECT_EQ(slurp(dir / "coloured.ply.pfm"), slurp(dir / "coloured.gpscene.pfm"));
        EXPECT_NE(slurp(dir / "coloured.ply.pfm"), slurp(dir / "plain.ply.pfm"));
    }
}

// glTF TANGENT goes through `gpurt pack` (TANG): the fuzz seed's normal-mapped quads (TANGENT as
// FLOAT and as normalized BYTE, a mirroring node; scripts/gltf/make-tangent-seed.py) render as the
// packed file does, byte for byte, on both backends, and differ from the same file without
// TANGENT. A TANGENT accessor that is not VEC4 is exit 1, one line naming the file and primitive.
TEST_F(Cli, GltfTangentsPackAndAWrongTangentTypeIsExitOne) {
    const std::string seed = slurp("tests/fuzz/corpus/gltf/tangent.gltf");
    ASSERT_NE(seed.find("\"TANGENT\": 3"), std::string::npos);
    write("tangent.gltf", seed);
    std::string plain = seed;
    for (const char* attribute : {", \"TANGENT\": 3", ", \"TANGENT\": 4"}) {
        const size_t at = plain.find(attribute);
        ASSERT_NE(at, std::string::npos) << attribute;
        plain.erase(at, std::strlen(attribute));
    }
    write("plain.gltf", plain);
    std::string wrong = seed;
    const std::string vec4 = "\"count\": 4, \"type\": \"VEC4\"";
    wrong.replace(wrong.find(vec4), vec4.size(), "\"count\": 4, \"type\": \"VEC3\"");
    write("wrong.gltf", wrong);
    const Result pack = gpurt("pack " + path("tangent.gltf") + " -o " + path("tangent.gpscene"));
    ASSERT_EQ(pack.code, 0) << pack.err;
    EXPECT_NE(pack.out.find("vertexTangents"), std::string::npos) << pack.out;
    for (const char* backend : {"gl", "cpu"}) {
        SCOPED_TRACE(backend);
        const std::string options = std::string(" --size 48x24 --eye 1.5,0,4 --target 1.5,0,0 --backend ") + backend;
        for (const char* scene : {"tangent.gltf", "tangent.gpscene", "plain.gltf"}) {
            const Result r = gpurt("render " + path(scene) + options + " -o " + path(std::string(scene) + ".png"));
            ASSERT_EQ(r.code, 0) << scene << "\n" << r.err;
        }
        EXPECT_EQ(slurp(dir / "tangent.gltf.png"), slurp(dir / "tangent.gpscene.png"));
        EXPECT_NE(slurp(dir / "tangent.gltf.png"), slurp(dir / "plain.gltf.png"));
        const Result r = gpurt("render " + path("wrong.gltf") + options + " -o " + path("wrong.png"));
        EXPECT_EQ(r.code, 1);
        EXPECT_NE(r.err.find(path("wrong.gltf") + ": mesh 0 primitive 0: TANGENT (accessor 3) is not VEC4 of one per vertex"),
                  std::string::npos)
            << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(fs::exists(dir / "wrong.png"));
    }
}

// glTF transmissionTexture goes through `gpurt pack` (TRNS): the quad of TransmissionQuad.h (its
// texture through texCoord 1 and KHR_texture_transform) in front of an emitter, lit by a point
// light, renders as the packed file does, byte for byte, on both backends with both integrators,
// and differs from the same file without the texture (the factor alone). pack counts the texture's
// user.
TEST_F(Cli, GltfTransmissionTexturePacksAndRendersAsItsSource) {
    using gpurt::test::TransmissionQuad;
    std::ofstream(dir / "bands.bmp", std::ios::binary) << TransmissionQuad::image();
    write("window.gltf", TransmissionQuad::gltf(0.8, "bands.bmp", true));
    write("plain.gltf", TransmissionQuad::gltf(0.8, "bands.bmp", true, false));
    const Result pack = gpurt("pack " + path("window.gltf") + " -o " + path("window.gpscene"));
    ASSERT_EQ(pack.code, 0) << pack.err;
    EXPECT_NE(pack.out.find("24x1, wrap clamp/clamp, 1 material\n"), std::string::npos) << pack.out;
    for (const char* backend : {"gl", "cpu"})
        for (const char* integrator : {"whitted", "path"}) {
            SCOPED_TRACE(std::string(backend) + " " + integrator);
            const std::string options = std::string(" --size 32x32 --eye 0,0,3 --target 0,0,0 --spp 4 --backend ") + backend +
                                        " --integrator " + integrator;
            for (const char* scene : {"window.gltf", "window.gpscene", "plain.gltf"}) {
                const Result r = gpurt("render " + path(scene) + options + " -o " + path(std::string(scene) + ".png") +
                                       " --aov color=" + path(std::string(scene) + ".pfm"));
                ASSERT_EQ(r.code, 0) << scene << "\n" << r.err;
            }
            EXPECT_TRUE(slurp(dir / "window.gltf.pfm") == slurp(dir / "window.gpscene.pfm")) << "the packed scene's colours";
            EXPECT_TRUE(slurp(dir / "window.gltf.png") == slurp(dir / "window.gpscene.png")) << "the packed scene's picture";
            EXPECT_FALSE(slurp(dir / "window.gltf.pfm") == slurp(dir / "plain.gltf.pfm")) << "the texture changes nothing";
        }
}

// glTF files written by another tool (Cesium's obj2gltf, checked by Khronos' glTF-Validator:
// scripts/make-test-assets.sh; a .gltf with its .bin and a .glb) hit what the OBJ they were made from
// hits, bit for bit: the same triangle ids, depths and normals at every pixel, on both backends
// (obj2gltf keeps the faces' order and reads the numbers exactly), wherever the camera sees the
// glTF's single-sided surfaces (doubleSided false, glTF's default) from the front. Their colours
// differ: obj2gltf gives the OBJ's missing material a base colour of 0.5, gpurt's default is 0.8.
// The teapot is seen from the default camera; the Cornell box, whose walls face inwards, from its
// open side (the default camera, on the +z side, is behind its back wall: see the next test).
TEST_F(Cli, GltfModelsHitWhatTheirObjHits) {
    const std::tuple<const char*, const char*, const char*> models[] = {
        {"teapot.gltf", "teapot.obj", ""}, {"cornell_box.glb", "cornell_box.obj", " --eye 278,273,-800 --target 278,273,0"}};
    for (const auto& [gltf, obj, camera] : models)
        for (const char* backend : {"gl", "cpu"}) {
            SCOPED_TRACE(std::string(gltf) + " " + backend);
            const std::string options = std::string(" --size 48x40 --backend ") + backend + camera;
            auto outputs = [&](const std::string& name) {
                return " -o " + path(name + ".png") + " --aov depth=" + path(name + "_depth.pfm") + " --aov prim=" +
                       path(name + "_prim.pfm") + " --aov normal=" + path(name + "_normal.pfm");
            };
            const Result a = gpurt("render tests/assets/gltf/" + std::string(gltf) + options + outputs("gltf"));
            ASSERT_EQ(a.code, 0) << a.err;
            EXPECT_EQ(a.err, "");
            ASSERT_EQ(gpurt("render ../shared/models/" + std::string(obj) + options + outputs("obj")).code, 0);
            for (const char* aov : {"_depth.pfm", "_prim.pfm", "_normal.pfm"})
                EXPECT_TRUE(slurp(dir / ("gltf" + std::string(aov))) == slurp(dir / ("obj" + std::string(aov)))) << aov;
        }
}

// The Cornell box's glTF is single-sided (doubleSided false) with its walls wound to face inwards
// (counter-clockwise seen from inside). The default camera, on the +z side, is behind the back
// wall (triangles 8 and 9, z = 559.2): the OBJ (two-sided) shows the wall's back wherever the box
// is, the glTF culls it and shows the inside through it; where the OBJ misses, the glTF misses too
// (the other walls are seen from behind as well).
TEST_F(Cli, SingleSidedCornellBoxFromBehindShowsItsInside) {
    for (const char* backend : {"gl", "cpu"}) {
        SCOPED_TRACE(backend);
        const std::string options = std::string(" --size 48x40 --backend ") + backend;
        for (const char* model : {"tests/assets/gltf/cornell_box.glb", "../shared/models/cornell_box.obj"}) {
            const std::string name = std::string(model).find(".glb") != std::string::npos ? "gltf" : "obj";
            const Result r = gpurt("render " + std::string(model) + options + " -o " + path(name + ".png") + " --aov prim=" +
                                   path(name + "_prim.pfm"));
            ASSERT_EQ(r.code, 0) << r.err;
        }
        const Pfm gltf = readPfm(dir / "gltf_prim.pfm"), obj = readPfm(dir / "obj_prim.pfm");
        ASSERT_EQ(gltf.bottomFirst.size(), obj.bottomFirst.size());
        const size_t step = gltf.kind == "PF" ? 3 : 1;
        size_t wall = 0, inside = 0;
        for (size_t k = 0; k < gltf.bottomFirst.size(); k += step) {
            const float g = gltf.bottomFirst[k], o = obj.bottomFirst[k];
            EXPECT_TRUE(o == -1.0f || o == 8.0f || o == 9.0f) << "the OBJ shows only the back wall, pixel " << k / step << ": " << o;
            EXPECT_TRUE(g != 8.0f && g != 9.0f) << "the glTF's back wall is culled, pixel " << k / step;
            if (o == -1.0f) {
                EXPECT_EQ(g, -1.0f) << "pixel " << k / step;
            }
            wall += o != -1.0f;
            inside += g != -1.0f;
        }
        EXPECT_GT(wall, 1000u);
        EXPECT_GT(inside, 800u);  // floor, ceiling, side walls and blocks through the back wall
    }
}

TEST_F(Cli, PackedJsonAndObjRoutesRenderIdentically) {
    write("teapot.json", "{\"meshes\": [{\"file\": \"" + fs::absolute(kTeapot).string() + "\"}]}");
    ASSERT_EQ(gpurt("pack " + kTeapot + " -o " + path("obj.gpscene")).code, 0);
    ASSERT_EQ(gpurt("pack " + path("teapot.json") + " -o " + path("json.gpscene")).code, 0);
    const std::vector<std::string> routes = {kTeapot, path("teapot.json"), path("obj.gpscene"),
                                             path("json.gpscene")};
    const std::vector<std::string> outputs = {".png", "-depth.pfm", "-prim.pfm", "-normal.pfm",
                                              "-steps.pfm"};
    for (const char* backend : {"gl", "cpu"}) {
        for (size_t k = 0; k < routes.size(); ++k) {
            const std::string stem = path(std::string(backend) + std::to_string(k));
            const Result r = gpurt(
                "render " + routes[k] + " --size 48x40 --eye 20,15,40 --target 0,0,0 --backend " +
                backend + " -o " + stem + ".png --aov depth=" + stem +
                "-depth.pfm --aov prim=" + stem + "-prim.pfm --aov normal=" + stem +
                "-normal.pfm --aov steps=" + stem + "-steps.pfm");
            ASSERT_EQ(r.code, 0) << routes[k] << " " << backend << "\n" << r.err;
            if (k == 0) continue;
            for (const std::string& o : outputs) {
                const std::string first = slurp(path(std::string(backend) + "0" + o));
                EXPECT_FALSE(first.empty());
                EXPECT_TRUE(first == slurp(stem + o)) << backend << ": " << routes[k] << " " << o;
            }
        }
    }
}

// The pictures' scene data travels in the packed file: emitters, glass (index and filter) and the
// OBJ's vertex normals give the same PNG and linear colour, byte for byte, with samples.
TEST_F(Cli, PackedCornellBoxKeepsItsLightGlassAndNormals) {
    ASSERT_EQ(gpurt("pack scenes/cornell.json -o " + path("cornell.gpscene")).code, 0);
    for (const char* backend : {"gl", "cpu"}) {
        const std::string common = std::string(" --backend ") + backend + " --size 48x48 --spp 2 ";
        for (const std::string& route : {std::string("scenes/cornell.json"), path("cornell.gpscene")}) {
            const std::string stem = path(route == "scenes/cornell.json" ? "json" : "packed");
            const Result r = gpurt("render " + route + common + "-o " + stem + ".png --aov color=" + stem + ".pfm");
            ASSERT_EQ(r.code, 0) << route << " " << backend << "\n" << r.err;
        }
        EXPECT_FALSE(slurp(dir / "json.png").empty());
        EXPECT_TRUE(slurp(dir / "json.png") == slurp(dir / "packed.png")) << backend;
        EXPECT_TRUE(slurp(dir / "json.pfm") == slurp(dir / "packed.pfm")) << backend;
    }
}

// A JSON scene with a camera, lights, mirrors, a background and render settings keeps them all.
TEST_F(Cli, PackedDemoSceneRendersAsItsJson) {
    ASSERT_EQ(gpurt("pack scenes/boxes.json -o " + path("boxes.gpscene")).code, 0);
    for (const char* backend : {"gl", "cpu"}) {
        const std::string common = std::string(" --backend ") + backend + " --size 64x48 ";
        ASSERT_EQ(gpurt("render scenes/boxes.json" + common + "-o " + path("a.png") +
                        " --aov normal=" + path("a.pfm"))
                      .code,
                  0);
        ASSERT_EQ(gpurt("render " + path("boxes.gpscene") + common + "-o " + path("b.png") +
                        " --aov normal=" + path("b.pfm"))
                      .code,
                  0);
        EXPECT_TRUE(slurp(dir / "a.png") == slurp(dir / "b.png")) << backend;
        EXPECT_TRUE(slurp(dir / "a.pfm") == slurp(dir / "b.pfm")) << backend;
    }
    // The scene's own image size travels in the packed file.
    const nlohmann::json source = nlohmann::json::parse(slurp("scenes/boxes.json"));
    const Result r = gpurt("render " + path("boxes.gpscene") + " --backend cpu -o " +
                           path("c.png") + " --stats=json");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto stats = nlohmann::json::parse(r.out);
    EXPECT_EQ(stats["width"], source["render"]["size"][0]);
    EXPECT_EQ(stats["height"], source["render"]["size"][1]);
    EXPECT_EQ(stats["grid_source"], "packed");
}

TEST_F(Cli, RenderLambdaRebuildsAPackedScenesGrid) {
    ASSERT_EQ(gpurt("pack " + kTeapot + " -o " + path("t.gpscene")).code, 0);
    const std::string render = "render " + path("t.gpscene") + " --backend cpu --size 16x16 -o " +
                               path("o.png") + " --stats=json";
    const auto packed = nlohmann::json::parse(gpurt(render).out);
    const auto rebuilt = nlohmann::json::parse(gpurt(render + " --lambda 4").out);
    const auto obj =
        nlohmann::json::parse(gpurt("render " + kTeapot + " --backend cpu --size 16x16 -o " +
                                    path("o.png") + " --stats=json --lambda 4")
                                  .out);
    EXPECT_EQ(packed["grid_source"], "packed");
    EXPECT_EQ(rebuilt["grid_source"], "built");
    EXPECT_EQ(rebuilt["grid"], obj["grid"]);
    EXPECT_NE(rebuilt["grid"], packed["grid"]);
}

// --accel: either structure gives the same picture and AOVs (the same hits); --stats says which was
// traced and why; pack stores the chosen one and render uses it; bad values are refused.
TEST_F(Cli, EitherAcceleratorGivesTheSameFilesAndStatsSayWhich) {
    const std::string base = "render scenes/room.json --size 40x32 --stats=json";
    for (const char* backend : {"gl", "cpu"}) {
        const auto grid = gpurt(base + " --backend " + backend + " --accel grid -o " + path("g.png") +
                                " --aov prim=" + path("g.pfm"));
        const auto bvh = gpurt(base + " --backend " + backend + " --accel bvh -o " + path("b.png") +
                               " --aov prim=" + path("b.pfm"));
        ASSERT_EQ(grid.code, 0) << grid.err;
        ASSERT_EQ(bvh.code, 0) << bvh.err;
        EXPECT_EQ(nlohmann::json::parse(grid.out)["accel"], "grid");
        EXPECT_EQ(nlohmann::json::parse(bvh.out)["accel"], "bvh");
        EXPECT_EQ(nlohmann::json::parse(bvh.out)["accel_source"], "built");
        EXPECT_EQ(slurp(dir / "g.png"), slurp(dir / "b.png")) << backend;
        EXPECT_EQ(slurp(dir / "g.pfm"), slurp(dir / "b.pfm")) << backend;
    }
    const auto chosen = nlohmann::json::parse(gpurt(base + " -o " + path("a.png")).out);
    ASSERT_TRUE(chosen.contains("accel_estimate"));
    const bool bvhCheaper = chosen["accel_estimate"]["bvh"].get<double>() < chosen["accel_estimate"]["grid"].get<double>();
    EXPECT_EQ(chosen["accel"], bvhCheaper ? "bvh" : "grid");
    EXPECT_EQ(chosen["accel_source"], "auto");
    // Packed with a BVH: render uses it ("packed") and gives the source's files.
    ASSERT_EQ(gpurt("pack scenes/room.json --accel bvh -o " + path("r.gpscene")).code, 0);
    const auto packed = gpurt("render " + path("r.gpscene") + " --size 40x32 --stats=json --accel grid -o " + path("p0.png"));
    EXPECT_EQ(nlohmann::json::parse(packed.out)["accel_source"], "built");  // a grid asked for: built
    const auto own = gpurt("render " + path("r.gpscene") + " --size 40x32 --stats=json -o " + path("p.png"));
    ASSERT_EQ(own.code, 0) << own.err;
    EXPECT_EQ(nlohmann::json::parse(own.out)["accel"], "bvh");
    EXPECT_EQ(nlohmann::json::parse(own.out)["accel_source"], "packed");
    EXPECT_EQ(slurp(dir / "p.png"), slurp(dir / "a.png"));
    // Refusals name the option.
    const auto bad = gpurt(base + " --accel kd -o " + path("x.png"));
    EXPECT_EQ(bad.code, 1);
    EXPECT_NE(bad.err.find("--accel"), std::string::npos) << bad.err;
    const auto mixed = gpurt("pack scenes/room.json --accel bvh --grid 4,4,4 -o " + path("x.gpscene"));
    EXPECT_EQ(mixed.code, 1);
    EXPECT_NE(mixed.err.find("--grid"), std::string::npos) << mixed.err;
    EXPECT_FALSE(fs::exists(dir / "x.gpscene"));
}

TEST_F(Cli, DamagedPackedFilesAreRefusedWithExit1) {
    ASSERT_EQ(gpurt("pack " + kTeapot + " -o " + path("good.gpscene")).code, 0);
    const std::string good = slurp(dir / "good.gpscene");
    auto expectBoth = [&](const std::string& name, const std::string& bytes,
                          const std::string& problem) {
        spit(dir / name, bytes);
        expectRefusedWithout("render " + path(name) + " -o " + path("out.png"),
                             {path(name) + ": ", problem}, dir / "out.png");
        expectRefusedWithout("pack " + path(name) + " -o " + path("out.gpscene"),
                             {path(name) + ": ", problem}, dir / "out.gpscene");
    };
    for (size_t size :
         {size_t(8), size_t(20), size_t(32), size_t(1000), good.size() / 2, good.size() - 1})
        expectBoth("cut" + std::to_string(size) + ".gpscene", good.substr(0, size), "truncated");
    std::string flipped = good;
    flipped[good.size() / 2] ^= 0x01;
    expectBoth("flipped.gpscene", flipped, "checksum mismatch");
    std::string magic = good;
    magic[7] = '2';
    expectBoth("magic.gpscene", magic, "wrong magic 'GPRTSCN2'");
    std::string version = good;
    put32(version, 8, 9);
    reseal(version);
    expectBoth("version.gpscene", version,
               "unknown packed format version 9 (this gpurt reads version 2)");
    std::string lying = good;
    put32(lying, sectionOffset(lying, "TRIS"), 993);  // one more triangle than the section holds
    reseal(lying);
    expectBoth("lying.gpscene", lying, "do not fit");
}

TEST_F(Cli, PackRefusesBadOptionsAndWritesNothing) {
    const std::string pack = "pack " + kTeapot + " -o " + path("out.gpscene");
    const fs::path out = dir / "out.gpscene";
    expectRefusedWithout(pack + " --grid 0,4,4", {"--grid"}, out);
    expectRefusedWithout(pack + " --grid 4,4", {"--grid"}, out);
    expectRefusedWithout(pack + " --grid big", {"--grid"}, out);
    expectRefusedWithout(pack + " --grid 10000,10000,10000", {"--grid"}, out);
    expectRefusedWithout(pack + " --grid 4,4,4 --lambda 3", {"--lambda"}, out);
    expectRefusedWithout(pack + " --lambda 0", {"--lambda"}, out);
    expectRefusedWithout(pack + " --dump " + kTeapot, {"--dump"}, out);
    expectRefusedWithout("pack " + path("missing.obj") + " -o " + path("out.gpscene"),
                         {"missing.obj"}, out);
    // An output folder that does not exist: refused before --dump writes anything.
    expectRefusedWithout(
        "pack " + kTeapot + " -o " + path("no/such/dir/out.gpscene") + " --dump " + path("dump"),
        {"out.gpscene", "no folder"}, dir / "dump");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 0);
}

TEST_F(Cli, PackDumpWritesTheTexturesAndTheOccupancy) {
    const Result r = gpurt("pack " + kTeapot + " -o " + path("t.gpscene") +
                           " --grid 8,6,5 --dump " + path("dump"));
    ASSERT_EQ(r.code, 0) << r.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.out, m, std::regex("references +([0-9]+)"))) << r.out;
    const size_t references = std::stoul(m[1]);
    // Voxel index: one (start, count) texel per cell, 4096 a row; starts are the counts' prefix
    // sums.
    const Pfm index = readPfm(dir / "dump/voxelIndex.pfm");
    EXPECT_EQ(index.kind, "PF");
    EXPECT_EQ(index.width, 4096);
    EXPECT_EQ(index.height, 1);
    // (An empty cell holds its skip distance, >= 1, where a list start would be.)
    double start = 0;
    for (size_t c = 0; c < 8 * 6 * 5; ++c) {
        if (index.bottomFirst[3 * c + 1] > 0) ASSERT_EQ(index.bottomFirst[3 * c], start) << "cell " << c;
        else ASSERT_GE(index.bottomFirst[3 * c], 1.0) << "cell " << c;
        start += index.bottomFirst[3 * c + 1];
    }
    EXPECT_EQ(start, double(references));
    // Cell triangles: 3 texels an entry, 4096 entries a row, w of the first = the triangle id.
    const Pfm list = readPfm(dir / "dump/cellTriangles.pfm");
    const Pfm listW = readPfm(dir / "dump/cellTriangles_w.pfm");
    EXPECT_EQ(list.kind, "PF");
    EXPECT_EQ(list.width, 3 * 4096);
    EXPECT_EQ(list.height, int((references + 4095) / 4096));
    EXPECT_EQ(listW.width, 3 * 4096);
    // Triangles: 3 texels each, 1024 a row; texel 0 is (v0 of the first face, material id 0).
    const Pfm triangles = readPfm(dir / "dump/triangles.pfm");
    const Pfm triangleW = readPfm(dir / "dump/triangles_w.pfm");
    EXPECT_EQ(triangles.width, 3072);
    EXPECT_EQ(triangles.height, 1);  // 992 triangles
    EXPECT_EQ(triangleW.width, 3072);
    std::ifstream obj(kTeapot);
    std::vector<std::vector<float>> vertices;
    int firstVertex = 0;
    for (std::string line; std::getline(obj, line) && firstVertex == 0;) {
        std::istringstream in(line);
        std::string tag;
        in >> tag;
        if (tag == "v") {
            vertices.emplace_back(3);
            in >> vertices.back()[0] >> vertices.back()[1] >> vertices.back()[2];
        }
        if (tag == "f") in >> firstVertex;
    }
    ASSERT_GT(firstVertex, 0);
    for (int c = 0; c < 3; ++c)
        EXPECT_EQ(triangles.bottomFirst[size_t(c)], vertices[size_t(firstVertex - 1)][size_t(c)]);
    EXPECT_EQ(triangleW.bottomFirst[0], 0.0f);
    const Pfm materials = readPfm(dir / "dump/materials.pfm");
    EXPECT_EQ(materials.width, GPURT_MATERIAL_TEXELS);  // the teapot has only the default material (scene_layout.h)
    EXPECT_EQ(materials.height, 1);
    for (const char* axis : {"x", "y", "z"})
        EXPECT_EQ(slurp(dir / "dump" / (std::string("occupancy_") + axis + ".png")).substr(0, 8),
                  "\x89PNG\r\n\x1a\n")
            << axis;
}

}  // namespace

namespace {

// gpurt bench: every backend's rate on the same rays, with the fields the issue names.
TEST_F(Cli, BenchPrimaryReportsEveryBackendOnTheSameRays) {
    const Result r = gpurt("bench " + kTeapot + " --size 40x30 --runs 1 --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_TRUE(j.contains("backends"));
    std::set<std::string> names;
    for (const auto& b : j["backends"]) {
        names.insert(b["backend"].get<std::string>());
        for (const char* key : {"mrays_per_s", "rays", "ms", "passes", "threads", "renderer"})
            EXPECT_TRUE(b.contains(key)) << b["backend"] << " " << key;
        EXPECT_EQ(b["rays"], 40 * 30) << b["backend"];  // primary: one per pixel, all counted
        EXPECT_GT(b["mrays_per_s"].get<double>(), 0.0);
        if (b.contains("agreement")) {
            EXPECT_GE(b["agreement"].get<double>(), 0.999) << b["backend"];
        }
        if (b["backend"] == "embree") {
            EXPECT_DOUBLE_EQ(b["ratio_to_embree"].get<double>(), 1.0);
        }
    }
    EXPECT_TRUE(names.count("gl") && names.count("cpu"));
    for (const auto& b : j["backends"])
        if (b["backend"] == "gl") {  // one pass that generates its rays (trace.frag with CAMERA)
            EXPECT_EQ(b["passes"]["traceCamera"]["fragments"], 40 * 30);
            EXPECT_FALSE(b["passes"].contains("raygen"));
        }
}

// Shadow rays: one per primary hit, counted independently from the prim AOV of a render.
TEST_F(Cli, BenchShadowTracesOneRayPerPrimaryHit) {
    ASSERT_EQ(gpurt("render " + kTeapot + " -o " + path("out.png") + " --size 40x30 --backend cpu --aov prim=" +
                    path("p.pfm")).code, 0);
    std::ifstream in(dir / "p.pfm", std::ios::binary);
    std::string header[3];
    in >> header[0] >> header[1] >> header[2] >> header[2];
    in.get();
    std::vector<float> prim(40 * 30);
    in.read(reinterpret_cast<char*>(prim.data()), std::streamsize(prim.size() * 4));
    const auto hits = std::count_if(prim.begin(), prim.end(), [](float p) { return p >= 0.0f; });
    ASSERT_GT(hits, 0);
    for (const char* backend : {"gl", "cpu"}) {
        const Result r = gpurt("bench " + kTeapot + " --size 40x30 --runs 1 --rays shadow --json --backend " + backend);
        ASSERT_EQ(r.code, 0) << r.err;
        const auto j = nlohmann::json::parse(r.out);
        EXPECT_EQ(j["backend"], backend);
        EXPECT_EQ(j["rays"], hits) << backend;
        EXPECT_EQ(j["ray_kind"], "shadow");
    }
}

TEST_F(Cli, BenchRefusesBadOptions) {
    expectRefused("bench " + kTeapot + " --rays sideways", "--rays");
    expectRefused("bench " + kTeapot + " --backend optix", "--backend");
    expectRefused("bench " + path("missing.obj"), "missing.obj");
}

}  // namespace

namespace {

// The outputs of a render: the PNG and every AOV, named after `stem`.
std::string renderOutputs(const std::function<std::string(const std::string&)>& path, const std::string& stem) {
    std::string args = " -o " + path(stem + ".png");
    for (const char* aov : {"depth", "prim", "normal", "steps", "color"})
        args += std::string(" --aov ") + aov + "=" + path(stem + "_" + aov + ".pfm");
    return args;
}

// Tiles (--tile I/N) stitched together are the whole render, byte for byte, for every output, on
// both backends, with samples, for N that do and do not divide the height (37 rows).
TEST_F(Cli, StitchedTilesAreTheWholeRenderByteForByte) {
    auto p = [this](const std::string& name) { return path(name); };
    const std::string scene = "render scenes/cornell.json --size 30x37 --spp 4";
    const std::vector<std::string> outputs = {".png", "_depth.pfm", "_prim.pfm", "_normal.pfm", "_steps.pfm", "_color.pfm"};
    for (const char* backend : {"gl", "cpu"}) {
        const std::string options = std::string(" --backend ") + backend;
        ASSERT_EQ(gpurt(scene + options + renderOutputs(p, "whole")).code, 0);
        for (int n : {1, 3, 4, 7}) {
            SCOPED_TRACE(std::string(backend) + ", " + std::to_string(n) + " tiles");
            for (int i = n - 1; i >= 0; --i) {  // in any order
                const Result r = gpurt(scene + options + " --tile " + std::to_string(i) + "/" + std::to_string(n) +
                                       renderOutputs(p, "t" + std::to_string(i)));
                ASSERT_EQ(r.code, 0) << r.err;
            }
            for (const std::string& output : outputs) {
                std::string tiles;
                for (int i = 0; i < n; ++i) tiles += " " + path("t" + std::to_string(i) + output);
                const Result r = gpurt("stitch -o " + path("stitched" + output) + tiles);
                ASSERT_EQ(r.code, 0) << output << ": " << r.err;
                EXPECT_EQ(slurp(dir / ("stitched" + output)), slurp(dir / ("whole" + output))) << output;
            }
        }
    }
}

// Adaptive tiles render a margin of rows (a pixel's stopping decision reaches one row further each
// convergence pass): stitched, they are the whole adaptive render byte for byte, spp AOV included.
TEST_F(Cli, AdaptiveTilesStitchToTheWholeRender) {
    for (const char* backend : {"gl", "cpu"}) {
        SCOPED_TRACE(backend);
        const std::string scene = std::string("render scenes/cornell_blocks.json --size 40x36 --integrator path --spp 64 "
                                              "--noise-threshold 0.05 --min-spp 16 --backend ") + backend;
        ASSERT_EQ(gpurt(scene + " -o " + path("whole.png") + " --aov spp=" + path("whole_spp.pfm")).code, 0);
        std::string pngs, spps;
        for (int i = 0; i < 3; ++i) {
            const std::string t = "t" + std::to_string(i);
            const Result r = gpurt(scene + " --tile " + std::to_string(i) + "/3 -o " + path(t + ".png") + " --aov spp=" +
                                   path(t + "_spp.pfm"));
            ASSERT_EQ(r.code, 0) << r.err;
            pngs += " " + path(t + ".png");
            spps += " " + path(t + "_spp.pfm");
        }
        ASSERT_EQ(gpurt("stitch -o " + path("st.png") + pngs).code, 0);
        ASSERT_EQ(gpurt("stitch -o " + path("st_spp.pfm") + spps).code, 0);
        EXPECT_EQ(slurp(dir / "st.png"), slurp(dir / "whole.png"));
        EXPECT_EQ(slurp(dir / "st_spp.pfm"), slurp(dir / "whole_spp.pfm"));
    }
}

// The GNU parallel driver (scripts/farm/gpurt-parallel.sh) renders a 4-tile image with real GNU
// parallel on this machine's cores; stitched, it is the whole render. A run whose tiles fail exits
// non-zero and writes no image.
TEST_F(Cli, GnuParallelDriverRendersTheWholeImage) {
    const std::string driver = foreign("scripts/farm/gpurt-parallel.sh --gpurt " + gpurtKeepingPreloads(dir));
    const std::string scene = " scenes/cornell_blocks.json --size 32x26 --spp 2";
    const std::string command = driver + " --tiles 4 --jobs 2 -o " + path("farm.png") + scene + " 2>" + path("farm.err");
    const int code = std::system(command.c_str());
    ASSERT_EQ(code, 0) << command << "\n" << slurp(dir / "farm.err");
    ASSERT_EQ(gpurt("render" + scene + " -o " + path("whole.png")).code, 0);
    EXPECT_EQ(slurp(dir / "farm.png"), slurp(dir / "whole.png"));
    const std::string failing = driver + " --tiles 3 -o " + path("bad.png") + scene + " --spp 0 2>" + path("bad.err");
    EXPECT_NE(std::system(failing.c_str()), 0);
    EXPECT_FALSE(fs::exists(dir / "bad.png"));
    EXPECT_NE(slurp(dir / "bad.err").find("--resume"), std::string::npos) << slurp(dir / "bad.err");
    // One tile fails (its file's name is taken by a folder); --resume then re-runs that tile alone.
    fs::create_directories(dir / "again.png.tiles" / "tile2.png");
    const std::string again = driver + " --tiles 4 -o " + path("again.png");  // the driver's options before the scene
    EXPECT_NE(std::system((again + scene + " 2>" + path("again.err")).c_str()), 0);
    EXPECT_FALSE(fs::exists(dir / "again.png"));
    fs::remove(dir / "again.png.tiles" / "tile2.png");
    const auto firstTile = fs::last_write_time(dir / "again.png.tiles" / "tile0.png");
    ASSERT_EQ(std::system((again + " --resume" + scene + " 2>" + path("again.err")).c_str()), 0) << slurp(dir / "again.err");
    EXPECT_EQ(slurp(dir / "again.png"), slurp(dir / "whole.png"));
    EXPECT_EQ(fs::last_write_time(dir / "again.png.tiles" / "tile0.png"), firstTile);  // not rendered again
}

// A one-node Slurm on this machine (tests/farm/slurm-localhost.sh: its own munge, slurm.conf,
// state and ports in a scratch folder), started for the test and stopped by its daemons' process
// ids afterwards, whatever the test's outcome.
class SlurmCluster {
  public:
    explicit SlurmCluster(const fs::path& folder) : folder_(folder) {
        const fs::path log = folder_.string() + ".log";
        const int status = std::system(foreign("tests/farm/slurm-localhost.sh start " + folder_.string() + " >" +
                                               log.string() + " 2>&1").c_str());
        started_ = status == 0;
        std::ifstream in(log);
        log_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        fs::remove(log);
    }
    ~SlurmCluster() {
        std::system(foreign("tests/farm/slurm-localhost.sh stop " + folder_.string() + " >/dev/null 2>&1").c_str());
        fs::remove_all(folder_);
    }
    bool started() const { return started_; }
    const std::string& log() const { return log_; }
    // A command run as a client of this cluster (SLURM_CONF), without the sanitizer's preloads.
    std::string client(const std::string& command) const {
        return foreign("SLURM_CONF=" + (folder_ / "slurm.conf").string() + " " + command);
    }

  private:
    fs::path folder_;
    bool started_ = false;
    std::string log_;
};

// The Slurm driver (scripts/farm/gpurt-slurm.sh) against a real one-node Slurm: a 4-tile image (a job
// array and a stitch job after it), a 3-tile denoised one (the stitch job stitches the AOVs and
// denoises) and a 3-frame animation of the packed scene equal the whole renders; a failed tile
// fails --wait, naming it, and --resume re-runs that tile alone.
TEST_F(Cli, SlurmDriverRendersTilesAndFramesOnARealCluster) {
    // Short and without spaces: slurm.conf cannot quote paths, munge's socket path is limited.
    const SlurmCluster cluster(fs::temp_directory_path() / ("gpurt-slurm-" + std::to_string(::getpid())));
    ASSERT_TRUE(cluster.started()) << "the one-node Slurm did not start:\n" << cluster.log();
    const std::string driver = cluster.client("scripts/farm/gpurt-slurm.sh --wait --gpurt " + gpurtKeepingPreloads(dir));
    const std::string scene = " scenes/cornell_blocks.json --size 32x26 --spp 2";
    auto run = [&](const std::string& command) {
        const int status = std::system((command + " >" + path("slurm.out") + " 2>" + path("slurm.err")).c_str());
        return std::pair(WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir / "slurm.out") + slurp(dir / "slurm.err"));
    };
    ASSERT_EQ(gpurt("render" + scene + " -o " + path("whole.png")).code, 0);
    {
        const auto [code, log] = run(driver + " --tiles 4 -o " + path("farm.png") + scene);
        ASSERT_EQ(code, 0) << log;
        EXPECT_EQ(slurp(dir / "farm.png"), slurp(dir / "whole.png"));
    }
    {  // --denoise: the tiles' AOVs, stitched and denoised, are render --denoise's picture.
        const std::string traced = " scenes/cornell_blocks.json --size 32x26 --spp 4 --integrator path";
        ASSERT_EQ(gpurt("render" + traced + " --denoise -o " + path("whole_denoised.png")).code, 0);
        const auto [code, log] = run(driver + " --tiles 3 --denoise -o " + path("denoised.png") + traced);
        ASSERT_EQ(code, 0) << log;
        EXPECT_EQ(slurp(dir / "denoised.png"), slurp(dir / "whole_denoised.png"));
        EXPECT_TRUE(fs::exists(dir / "denoised.png.tiles" / "raw.png"));
    }
    {  // Tile 2 fails (its file's name is taken by a folder); --resume runs it alone, then the stitch.
        fs::create_directories(dir / "again.png.tiles" / "tile2.png");
        const auto [code, log] = run(driver + " --tiles 4 -o " + path("again.png") + scene);
        EXPECT_NE(code, 0) << log;
        EXPECT_NE(log.find("tile 2 failed"), std::string::npos) << log;
        EXPECT_FALSE(fs::exists(dir / "again.png"));
        fs::remove(dir / "again.png.tiles" / "tile2.png");
        const auto firstTile = fs::last_write_time(dir / "again.png.tiles" / "tile0.png");
        const auto [again, resumed] = run(driver + " --resume --tiles 4 -o " + path("again.png") + scene);
        ASSERT_EQ(again, 0) << resumed;
        EXPECT_NE(resumed.find("tiles 2: job"), std::string::npos) << resumed;
        EXPECT_EQ(slurp(dir / "again.png"), slurp(dir / "whole.png"));
        EXPECT_EQ(fs::last_write_time(dir / "again.png.tiles" / "tile0.png"), firstTile);
    }
    {  // Frames of the packed scene, one task each.
        ASSERT_EQ(gpurt("pack scenes/cornell_flythrough.json -o " + path("fly.gpscene")).code, 0);
        const std::string frames = " --size 24x24 --spp 2";
        ASSERT_EQ(gpurt("render scenes/cornell_flythrough.json --frames 0:2 -o " + path("whole%d.png") + frames).code, 0);
        const auto [code, log] = run(driver + " --frames 0:2 -o " + path("fly%04d.png") + " " + path("fly.gpscene") + frames);
        ASSERT_EQ(code, 0) << log;
        for (int f = 0; f <= 2; ++f) {
            char name[32];
            std::snprintf(name, sizeof name, "fly%04d.png", f);
            EXPECT_EQ(slurp(dir / name), slurp(dir / ("whole" + std::to_string(f) + ".png"))) << name;
        }
    }
}

// --frames A:B renders frames A..B of a JSON scene's camera animation: frame f's image is the
// render with the camera interpolated linearly at time f / fps (computed here, in double, from the
// keys) given on the command line; the packed scene carries the animation. One JSON object of
// statistics per frame.
TEST_F(Cli, FramesAreTheAnimationsCamerasRenderedOneByOne) {
    const std::string mesh = fs::absolute("scenes/cornell_blocks.obj").string();
    struct Key {
        double time, eye[3], target[3], up[3], fovy;
    };
    const Key keys[] = {{0.0, {278, 273, -800}, {278, 273, 0}, {0, 1, 0}, 39},
                        {1.0, {350, 300, -300}, {250, 200, 100}, {0.2, 1, 0}, 55},
                        {1.5, {400, 330, -100}, {250, 160, 280}, {0, 1, 0}, 70}};
    const double fps = 4;
    std::string json = "{\"meshes\": [{\"file\": \"" + mesh + "\"}], \"background\": [0, 0, 0], "
                       "\"animation\": {\"fps\": 4, \"camera\": [";
    auto vec = [](const double* v) {
        return "[" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " + std::to_string(v[2]) + "]";
    };
    for (const Key& k : keys)
        json += std::string(&k == keys ? "" : ", ") + "{\"time\": " + std::to_string(k.time) + ", \"eye\": " +
                vec(k.eye) + ", \"target\": " + vec(k.target) + ", \"up\": " + vec(k.up) +
                ", \"fovy\": " + std::to_string(k.fovy) + "}";
    write("anim.json", json + "]}}");
    const std::string scene = "render " + path("anim.json") + " --size 24x20 --spp 2";
    const Result r = gpurt(scene + " --frames 1:7 -o " + path("f%04d.png") + " --aov depth=" + path("d%d.pfm") +
                           " --stats=json");
    ASSERT_EQ(r.code, 0) << r.err;
    std::istringstream lines(r.out);
    std::string line;
    for (int frame = 1; frame <= 7; ++frame) {
        SCOPED_TRACE("frame " + std::to_string(frame));
        ASSERT_TRUE(std::getline(lines, line));
        EXPECT_EQ(nlohmann::json::parse(line)["frame"], frame);
        const double t = frame / fps;
        size_t k = 0;
        while (k + 2 < std::size(keys) && keys[k + 1].time < t) ++k;
        const Key &a = keys[k], &b = keys[k + 1];
        const double s = std::clamp((t - a.time) / (b.time - a.time), 0.0, 1.0);
        auto at = [&](const double* p, const double* q) {
            char text[128];
            std::snprintf(text, sizeof text, "%.9g,%.9g,%.9g", double(float(p[0] + (q[0] - p[0]) * s)),
                          double(float(p[1] + (q[1] - p[1]) * s)), double(float(p[2] + (q[2] - p[2]) * s)));
            return std::string(text);
        };
        char fovy[32];
        std::snprintf(fovy, sizeof fovy, "%.9g", double(float(a.fovy + (b.fovy - a.fovy) * s)));
        const Result one = gpurt(scene + " --eye " + at(a.eye, b.eye) + " --target " + at(a.target, b.target) +
                                 " --up " + at(a.up, b.up) + " --fovy " + fovy + " -o " + path("one.png") +
                                 " --aov depth=" + path("one.pfm"));
        ASSERT_EQ(one.code, 0) << one.err;
        char name[32];
        std::snprintf(name, sizeof name, "f%04d.png", frame);
        EXPECT_EQ(slurp(dir / name), slurp(dir / "one.png"));
        EXPECT_EQ(slurp(dir / ("d" + std::to_string(frame) + ".pfm")), slurp(dir / "one.pfm"));
    }
    EXPECT_FALSE(std::getline(lines, line)) << line;
    EXPECT_FALSE(fs::exists(dir / "f0000.png"));
    EXPECT_FALSE(fs::exists(dir / "f0008.png"));
    // What workers get: the packed scene, with its animation.
    ASSERT_EQ(gpurt("pack " + path("anim.json") + " -o " + path("anim.gpscene")).code, 0);
    ASSERT_EQ(gpurt("render " + path("anim.gpscene") + " --size 24x20 --spp 2 --frames 3:3 -o " + path("p%02d.png")).code, 0);
    EXPECT_EQ(slurp(dir / "p03.png"), slurp(dir / "f0003.png"));
    // And a frame of a tile: rows of that frame.
    ASSERT_EQ(gpurt(scene + " --frames 5:5 --tile 1/2 -o " + path("t1_%d.png")).code, 0);
    ASSERT_EQ(gpurt(scene + " --frames 5:5 --tile 0/2 -o " + path("t0_%d.png")).code, 0);
    ASSERT_EQ(gpurt("stitch -o " + path("s5.png") + " " + path("t0_5.png") + " " + path("t1_5.png")).code, 0);
    EXPECT_EQ(slurp(dir / "s5.png"), slurp(dir / "f0005.png"));
}

TEST_F(Cli, FramesRefuseScenesWithoutAnimationAndNamesWithoutTheNumber) {
    const std::string mesh = fs::absolute("scenes/cornell_blocks.obj").string();
    // The up vector turns over between the keys: at frame 1 (t = 0.5) it is zero.
    write("flip.json", "{\"meshes\": [{\"file\": \"" + mesh + "\"}], \"animation\": {\"fps\": 2, \"camera\": ["
                       "{\"time\": 0, \"eye\": [278, 273, -800], \"target\": [278, 273, 0], \"up\": [0, 1, 0]},"
                       "{\"time\": 1, \"eye\": [278, 273, -800], \"target\": [278, 273, 0], \"up\": [0, -1, 0]}]}}");
    const std::string out = " --size 8x8 -o " + path("f%04d.png");
    expectRefused("render " + path("flip.json") + " --frames 0:2" + out, "flip.json: frame 1:");
    EXPECT_FALSE(fs::exists(dir / "f0000.png"));  // nothing written, not even the good frames
    expectRefused("render scenes/cornell_blocks.json --frames 0:2" + out, "has no camera animation");
    expectRefused("render " + path("flip.json") + " --frames 0:0 --size 8x8 -o " + path("out.png"), "-o: '");
    expectRefused("render " + path("flip.json") + " --frames 0:0" + out + " --aov depth=" + path("d.pfm"), "--aov depth");
    expectRefused("render " + path("flip.json") + " --frames 2:0" + out, "--frames");
    expectRefused("render " + path("flip.json") + " --frames 0-2" + out, "--frames");
    // With --up given, every frame has a camera.
    EXPECT_EQ(gpurt("render " + path("flip.json") + " --frames 0:2 --up 1,0,0" + out).code, 0);
    EXPECT_TRUE(fs::exists(dir / "f0002.png"));
}

// A task killed at any moment (SIGKILL, as a scheduler kills a task past its time) leaves its
// outputs whole or absent: each file appears by a rename of a finished temporary file, in the order
// PNG, its sidecar, the AOV, its sidecar, so what a kill leaves is a prefix of that list (almost
// always all or nothing), and a tile with its sidecar is one stitch accepts. The drivers count a
// tile done only with its sidecar. The kills wait for events of the task, never for a time: its
// progress lines (rendering: nothing may exist yet), the first temporary file or the first
// output file (writing: a prefix), and its end (all of it).
TEST_F(Cli, AKilledTaskLeavesNoHalfWrittenOutput) {
    const std::vector<std::string> render = {GPURT_BINARY, "render", "scenes/cornell_blocks.json", "--size", "200x160",
                                             "--spp", "4", "--tile", "0/1", "--progress", "-o", path("t.png"),
                                             "--aov", "depth=" + path("t.pfm")};
    const std::vector<std::string> outputs = {"t.png", "t.png.tile", "t.pfm", "t.pfm.tile"};
    auto temporaryExists = [&] {
        for (const auto& entry : fs::directory_iterator(dir))
            if (entry.path().filename().string().find(".tmp-") != std::string::npos) return true;
        return false;
    };
    using Event = std::function<bool()>;
    const std::pair<std::string, Event> events[] = {
        {"its first progress line", [&] { return gpurt::test::readFile(dir / "err").find("progress ") != std::string::npos; }},
        {"its second progress line", [&] {
             const std::string err = gpurt::test::readFile(dir / "err");
             return std::count(err.begin(), err.end(), '\n') >= 2;
         }},
        {"its first temporary file", temporaryExists},
        {"its first output file", [&] { return fs::exists(dir / "t.png"); }},
        {"its end", Event()},
    };
    for (const auto& [name, event] : events) {
        SCOPED_TRACE("killed at " + name);
        std::vector<fs::path> left;  // the last task's files, temporaries of a kill too
        for (const auto& entry : fs::directory_iterator(dir)) left.push_back(entry.path());
        for (const fs::path& file : left) fs::remove(file);
        gpurt::test::Background task(render, dir / "out", dir / "err", "");
        ASSERT_TRUE(task.started());
        // Polled as fast as the file system answers; at most five minutes (a loaded machine).
        const auto end = std::chrono::steady_clock::now() + std::chrono::minutes(5);
        bool seen = !event;
        while (!seen && task.running() && std::chrono::steady_clock::now() < end) seen = event();
        if (event && seen) task.killNow();
        // Writing takes milliseconds: a poll can miss it (the task then ends whole), so the kills
        // while writing are reported, not required.
        std::printf("[   INFO   ] %s: %s\n", name.c_str(), !event ? "not killed" : seen ? "killed" : "ended first");
        if (!event) {
            EXPECT_EQ(task.wait(std::chrono::seconds(300)), 0) << gpurt::test::readFile(dir / "err");
        }
        const bool png = fs::exists(dir / "t.png"), sidecar = fs::exists(dir / "t.png.tile"),
                   depth = fs::exists(dir / "t.pfm"), depthSidecar = fs::exists(dir / "t.pfm.tile");
        EXPECT_TRUE(png >= sidecar && sidecar >= depth && depth >= depthSidecar);
        if (name.find("progress") != std::string::npos) {
            ASSERT_TRUE(seen) << "no progress line: " << gpurt::test::readFile(dir / "err");
            EXPECT_FALSE(png) << "an output before the render's end";
        }
        if (!event) {
            EXPECT_TRUE(depthSidecar) << "the whole task left no complete output";
        }
        if (sidecar) {
            EXPECT_EQ(gpurt("stitch -o " + path("s.png") + " " + path("t.png")).code, 0);
        }
        if (depthSidecar) {
            EXPECT_EQ(gpurt("stitch -o " + path("s.pfm") + " " + path("t.pfm")).code, 0);
        }
    }
}

// The layout's channels of an EXR file, read with OpenEXR itself, interleaved, top row first.
std::vector<float> openExr(const fs::path& file, const std::vector<std::string>& channels, Imf::PixelType type,
                           int& width, int& height) {
    Imf::InputFile in(file.c_str());
    const Imath::Box2i window = in.header().dataWindow();
    width = window.max.x + 1;
    height = window.max.y + 1;
    EXPECT_EQ(window.min.x, 0);
    EXPECT_EQ(window.min.y, 0);
    const size_t n = channels.size();
    std::vector<float> values(size_t(width) * size_t(height) * n);
    Imf::FrameBuffer frame;
    for (size_t c = 0; c < n; ++c) {
        const Imf::Channel* channel = in.header().channels().findChannel(channels[c]);
        EXPECT_TRUE(channel && channel->type == type) << file << " " << channels[c];
        frame.insert(channels[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data() + c), n * sizeof(float),
                                             n * sizeof(float) * size_t(width)));
    }
    in.setFrameBuffer(frame);
    in.readPixels(0, height - 1);
    return values;
}

// The PFM's values top row first (PFM stores the bottom row first).
std::vector<float> topFirst(const Pfm& pfm) {
    const size_t row = pfm.bottomFirst.size() / size_t(pfm.height);
    std::vector<float> out;
    for (int y = pfm.height - 1; y >= 0; --y)
        out.insert(out.end(), pfm.bottomFirst.begin() + std::ptrdiff_t(size_t(y) * row),
                   pfm.bottomFirst.begin() + std::ptrdiff_t(size_t(y + 1) * row));
    return out;
}

// -o OUT.exr is the linear colour times 2^EV as half floats (R, G, B); AOVs named .exr are 32-bit
// float channels (depth Z, prim, normal X Y Z, color R G B) with the PFM AOVs' very values.
// Read back with OpenEXR's library and its exrheader tool.
TEST_F(Cli, ExrOutputsReadBackWithOpenExr) {
    const std::string render = "render " + kTeapot + " --size 40x30 --exposure 1";
    std::string exr = " -o " + path("out.exr"), pfm = " -o " + path("out.png");
    for (const char* aov : {"depth", "prim", "normal", "color"}) {
        exr += std::string(" --aov ") + aov + "=" + path(std::string(aov) + ".exr");
        pfm += std::string(" --aov ") + aov + "=" + path(std::string(aov) + ".pfm");
    }
    ASSERT_EQ(gpurt(render + exr).code, 0);
    ASSERT_EQ(gpurt(render + pfm).code, 0);
    const std::vector<float> color = topFirst(readPfm(dir / "color.pfm"));
    int w = 0, h = 0;
    const std::vector<float> image = openExr(dir / "out.exr", {"R", "G", "B"}, Imf::HALF, w, h);
    EXPECT_EQ(w, 40);
    EXPECT_EQ(h, 30);
    ASSERT_EQ(image.size(), color.size());
    size_t differ = 0;
    for (size_t k = 0; k < image.size(); ++k) differ += image[k] != float(Imath::half(color[k] * 2.0f));
    EXPECT_EQ(differ, 0u);
    const std::pair<const char*, std::vector<std::string>> aovs[] = {
        {"depth", {"Z"}}, {"prim", {"prim"}}, {"normal", {"X", "Y", "Z"}}, {"color", {"R", "G", "B"}}};
    for (const auto& [aov, channels] : aovs) {
        const std::vector<float> values = openExr(dir / (std::string(aov) + ".exr"), channels, Imf::FLOAT, w, h);
        const std::vector<float> expected = topFirst(readPfm(dir / (std::string(aov) + ".pfm")));
        ASSERT_EQ(values.size(), expected.size()) << aov;
        EXPECT_EQ(std::memcmp(values.data(), expected.data(), values.size() * sizeof(float)), 0) << aov;
    }
    const std::string info = path("exrheader.txt");
    ASSERT_EQ(std::system(("exrheader " + path("depth.exr") + " >" + info + " 2>&1").c_str()), 0) << slurp(info);
    const std::string header = slurp(info);
    EXPECT_NE(header.find("Z, 32-bit floating-point"), std::string::npos) << header;
    EXPECT_NE(header.find("compression (type compression): zip"), std::string::npos) << header;
    EXPECT_NE(header.find("dataWindow (type box2i): (0 0) - (39 29)"), std::string::npos) << header;
}

// EXR tiles stitch, as PNG and PFM tiles do, into the bytes of the whole render's EXR files; a
// PNG tile is no tile of an EXR.
TEST_F(Cli, StitchedExrTilesAreTheWholeRender) {
    const std::string scene = "render scenes/cornell_blocks.json --size 20x17 --spp 2";
    auto outputs = [&](const std::string& stem) {
        return " -o " + path(stem + ".exr") + " --aov depth=" + path(stem + "_depth.exr") + " --aov normal=" +
               path(stem + "_normal.exr");
    };
    ASSERT_EQ(gpurt(scene + outputs("whole")).code, 0);
    for (int i = 0; i < 3; ++i)
        ASSERT_EQ(gpurt(scene + " --tile " + std::to_string(i) + "/3" + outputs("t" + std::to_string(i))).code, 0);
    for (const std::string suffix : {".exr", "_depth.exr", "_normal.exr"}) {
        const Result r = gpurt("stitch -o " + path("s" + suffix) + " " + path("t2" + suffix) + " " + path("t0" + suffix) +
                               " " + path("t1" + suffix));
        ASSERT_EQ(r.code, 0) << r.err;
        EXPECT_EQ(slurp(dir / ("s" + suffix)), slurp(dir / ("whole" + suffix))) << suffix;
    }
    ASSERT_EQ(gpurt(scene + " --tile 0/1 -o " + path("png0.png")).code, 0);
    expectRefused("stitch -o " + path("out.exr") + " " + path("png0.png"), "a PNG tile for");
}

// Stitch refuses, with exit 1 and one line naming the tile, a missing, repeated, foreign or
// damaged tile, and a file that is not a tile; it writes nothing then.
TEST_F(Cli, StitchRefusesMissingRepeatedForeignAndDamagedTiles) {
    const std::string scene = "render scenes/cornell_blocks.json --size 16x12 --spp 2";
    for (int i = 0; i < 3; ++i)
        ASSERT_EQ(gpurt(scene + " --tile " + std::to_string(i) + "/3 -o " + path("t" + std::to_string(i) + ".png") +
                        " --aov depth=" + path("d" + std::to_string(i) + ".pfm")).code, 0);
    ASSERT_EQ(gpurt(scene + " --seed 7 --tile 1/3 -o " + path("other1.png")).code, 0);
    ASSERT_EQ(gpurt("render scenes/cornell_blocks.json --size 16x12 -o " + path("plain.png")).code, 0);
    const std::string out = " -o " + path("out.png");
    expectRefused("stitch" + out + " " + path("t0.png") + " " + path("t2.png"), "tile 1/3");
    expectRefused("stitch" + out + " " + path("t0.png") + " " + path("t1.png") + " " + path("t1.png") + " " + path("t2.png"),
                  "t1.png: tile 1 given twice");
    expectRefused("stitch" + out + " " + path("t0.png") + " " + path("other1.png") + " " + path("t2.png"), "other1.png");
    expectRefused("stitch" + out + " " + path("plain.png"), "plain.png");
    expectRefused("stitch" + out + " " + path("d0.pfm") + " " + path("d1.pfm") + " " + path("d2.pfm"), "d0.pfm");
    // A value of a tile changed after it was written.
    std::string bytes = slurp(dir / "d1.pfm");
    bytes[bytes.size() - 3] ^= 0x40;
    std::ofstream(dir / "d1.pfm", std::ios::binary) << bytes;
    expectRefused("stitch -o " + path("out.pfm") + " " + path("d0.pfm") + " " + path("d1.pfm") + " " + path("d2.pfm"),
                  "d1.pfm: damaged");
    EXPECT_FALSE(fs::exists(dir / "out.pfm"));
    // --tile itself: N beyond the height, I beyond N, not I/N.
    for (const char* bad : {"--tile 0/13", "--tile 3/3", "--tile 1", "--tile a/b", "--tile -1/2"})
        expectRefused(scene + " -o " + path("out.png") + " " + bad, "--tile");
}

// --integrator ao (integrators/ao, one registry entry): the same samples on both backends, tiles
// that stitch to the whole render, its option refused where it means nothing or is out of range,
// and --help naming every registered integrator.
TEST_F(Cli, AmbientOcclusionRendersOnBothBackendsAndStitches) {
    const std::string scene = "render scenes/cornell_blocks.json --size 24x20 --integrator ao --spp 4 --ao-distance 200";
    for (const char* backend : {"gl", "cpu"}) {
        const std::string b = std::string(" --backend ") + backend;
        ASSERT_EQ(gpurt(scene + b + " -o " + path(std::string(backend) + ".png") + " --aov color=" +
                        path(std::string(backend) + ".pfm")).code, 0);
        for (int i = 0; i < 2; ++i) {
            const Result r = gpurt(scene + b + " --tile " + std::to_string(i) + "/2 -o " + path("t" + std::to_string(i) + ".pfm.png") +
                                   " --aov color=" + path("t" + std::to_string(i) + ".pfm"));
            ASSERT_EQ(r.code, 0) << r.err;
        }
        ASSERT_EQ(gpurt("stitch -o " + path("stitched.pfm") + " " + path("t0.pfm") + " " + path("t1.pfm")).code, 0);
        EXPECT_EQ(slurp(dir / "stitched.pfm"), slurp(dir / (std::string(backend) + ".pfm"))) << backend;
    }
    EXPECT_EQ(slurp(dir / "gl.pfm"), slurp(dir / "cpu.pfm"));  // the same rays, the same 0s and 1s
    int w = 0, h = 0, channels = 0;
    const std::vector<float> ao = gpurt::readPfm(path("cpu.pfm"), w, h, channels);
    for (float v : ao) EXPECT_TRUE(v >= 0.0f && v <= 1.0f) << v;  // means of 0s and 1s
    expectRefused("render scenes/cornell_blocks.json --integrator path --ao-distance 2 -o " + path("x.png"), "--ao-distance");
    expectRefused("render scenes/cornell_blocks.json --integrator ao --ao-distance 0 -o " + path("x.png"), "--ao-distance");
    expectRefused("render scenes/cornell_blocks.json --integrator ao --ao-distance -3 -o " + path("x.png"), "--ao-distance");
    expectRefused("render scenes/cornell_blocks.json --integrator ao --ao-distance far -o " + path("x.png"), "--ao-distance");
    expectRefused("render scenes/cornell_blocks.json --integrator ao --denoise -o " + path("x.png"), "--denoise");
    const Result help = gpurt("render --help");
    for (const char* name : {"whitted", "path", "ao"}) EXPECT_NE(help.out.find(name), std::string::npos) << name;
    EXPECT_NE(help.out.find("--ao-distance"), std::string::npos);
}

// An accelerator owns its data (issue 36): every accelerator, from the source file and packed, of
// a file whose up axis is y or z (--up-axis z turns it), at unit size, 1024 times it and 2^40
// times it (rescaled to render: SceneScale.h), hits the same triangles in the same picture. Ambient
// occlusion makes the picture: hits and occlusion alone, the same at any scale.
TEST_F(Cli, EveryAcceleratorPackedOrNotTurnedAndScaledRendersTheSamePicture) {
    std::ifstream in("scenes/cornell_blocks.obj");
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    ASSERT_GT(lines.size(), 50u);
    std::ofstream(dir / "cornell_blocks.mtl") << slurp("scenes/cornell_blocks.mtl");
    // The file with its vertices scaled and, for z up, turned so that --up-axis z turns them back.
    auto variant = [&](const std::string& name, bool zUp, double scale) {
        std::ofstream out(dir / name);
        for (const std::string& line : lines) {
            std::istringstream fields(line);
            std::string kind;
            double x, y, z;
            if (!(fields >> kind) || kind != "v" || !(fields >> x >> y >> z)) {
                out << line << "\n";
                continue;
            }
            char v[128];
            if (zUp) std::snprintf(v, sizeof(v), "v %.17g %.17g %.17g\n", x * scale, -z * scale, y * scale);
            else std::snprintf(v, sizeof(v), "v %.17g %.17g %.17g\n", x * scale, y * scale, z * scale);
            out << v;
        }
    };
    const std::string options = " --integrator ao --spp 2 --size 40x30 --smooth off";
    std::vector<float> referencePrim, referenceAo;       // the first render's (the grid's)
    std::map<std::string, std::vector<float>> accelPrim;  // each accelerator's first
    int renders = 0;
    for (const bool zUp : {false, true})
        for (const double scale : {1.0, 1024.0, 0x1p40}) {
            const std::string name = std::string(zUp ? "z" : "y") + std::to_string(int(std::log2(scale)));
            variant(name + ".obj", zUp, scale);
            const std::string up = zUp ? " --up-axis z" : "";
            for (const char* accel : {"grid", "bvh"}) {
                const std::string packed = path(name + "_" + accel + ".gpscene");
                ASSERT_EQ(gpurt("pack " + path(name + ".obj") + " --accel " + accel + " -o " + packed).code, 0);
                for (const std::string& file : {path(name + ".obj"), packed}) {
                    SCOPED_TRACE(file + up + " --accel " + accel);
                    const Result r = gpurt("render " + file + up + " --accel " + accel + options + " -o " +
                                           path("x.png") + " --aov prim=" + path("prim.pfm") + " --aov color=" +
                                           path("ao.pfm") + " --stats=json");
                    ASSERT_EQ(r.code, 0) << r.err;
                    EXPECT_NE(r.out.find(std::string("\"accel\":\"") + accel + "\""), std::string::npos) << r.out;
                    int w = 0, h = 0, channels = 0;
                    const std::vector<float> prim = gpurt::readPfm(path("prim.pfm"), w, h, channels);
                    const std::vector<float> ao = gpurt::readPfm(path("ao.pfm"), w, h, channels);
                    ++renders;
                    // Each accelerator hits the same triangles whatever the file, packing, up axis and scale.
                    if (!accelPrim.count(accel)) accelPrim[accel] = prim;
                    EXPECT_EQ(prim, accelPrim[accel]);
                    if (referencePrim.empty()) {
                        referencePrim = prim;
                        referenceAo = ao;
                        size_t hits = 0;
                        for (float p : prim) hits += p >= 0.0f;
                        ASSERT_GT(hits, prim.size() / 2);  // the box fills the picture
                        continue;
                    }
                    ASSERT_EQ(prim.size(), referencePrim.size());
                    size_t samePrim = 0;
                    double aoDifference = 0.0;
                    for (size_t i = 0; i < prim.size(); ++i) samePrim += prim[i] == referencePrim[i];
                    for (size_t i = 0; i < ao.size(); ++i) aoDifference += std::abs(ao[i] - referenceAo[i]);
                    // Across accelerators, a ray through a shared edge may take either triangle: a few
                    // pixels of the box's many edges at this size.
                    EXPECT_GE(samePrim, prim.size() - prim.size() / 50);
                    EXPECT_LT(aoDifference / double(ao.size()), 0.01);
                }
            }
        }
    EXPECT_EQ(renders, 24);
}

}  // namespace
