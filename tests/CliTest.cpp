// The gpurt program as users and scripts run it (CONTRACT.md): exit codes, one-line errors that
// name the file or option, no output on failure, real PNG and PFM files, statistics as JSON.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>
#include <algorithm>

namespace {

namespace fs = std::filesystem;

struct Result {
    int code = -1;
    std::string out, err;
};

// Runs `gpurt ARGS` from the project root; stdout and stderr are captured separately.
Result gpurt(const std::string& args, const std::string& env = "") {
    const fs::path dir = fs::temp_directory_path() / ("gpurt-cli-" + std::to_string(::getpid()));
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
        dir = fs::temp_directory_path() /
              ("gpurt-cli-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
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

TEST_F(Cli, StatsJsonHasTheContractFields) {
    const Result r = gpurt("render " + kTeapot + " -o " + path("out.png") + " --size 32x32 --stats=json");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    for (const char* key : {"width", "height", "triangles", "grid", "rays", "passes", "total_ms", "mrays_per_s"})
        EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j["width"], 32);
    EXPECT_EQ(j["triangles"], 992);
    EXPECT_EQ(j["rays"]["primary"], 32 * 32);
    EXPECT_EQ(j["grid"].size(), 3u);
    EXPECT_EQ(j["passes"]["raygen"]["calls"], 1);
    EXPECT_EQ(j["passes"]["raygen"]["fragments"], 32 * 32);
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
        if (b.contains("agreement")) EXPECT_GE(b["agreement"].get<double>(), 0.999) << b["backend"];
        if (b["backend"] == "embree") EXPECT_DOUBLE_EQ(b["ratio_to_embree"].get<double>(), 1.0);
    }
    EXPECT_TRUE(names.count("gl") && names.count("cpu"));
    for (const auto& b : j["backends"])
        if (b["backend"] == "gl") EXPECT_EQ(b["passes"]["trace"]["fragments"], 40 * 30);
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
