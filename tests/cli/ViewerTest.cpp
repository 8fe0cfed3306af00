// `gpurt view` in a real window: the test starts its own X server (Xvfb, stopped by its process
// id afterwards), runs the viewer on Mesa's llvmpipe through GLX, and drives it with real input
// from xdotool (XTEST): a drag orbits, a key flies, a display-mode key shows the AOV, a resize
// keeps rendering, Esc closes. Each picture is checked against `gpurt render` with the camera the
// viewer printed (at most 1 level of 255 apart on 99.9% of the pixels). An X server or xdotool
// that cannot start fails the test with the reason; nothing is skipped.
#include "CliRunner.h"
#include "PngPixels.h"

#include "image/ImageIO.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <thread>

namespace gpurt::test {
namespace {

using namespace std::chrono_literals;

// The shell command that runs xdotool with `arguments` on `display` (without the sanitizer build's
// preloads, which are gpurt's).
std::string xdotoolCommand(const std::string& display, const std::string& arguments) {
    return "env -u LD_PRELOAD -u ASAN_OPTIONS -u LSAN_OPTIONS DISPLAY=" + display + " xdotool " + arguments;
}

// One X server for the test suite.
class XServer {
  public:
    static XServer& get() {
        static XServer server;
        return server;
    }
    const std::string& display() const { return display_; }
    const std::string& failure() const { return failure_; }
    // What a test that could not reach the display reports: whether the server still runs, its
    // log, and the X sockets there are (a display another server answers on looks the same).
    std::string state() {
        std::string sockets;
        std::error_code error;
        for (const auto& entry : fs::directory_iterator("/tmp/.X11-unix", error)) sockets += " " + entry.path().filename().string();
        return "Xvfb on " + display_ + (server_ && server_->running() ? " is running" : " has exited") +
               " (it served a client at the " + std::to_string(probes_) + ". try before the test began)" +
               "; /tmp/.X11-unix:" + (sockets.empty() ? " (none)" : sockets) + "; its log: " + readFile(log_);
    }

  private:
    // Xvfb chooses a free display itself (-displayfd): test processes run side by side. -noreset:
    // an X server resets when its last client leaves, and a client that connects then may be
    // refused ("Failed to open display"): the probe below leaving, then the viewer connecting, failed
    // 1 run in 32 of a loop over one viewer test here (stop 44), none in 100 with -noreset.
    XServer() {
        const std::string stem = (fs::temp_directory_path() / ("gpurt-xvfb-" + std::to_string(getpid()))).string();
        const fs::path number = stem + ".display", log = stem + ".log";
        log_ = log;
        server_ = std::make_unique<Background>(
            std::vector<std::string>{"/usr/bin/Xvfb", "-displayfd", "1", "-screen", "0", "1024x768x24", "-nolisten", "tcp", "-noreset"},
            number, log, "", false);
        std::string text;
        // Polled until Xvfb writes its display number, at most a minute (a loaded machine).
        const auto end = std::chrono::steady_clock::now() + 60s;
        while (server_->running() && std::chrono::steady_clock::now() < end) {
            text = readFile(number);
            if (!text.empty() && text.back() == '\n') break;
            std::this_thread::sleep_for(20ms);
        }
        if (!server_->started() || !server_->running() || text.empty() || text.back() != '\n')
            failure_ = "Xvfb did not start (is the xvfb package installed?): " + readFile(log);
        else
            display_ = ":" + text.substr(0, text.size() - 1);
        fs::remove(number);
        // Then until a client is served (a viewer that could not open the display the server had
        // just reported failed some runs of stop 42 and 43; xdotool opened it right after).
        while (failure_.empty() && std::chrono::steady_clock::now() < end) {
            ++probes_;
            if (std::system((xdotoolCommand(display_, "getdisplaygeometry") + " >/dev/null 2>&1").c_str()) == 0) break;
            std::this_thread::sleep_for(20ms);
        }
    }
    ~XServer() {
        server_.reset();
        fs::remove(log_);
    }
    std::string display_, failure_;
    fs::path log_;
    int probes_ = 0;
    std::unique_ptr<Background> server_;
};

// Runs `command` (an xdotool call) on the test's display; returns its stdout.
std::string xdotool(const std::string& arguments) {
    const std::string command = xdotoolCommand(XServer::get().display(), arguments) + " 2>&1";
    std::string out;
    if (FILE* pipe = popen(command.c_str(), "r")) {
        char buffer[256];
        while (fgets(buffer, sizeof buffer, pipe)) out += buffer;
        pclose(pipe);
    }
    return out;
}

class Viewer : public GpurtTest {
  protected:
    void SetUp() override {
        GpurtTest::SetUp();
        ASSERT_TRUE(XServer::get().failure().empty()) << XServer::get().failure();
        ASSERT_EQ(std::system("command -v xdotool >/dev/null"), 0) << "xdotool is not installed";
    }
    // gpurt view ARGS in the background on the test's display.
    std::unique_ptr<Background> view(const std::string& scene, const std::vector<std::string>& options) {
        std::vector<std::string> argv = {GPURT_BINARY, "view", scene};
        argv.insert(argv.end(), options.begin(), options.end());
        return std::make_unique<Background>(argv, dir / "view.out", dir / "view.err", XServer::get().display());
    }
    // The id of the viewer's window, once it is mapped and has shown a frame (its title then
    // carries the frame rate and the frame count); polled for at most two minutes, or until the
    // viewer exits.
    std::string window(Background& viewer) {
        const auto end = std::chrono::steady_clock::now() + 120s;
        while (std::chrono::steady_clock::now() < end && viewer.running()) {
            const std::string out = xdotool("search --onlyvisible --name '^gpurt view: '");
            if (!out.empty() && std::isdigit(static_cast<unsigned char>(out[0]))) return out.substr(0, out.find('\n'));
            std::this_thread::sleep_for(50ms);
        }
        return {};
    }
    // Why window() found none: the viewer's errors, the X server's state, and what xdotool makes
    // of the display.
    std::string noWindow() {
        return "no viewer window appeared: " + readFile(dir / "view.err") + "; " + XServer::get().state() +
               "; xdotool getdisplaygeometry: " + xdotool("getdisplaygeometry");
    }
    // The frame count in the window's title ("..., frame N"), or -1.
    static int titleFrame(const std::string& id) {
        const std::string title = xdotool("getwindowname " + id);
        const size_t at = title.rfind("frame ");
        return at == std::string::npos ? -1 : std::atoi(title.c_str() + at + 6);
    }
    // Waits (at most a minute) until the viewer has handled every event sent before the call and
    // rendered a frame after them: the title's frame count changes twice (the title is set at
    // most twice a second, so the first change may report a frame that began before the events;
    // every frame counted by the second began after the first change, so after the events).
    bool framesAfterEvents(const std::string& id) {
        const auto end = std::chrono::steady_clock::now() + 60s;
        int changes = 0, last = titleFrame(id);
        while (changes < 2 && std::chrono::steady_clock::now() < end) {
            std::this_thread::sleep_for(20ms);
            const int now = titleFrame(id);
            if (now > last) ++changes;
            last = std::max(last, now);
        }
        return changes >= 2;
    }
    // The camera the viewer printed as render options (its last stdout line).
    std::string printedCamera() const {
        std::string out = readFile(dir / "view.out");
        while (!out.empty() && out.back() == '\n') out.pop_back();
        return out.substr(out.rfind('\n') + 1);
    }
    std::vector<unsigned char> png(const std::string& name, int& w, int& h) const {
        return pngPixels(readFile(dir / name), w, h);
    }
    // At most 1 level apart on 99.9% of the pixels.
    void expectSame(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b, const std::string& what) {
        ASSERT_EQ(a.size(), b.size()) << what;
        ASSERT_FALSE(a.empty()) << what;
        size_t close = 0;
        for (size_t i = 0; i < a.size(); i += 3) {
            int worst = 0;
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(a[i + c]) - int(b[i + c])));
            close += worst <= 1;
        }
        EXPECT_GE(double(close) / double(a.size() / 3), 0.999) << what;
    }
    void expectRenderMatches(const std::string& scene, const std::string& camera, const std::string& options,
                             const std::string& screenshot) {
        const GpurtRun r = gpurt("render " + shellQuote(scene) + " -o " + quoted("render.png") + " " + camera + " " + options);
        ASSERT_EQ(r.code, 0) << r.err;
        int w0 = 0, h0 = 0, w1 = 0, h1 = 0;
        const auto shot = png(screenshot, w0, h0), rendered = png("render.png", w1, h1);
        EXPECT_EQ(w0, w1);
        EXPECT_EQ(h0, h1);
        expectSame(shot, rendered, "screenshot " + screenshot + " against render " + camera + " " + options);
    }
};

TEST_F(GpurtTest, ViewWithoutADisplayExits2) {
    const GpurtRun run = gpurt("view scenes/boxes.json", "env -u DISPLAY");
    EXPECT_EQ(run.code, 2) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_NE(run.err.find("display"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("gpurt render"), std::string::npos) << run.err;
    // Bad input is refused before any window is asked for.
    expectRefused("view " + quoted("missing.obj"), {"missing.obj"});
    write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expectRefused("view " + quoted("tri.obj") + " --spp 0", {"--spp"});
}

// K frames of a still camera are K samples: the screenshot is `gpurt render --spp K`.
TEST_F(Viewer, FramesAndScreenshotAreTheRenderWithAsManySamples) {
    auto v = view("scenes/boxes.json", {"--size", "160x120", "--frames", "4", "--screenshot", path("shot.png")});
    ASSERT_TRUE(v->started());
    ASSERT_EQ(v->wait(120s), 0) << readFile(dir / "view.err");
    const std::string camera = printedCamera();
    EXPECT_NE(camera.find("--eye "), std::string::npos) << camera;
    expectRenderMatches("scenes/boxes.json", camera, "--spp 4", "shot.png");
}

// The path integrator refines progressively the same way and shows the denoised picture: K frames
// are `gpurt render --integrator path --spp K --denoise`; with --no-denoise the raw mean.
TEST_F(Viewer, PathTracedFramesAreTheRenderWithAsManySamples) {
    auto v = view("scenes/cornell.json", {"--size", "96x96", "--integrator", "path", "--frames", "6", "--screenshot",
                                          path("shot.png")});
    ASSERT_TRUE(v->started());
    ASSERT_EQ(v->wait(120s), 0) << readFile(dir / "view.err");
    expectRenderMatches("scenes/cornell.json", printedCamera(), "--integrator path --spp 6 --denoise", "shot.png");
    auto raw = view("scenes/cornell.json", {"--size", "96x96", "--integrator", "path", "--frames", "6", "--no-denoise",
                                            "--screenshot", path("raw.png")});
    ASSERT_EQ(raw->wait(120s), 0) << readFile(dir / "view.err");
    expectRenderMatches("scenes/cornell.json", printedCamera(), "--integrator path --spp 6", "raw.png");
}

// Key N turns the denoiser off (and on again): after it the window shows the raw mean, and P
// writes the screenshot (what the window shows).
TEST_F(Viewer, KeyNTogglesTheDenoiser) {
    auto v = view("scenes/cornell.json", {"--size", "96x96", "--integrator", "path", "--spp", "4", "--screenshot",
                                          path("shot.png")});
    const std::string id = window(*v);
    ASSERT_FALSE(id.empty()) << noWindow();
    xdotool("windowfocus --sync " + id);
    xdotool("key n");
    ASSERT_TRUE(framesAfterEvents(id)) << "the viewer rendered no frames: " << readFile(dir / "view.err");
    xdotool("key Escape");
    ASSERT_EQ(v->wait(60s), 0) << readFile(dir / "view.err");
    const std::string camera = printedCamera();
    expectRenderMatches("scenes/cornell.json", camera, "--integrator path --spp 4", "shot.png");
}

// Adaptive sampling in the viewer: its sums stop refining the pixels that converged, in the same
// rounds as render, so K frames are `gpurt render --spp K` with the same threshold.
TEST_F(Viewer, AdaptiveFramesAreTheAdaptiveRender) {
    const std::vector<std::string> adaptive = {"--integrator", "path", "--spp", "48", "--noise-threshold", "0.05",
                                               "--min-spp", "16"};
    std::vector<std::string> args = {"--size", "96x96", "--frames", "48", "--screenshot", path("shot.png")};
    args.insert(args.end(), adaptive.begin(), adaptive.end());
    auto v = view("scenes/cornell_blocks.json", args);
    ASSERT_TRUE(v->started());
    ASSERT_EQ(v->wait(120s), 0) << readFile(dir / "view.err");
    expectRenderMatches("scenes/cornell_blocks.json", printedCamera(),
                        "--integrator path --spp 48 --noise-threshold 0.05 --min-spp 16 --denoise", "shot.png");
}

// F focuses on the surface under the mouse: a wall facing the camera 5 units along its view is
// sharp after F, and the camera printed on closing says so (--focus-distance 5, the lens kept);
// `gpurt render` with it is the picture the window showed.
TEST_F(Viewer, KeyFFocusesOnTheSurfaceUnderTheMouse) {
    const std::string floor = std::filesystem::absolute("scenes/floor.obj").string();
    const std::string scene = path("wall.json");
    std::ofstream(scene) << (R"({"meshes": [{"file": ")" + floor + R"(", "transform": {"translate": [0, 0, -3],
        "rotate": [90, 0, 0], "scale": 5}}], "camera": {"eye": [0, 0, 2], "target": [0, 0, 0], "lens_radius": 0.2}})");
    auto v = view(scene, {"--size", "120x90", "--spp", "2", "--screenshot", path("shot.png")});
    const std::string id = window(*v);
    ASSERT_FALSE(id.empty()) << noWindow();
    xdotool("mousemove --window " + id + " 70 40");
    ASSERT_TRUE(framesAfterEvents(id)) << "the viewer rendered no frames: " << readFile(dir / "view.err");
    xdotool("windowfocus --sync " + id);
    xdotool("key f");
    ASSERT_TRUE(framesAfterEvents(id)) << "the viewer rendered no frames: " << readFile(dir / "view.err");
    xdotool("key Escape");
    ASSERT_EQ(v->wait(60s), 0) << readFile(dir / "view.err");
    const std::string camera = printedCamera();
    const size_t at = camera.find("--focus-distance ");
    ASSERT_NE(at, std::string::npos) << camera;
    EXPECT_NEAR(std::stod(camera.substr(at + 17)), 5.0, 1e-4) << camera;
    EXPECT_NE(camera.find("--lens-radius 0.2"), std::string::npos) << camera;
    expectRenderMatches(scene, camera, "--spp 2", "shot.png");
}

// A drag and a key move the camera; `gpurt render` with the camera printed on closing is the
// picture the window showed; Esc closes with exit 0.
TEST_F(Viewer, MouseDragAndKeysMoveTheCamera) {
    auto still = view("scenes/boxes.json", {"--size", "200x150", "--frames", "1"});
    ASSERT_EQ(still->wait(120s), 0) << readFile(dir / "view.err");
    const std::string initial = printedCamera();
    auto v = view("scenes/boxes.json", {"--size", "200x150", "--spp", "1", "--screenshot", path("shot.png")});
    const std::string id = window(*v);
    ASSERT_FALSE(id.empty()) << noWindow();
    // X delivers the events in order; each group is waited for by the frames rendered after it.
    xdotool("mousemove --window " + id + " 100 75");
    ASSERT_TRUE(framesAfterEvents(id)) << "the viewer rendered no frames: " << readFile(dir / "view.err");
    xdotool("mousedown 1");
    for (int step = 1; step <= 8; ++step)
        xdotool("mousemove --window " + id + " " + std::to_string(100 + 5 * step) + " " + std::to_string(75 + 2 * step));
    xdotool("mouseup 1");
    xdotool("windowfocus --sync " + id);
    xdotool("key w");
    ASSERT_TRUE(framesAfterEvents(id)) << "the viewer rendered no frames: " << readFile(dir / "view.err");
    xdotool("key Escape");
    ASSERT_EQ(v->wait(60s), 0) << "the viewer did not close on Esc: " << readFile(dir / "view.err");
    const std::string moved = printedCamera();
    EXPECT_NE(moved, initial) << "the drag and the key did not move the camera";
    expectRenderMatches("scenes/boxes.json", moved, "--spp 1", "shot.png");
}

// Key 3 shows the normal AOV (n * 0.5 + 0.5, black on a miss); a resized window renders at its
// new size.
TEST_F(Viewer, DisplayModeKeyShowsTheAovAndResizeKeepsRendering) {
    auto v = view("scenes/boxes.json", {"--size", "200x150", "--spp", "1", "--screenshot", path("shot.png")});
    const std::string id = window(*v);
    ASSERT_FALSE(id.empty()) << noWindow();
    xdotool("windowsize --sync " + id + " 240 180");
    xdotool("windowfocus --sync " + id);
    xdotool("key 3");
    ASSERT_TRUE(framesAfterEvents(id)) << "the viewer rendered no frames: " << readFile(dir / "view.err");
    xdotool("key Escape");
    ASSERT_EQ(v->wait(60s), 0) << readFile(dir / "view.err");
    const std::string camera = printedCamera();
    EXPECT_NE(camera.find("--size 240x180"), std::string::npos) << camera;
    const GpurtRun r = gpurt("render scenes/boxes.json -o " + quoted("render.png") + " " + camera +
                             " --aov normal=" + quoted("normal.pfm"));
    ASSERT_EQ(r.code, 0) << r.err;
    int w = 0, h = 0, channels = 0;
    const std::vector<float> normal = readPfm(path("normal.pfm"), w, h, channels);
    std::vector<unsigned char> expected(normal.size());
    for (size_t i = 0; i < normal.size(); i += 3) {
        const bool miss = normal[i] == 0.0f && normal[i + 1] == 0.0f && normal[i + 2] == 0.0f;
        for (int c = 0; c < 3; ++c)
            expected[i + c] = miss ? 0 : (unsigned char)std::lround((normal[i + c] * 0.5f + 0.5f) * 255.0f);
    }
    int sw = 0, sh = 0;
    const std::vector<unsigned char> shot = png("shot.png", sw, sh);
    EXPECT_EQ(sw, 240);
    EXPECT_EQ(sh, 180);
    expectSame(shot, expected, "normal display mode");
}

// --bench prints its JSON object and nothing else on stdout (`| jq .fps` works); the camera line
// goes to stderr.
TEST_F(Viewer, BenchPrintsOnlyItsJsonOnStdout) {
    auto v = view("scenes/boxes.json", {"--size", "64x48", "--bench"});
    ASSERT_TRUE(v->started());
    ASSERT_EQ(v->wait(300s), 0) << readFile(dir / "view.err");
    const std::string out = readFile(dir / "view.out");
    nlohmann::json bench;
    ASSERT_NO_THROW(bench = nlohmann::json::parse(out)) << out;
    ASSERT_TRUE(bench.is_object()) << out;
    EXPECT_GT(bench["fps"].get<double>(), 0.0) << out;
    EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
    EXPECT_NE(readFile(dir / "view.err").find("--eye "), std::string::npos) << readFile(dir / "view.err");
}

// The viewer honours --up-axis: a Z-up mesh turned up is the mesh turned by hand, (x, z, -y),
// rendered with the camera the viewer printed.
TEST_F(Viewer, UpAxisTurnsTheSceneAsRenderDoes) {
    const float v[][3] = {{-1, -0.5f, 0}, {1, -0.5f, 0}, {0, 0.5f, 2}, {1, -0.5f, 0}, {0.5f, 1, 0}, {0, 0.5f, 2}};
    std::string zUp, turned;
    for (const auto& p : v) {
        zUp += "v " + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + "\n";
        turned += "v " + std::to_string(p[0]) + " " + std::to_string(p[2]) + " " + std::to_string(-p[1]) + "\n";
    }
    write("zup.obj", zUp + "f 1 2 3\nf 4 5 6\n");
    write("turned.obj", turned + "f 1 2 3\nf 4 5 6\n");
    auto viewer = view(path("zup.obj"), {"--up-axis", "z", "--size", "96x72", "--frames", "2", "--screenshot",
                                         path("shot.png")});
    ASSERT_EQ(viewer->wait(120s), 0) << readFile(dir / "view.err");
    std::string camera = printedCamera();
    const std::string option = " --up-axis z";
    ASSERT_NE(camera.find(option), std::string::npos) << camera;
    expectRenderMatches(path("turned.obj"), camera.erase(camera.find(option), option.size()), "--spp 2", "shot.png");
}

}  // namespace
}  // namespace gpurt::test
