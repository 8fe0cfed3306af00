// What a person running long renders relies on, end to end on both backends: progress lines on
// stderr (parseable, rising, ending at 1) only when asked for or on a terminal; --time-limit (at
// least one sample; the image is the --spp image of the count it reports); --up-axis (a Z-up mesh
// turned up is the mesh turned by hand); help that names every format and the new options.
#include "CliRunner.h"

#include <glm/glm.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace gpurt::test {
namespace {

const char* const kBackends[] = {"gl", "cpu"};

// The fractions of the progress lines of `err`; fails on a stderr line that is not one.
std::vector<double> progressFractions(const std::string& err) {
    static const std::regex line(R"(progress ([01]\.[0-9]{2}) eta ([0-9]+\.[0-9])s)");
    std::vector<double> fractions;
    std::istringstream in(err);
    for (std::string text; std::getline(in, text);) {
        std::smatch m;
        EXPECT_TRUE(std::regex_match(text, m, line)) << "not a progress line: '" << text << "'";
        if (!m.empty()) fractions.push_back(std::stod(m[1].str()));
    }
    return fractions;
}

void expectRisingToOne(const std::vector<double>& fractions, const std::string& what) {
    ASSERT_FALSE(fractions.empty()) << what;
    for (size_t i = 1; i < fractions.size(); ++i) EXPECT_LT(fractions[i - 1], fractions[i]) << what << " line " << i;
    EXPECT_EQ(fractions.back(), 1.0) << what;
    EXPECT_GE(fractions.front(), 0.0) << what;
}

class DailyUse : public GpurtTest {
  protected:
    // The stats JSON object of a render's stdout.
    static nlohmann::json stats(const GpurtRun& run) { return nlohmann::json::parse(run.out); }
};

TEST_F(DailyUse, ProgressLinesParseRiseAndEndAtOne) {
    for (const char* backend : kBackends) {
        SCOPED_TRACE(backend);
        const GpurtRun run = gpurt(std::string("render scenes/cornell.json --size 32x24 --spp 8 --progress --backend ") +
                                   backend + " -o " + quoted("p.png"));
        ASSERT_EQ(run.code, 0) << run.err;
        const std::vector<double> fractions = progressFractions(run.err);
        expectRisingToOne(fractions, run.err);
        // gl reports each of the 8 samples, cpu each of the 24 rows: at least every other 5% step
        // of a sample's 12.5% is passed.
        EXPECT_GE(fractions.size(), 8u) << run.err;
    }
}

// One line at the end of each frame: k / frames, rounded to two decimals.
TEST_F(DailyUse, ProgressHasALinePerFrame) {
    const int frames = 3;
    const GpurtRun run = gpurt("render scenes/cornell_flythrough.json --size 16x12 --frames 0:" +
                               std::to_string(frames - 1) + " --progress -o " + quoted("f%04d.png"));
    ASSERT_EQ(run.code, 0) << run.err;
    const std::vector<double> fractions = progressFractions(run.err);
    expectRisingToOne(fractions, run.err);
    for (int k = 1; k <= frames; ++k) {
        const double expected = std::round(double(k) / frames * 100.0) / 100.0;
        EXPECT_NE(std::find(fractions.begin(), fractions.end(), expected), fractions.end())
            << "no line for frame " << k << ": " << run.err;
    }
}

TEST_F(DailyUse, PackProgressEndsAtOne) {
    const GpurtRun run = gpurt("pack scenes/cornell.json --progress -o " + quoted("c.gpscene"));
    ASSERT_EQ(run.code, 0) << run.err;
    expectRisingToOne(progressFractions(run.err), run.err);
}

TEST_F(DailyUse, NoProgressWithoutATerminalOrTheOption) {
    for (const char* backend : kBackends) {
        const GpurtRun run = gpurt(std::string("render scenes/cornell.json --size 16x12 --spp 4 --backend ") +
                                   backend + " -o " + quoted("p.png"));
        ASSERT_EQ(run.code, 0) << run.err;
        EXPECT_EQ(run.err, "") << backend;
    }
    const GpurtRun pack = gpurt("pack scenes/cornell.json -o " + quoted("c.gpscene"));
    ASSERT_EQ(pack.code, 0) << pack.err;
    EXPECT_EQ(pack.err, "");
}

// On a terminal (a pseudo-terminal from util-linux's script), the bar redraws itself with \r and
// ends its line at 100%; --quiet turns it off.
TEST_F(DailyUse, ATerminalShowsTheBarAndQuietHidesIt) {
    ASSERT_EQ(std::system("command -v script >/dev/null"), 0) << "script (util-linux) is not installed";
    // What gpurt writes to stderr when that is a terminal: script copies the terminal's output
    // to its stdout (gpurt's own stdout goes to /dev/null). script runs without the sanitizer
    // build's preloads, gpurt inside it with them (without the driver preloaded, LeakSanitizer
    // reports the unloaded driver's memory and gpurt exits 1).
    auto onTerminal = [&](const std::string& options) {
        const std::string render = gpurtKeepingPreloads(dir) + " render scenes/cornell.json --size 16x12 --spp 4 -o " +
                                   path("p.png") + options + " 2>&1 >/dev/null";
        const std::string command = foreign("script -qec " + shellQuote(render) + " /dev/null </dev/null >" +
                                            shellQuote(path("terminal.txt")));
        EXPECT_EQ(std::system(command.c_str()), 0) << command;
        const std::string text = readFile(dir / "terminal.txt");
        fs::remove(dir / "terminal.txt");
        return text;
    };
    const std::string bar = onTerminal("");
    EXPECT_NE(bar.find("\r["), std::string::npos) << bar;
    EXPECT_NE(bar.find("100%"), std::string::npos) << bar;
    const std::string quiet = onTerminal(" --quiet");
    EXPECT_EQ(quiet.find("\r["), std::string::npos) << quiet;
}

// --quiet says a warning once however often it recurs (its line number aside); without it every
// occurrence is said.
TEST_F(DailyUse, QuietSaysEachWarningOnce) {
    write("odd.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nfoo 1\nfoo 2\nfoo 3\nbar 1\nf 1 2 3\n");
    auto warnings = [](const std::string& err, const std::string& what) {
        size_t n = 0;
        for (size_t at = err.find(what); at != std::string::npos; at = err.find(what, at + 1)) ++n;
        return n;
    };
    const std::string render = "render " + quoted("odd.obj") + " --size 8x8 -o " + quoted("o.png");
    const GpurtRun loud = gpurt(render);
    ASSERT_EQ(loud.code, 0) << loud.err;
    EXPECT_EQ(warnings(loud.err, "unknown statement 'foo'"), 3u) << loud.err;
    EXPECT_EQ(warnings(loud.err, "unknown statement 'bar'"), 1u) << loud.err;
    const GpurtRun quiet = gpurt(render + " --quiet");
    ASSERT_EQ(quiet.code, 0) << quiet.err;
    EXPECT_EQ(warnings(quiet.err, "unknown statement 'foo'"), 1u) << quiet.err;
    EXPECT_EQ(warnings(quiet.err, "unknown statement 'bar'"), 1u) << quiet.err;
}

TEST_F(DailyUse, TimeLimitFarBelowOneSampleTakesOne) {
    for (const char* backend : kBackends) {
        SCOPED_TRACE(backend);
        const std::string common = std::string("render scenes/cornell.json --size 24x16 --backend ") + backend;
        const GpurtRun timed = gpurt(common + " --time-limit 0.000001 --stats=json -o " + quoted("t.png"));
        ASSERT_EQ(timed.code, 0) << timed.err;
        EXPECT_EQ(stats(timed)["spp"], 1);
        EXPECT_NE(timed.err.find(" 1 samples a pixel"), std::string::npos) << timed.err;
        ASSERT_EQ(gpurt(common + " --spp 1 -o " + quoted("s.png")).code, 0);
        EXPECT_EQ(readFile(dir / "t.png"), readFile(dir / "s.png"));
    }
}

// The count is within its bounds (at least one, at most --spp), and the image and its linear
// colour are those of --spp with that count, byte for byte.
TEST_F(DailyUse, TimeLimitImageIsTheSppImageOfItsCount) {
    for (const char* backend : kBackends) {
        for (const char* integrator : {"whitted", "path"}) {
            SCOPED_TRACE(std::string(backend) + " " + integrator);
            const std::string common = std::string("render scenes/cornell.json --size 24x16 --backend ") + backend +
                                       " --integrator " + integrator;
            const GpurtRun timed = gpurt(common + " --time-limit 30 --spp 6 --stats=json --progress -o " +
                                         quoted("t.png") + " --aov color=" + quoted("t.pfm"));
            ASSERT_EQ(timed.code, 0) << timed.err;
            const int spp = stats(timed)["spp"];
            EXPECT_GE(spp, 1);
            EXPECT_LE(spp, 6);
            EXPECT_NE(timed.err.find(" " + std::to_string(spp) + " samples a pixel"), std::string::npos) << timed.err;
            // Progress over both renders still rises to 1 (the count line aside).
            std::string lines;
            std::istringstream in(timed.err);
            for (std::string text; std::getline(in, text);)
                if (text.rfind("progress ", 0) == 0) lines += text + "\n";
            expectRisingToOne(progressFractions(lines), timed.err);
            ASSERT_EQ(gpurt(common + " --spp " + std::to_string(spp) + " -o " + quoted("s.png") + " --aov color=" +
                            quoted("s.pfm")).code, 0);
            EXPECT_EQ(readFile(dir / "t.png"), readFile(dir / "s.png"));
            EXPECT_EQ(readFile(dir / "t.pfm"), readFile(dir / "s.pfm"));
        }
    }
}

TEST_F(DailyUse, TimeLimitRefusesBadValuesAndTiles) {
    const std::string render = "render scenes/cornell.json --size 8x8 -o " + quoted("t.png");
    for (const char* bad : {"0", "-1", "abc", "inf"}) expectRefused(render + " --time-limit " + bad, {"--time-limit"});
    expectRefused(render + " --time-limit 5 --tile 0/2", {"--time-limit", "--tile"});
}

// A mesh whose up axis is z, with nothing symmetric: a tall box along z, a flag along +x, a spike
// along +y (a Z-up file's "forward").
std::vector<glm::vec3> zUpMesh() {
    std::vector<glm::vec3> v;
    auto quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) { v.insert(v.end(), {a, b, c, a, c, d}); };
    const float w = 0.3f, h = 2.0f;
    quad({-w, -w, 0}, {w, -w, 0}, {w, -w, h}, {-w, -w, h});
    quad({w, -w, 0}, {w, w, 0}, {w, w, h}, {w, -w, h});
    quad({w, w, 0}, {-w, w, 0}, {-w, w, h}, {w, w, h});
    quad({-w, w, 0}, {-w, -w, 0}, {-w, -w, h}, {-w, w, h});
    quad({-w, -w, h}, {w, -w, h}, {w, w, h}, {-w, w, h});
    quad({w, 0, 1.5f}, {1.2f, 0, 1.5f}, {1.2f, 0, 1.9f}, {w, 0, 1.9f});  // the flag, +x
    v.insert(v.end(), {glm::vec3(-0.1f, w, 0.2f), glm::vec3(0.1f, w, 0.2f), glm::vec3(0, 0.9f, 0.3f)});  // spike, +y
    return v;
}

std::string objText(const std::vector<glm::vec3>& vertices) {
    std::string text;
    char line[128];
    for (const glm::vec3& p : vertices) {
        std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", double(p.x), double(p.y), double(p.z));
        text += line;
    }
    for (size_t i = 0; i < vertices.size(); i += 3)
        text += "f " + std::to_string(i + 1) + " " + std::to_string(i + 2) + " " + std::to_string(i + 3) + "\n";
    return text;
}

// --up-axis z renders a Z-up mesh as the same mesh turned by hand, (x, y, z) -> (x, z, -y), with
// the default camera and with a given one; a JSON scene's "up_axis" does the same, and so does
// its packed file.
TEST_F(DailyUse, UpAxisZIsTheMeshTurnedByHand) {
    const std::vector<glm::vec3> zUp = zUpMesh();
    std::vector<glm::vec3> turned;
    for (const glm::vec3& p : zUp) turned.push_back({p.x, p.z, -p.y});
    write("zup.obj", objText(zUp));
    write("turned.obj", objText(turned));
    write("zup.json", "{\"up_axis\": \"z\", \"meshes\": [{\"file\": \"zup.obj\"}]}");
    ASSERT_EQ(gpurt("pack " + quoted("zup.json") + " -o " + quoted("zup.gpscene")).code, 0);
    const std::string aovs = " --aov depth=", prim = " --aov prim=";
    for (const char* backend : kBackends) {
        for (const std::string& camera : {std::string(), std::string(" --eye 3,2.5,4 --target 0,1,0 --fovy 40")}) {
            SCOPED_TRACE(std::string(backend) + camera);
            const std::string common = std::string(" --size 48x40 --spp 2 --backend ") + backend + camera;
            auto render = [&](const std::string& scene, const std::string& name) {
                const GpurtRun run = gpurt("render " + scene + common + " -o " + quoted(name + ".png") + aovs +
                                           quoted(name + ".d.pfm") + prim + quoted(name + ".p.pfm"));
                EXPECT_EQ(run.code, 0) << scene << ": " << run.err;
            };
            render(quoted("turned.obj"), "expected");
            render(quoted("zup.obj") + " --up-axis z", "option");
            render(quoted("zup.json"), "json");
            render(quoted("zup.gpscene"), "packed");
            render(quoted("zup.obj"), "unturned");
            for (const char* name : {"option", "json", "packed"})
                for (const char* ext : {".png", ".d.pfm", ".p.pfm"})
                    EXPECT_EQ(readFile(dir / (std::string(name) + ext)), readFile(dir / (std::string("expected") + ext)))
                        << name << ext;
            // And the axis matters: the file as it is, unturned, is another picture.
            EXPECT_NE(readFile(dir / "unturned.p.pfm"), readFile(dir / "expected.p.pfm"));
        }
    }
    // --up-axis y on the JSON scene overrides its "up_axis": the file as it is.
    ASSERT_EQ(gpurt("render " + quoted("zup.json") + " --up-axis y --size 48x40 -o " + quoted("y.png")).code, 0);
    ASSERT_EQ(gpurt("render " + quoted("zup.obj") + " --size 48x40 -o " + quoted("plain.png")).code, 0);
    EXPECT_EQ(readFile(dir / "y.png"), readFile(dir / "plain.png"));
}

// Each of the six axes turns the axis it names up: the box's top (the triangles at the largest
// coordinate along that axis) faces the default camera's top rows, whichever axis it is along.
TEST_F(DailyUse, EveryUpAxisTurnsItsAxisUp) {
    const std::vector<glm::vec3> zUp = zUpMesh();
    write("zup.obj", objText(zUp));
    const std::pair<const char*, glm::mat3> axes[] = {
        // Columns: where the file's x, y and z go (the file's axis "up" goes to +y).
        {"z", glm::mat3(1, 0, 0, 0, 0, -1, 0, 1, 0)},  {"-z", glm::mat3(1, 0, 0, 0, 0, 1, 0, -1, 0)},
        {"y", glm::mat3(1.0f)},                         {"-y", glm::mat3(1, 0, 0, 0, -1, 0, 0, 0, -1)},
        {"x", glm::mat3(0, 1, 0, -1, 0, 0, 0, 0, 1)},  {"-x", glm::mat3(0, -1, 0, 1, 0, 0, 0, 0, 1)},
    };
    for (const auto& [name, m] : axes) {
        SCOPED_TRACE(name);
        // The matrix is a rotation taking the named axis to +y.
        EXPECT_NEAR(glm::determinant(m), 1.0f, 0.0f);
        glm::vec3 axis(0.0f);
        axis[std::string(name).back() - 'x'] = name[0] == '-' ? -1.0f : 1.0f;
        EXPECT_EQ(m * axis, glm::vec3(0, 1, 0));
        // Turned by the matrix's one entry a row (no 0 * y terms: -y keeps a -0 as the program's does).
        std::vector<glm::vec3> turned;
        for (const glm::vec3& p : zUp) {
            glm::vec3 q(0.0f);
            for (int row = 0; row < 3; ++row)
                for (int column = 0; column < 3; ++column)
                    if (m[column][row] != 0.0f) q[row] = m[column][row] == 1.0f ? p[column] : -p[column];
            turned.push_back(q);
        }
        write("turned.obj", objText(turned));
        ASSERT_EQ(gpurt("render " + quoted("turned.obj") + " --size 32x32 -o " + quoted("e.png") + " --aov prim=" +
                        quoted("e.pfm")).code, 0);
        ASSERT_EQ(gpurt("render " + quoted("zup.obj") + " --up-axis " + name + " --size 32x32 -o " + quoted("o.png") +
                        " --aov prim=" + quoted("o.pfm")).code, 0) << name;
        EXPECT_EQ(readFile(dir / "o.pfm"), readFile(dir / "e.pfm"));
        EXPECT_EQ(readFile(dir / "o.png"), readFile(dir / "e.png"));
    }
    write("bad.json", "{\"up_axis\": \"w\", \"meshes\": []}");
    expectRefused("render " + quoted("zup.obj") + " --up-axis w -o " + quoted("o.png"), {"--up-axis", "'w'"});
    expectRefused("render " + quoted("bad.json") + " -o " + quoted("o.png"), {"bad.json", "up_axis"});
}

// --help names every scene format, both picture formats, the AOV formats and the options of the
// daily-use issue; bench and view name the scene formats too.
TEST_F(DailyUse, HelpNamesEveryFormatAndOption) {
    const GpurtRun render = gpurt("render --help");
    ASSERT_EQ(render.code, 0) << render.err;
    for (const char* word : {".obj", ".json", ".gltf", ".glb", ".ply", ".gpscene", ".png", ".exr", ".pfm",
                             "--time-limit", "--progress", "--quiet", "--up-axis", "--tile", "--frames", "--aov"})
        EXPECT_NE(render.out.find(word), std::string::npos) << word << " not in render --help";
    for (const char* command : {"view", "bench", "pack"}) {
        const GpurtRun help = gpurt(std::string(command) + " --help");
        ASSERT_EQ(help.code, 0) << help.err;
        for (const char* word : {".gltf", ".glb", ".ply", ".gpscene", "--up-axis"})
            EXPECT_NE(help.out.find(word), std::string::npos) << word << " not in " << command << " --help";
    }
}

}  // namespace
}  // namespace gpurt::test
