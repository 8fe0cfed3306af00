// Running the gpurt program from tests: a scratch folder per test, the program's exit status,
// stdout and stderr, and the files it left behind.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

namespace gpurt::test {

namespace fs = std::filesystem;

struct GpurtRun {
    int code = -1;  // exit status; -1 when the program did not exit normally (a signal)
    std::string out, err;
};

inline std::string readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// 'text' for the shell (single quotes inside closed and escaped).
inline std::string shellQuote(const std::string& text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// Programs that are not gpurt (bash, GNU parallel, Slurm's daemons) must not inherit the sanitizer
// build's preloads: LeakSanitizer would report their own leaks and fail them. `foreign(command)`
// runs a shell command without them; `gpurtKeepingPreloads(folder)` writes a script into folder
// that starts gpurt with them again, for such programs to run.
inline std::string foreign(const std::string& command) { return "env -u LD_PRELOAD " + command; }
inline std::string gpurtKeepingPreloads(const fs::path& folder) {
    const fs::path script = folder / "gpurt-preloaded";
    const char* preload = std::getenv("LD_PRELOAD");
    std::ofstream(script) << "#!/bin/sh\n"
                          << (preload ? "export LD_PRELOAD=" + shellQuote(preload) + "\n" : std::string())
                          << "exec " << shellQuote(GPURT_BINARY) << " \"$@\"\n";
    fs::permissions(script, fs::perms::owner_all, fs::perm_options::add);
    return script.string();
}

// A fresh folder for each test (named after it), removed afterwards; runs gpurt with its output
// captured in files outside that folder, so that the folder holds only what gpurt wrote.
class GpurtTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        const std::string name = std::string(info->test_suite_name()) + "-" + info->name();
        base_ = fs::temp_directory_path() / ("gpurt-" + std::to_string(::getpid()) + "-" + name);
        fs::remove_all(base_);
        dir = base_ / "files";
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(base_); }

    std::string path(const std::string& name) const { return (dir / name).string(); }
    std::string quoted(const std::string& name) const { return shellQuote(path(name)); }
    fs::path write(const std::string& name, const std::string& text) const {
        std::ofstream(dir / name, std::ios::binary) << text;
        return dir / name;
    }
    // The names of the files in the scratch folder.
    std::set<std::string> files() const {
        std::set<std::string> names;
        for (const auto& entry : fs::directory_iterator(dir))
            names.insert(entry.path().filename().string());
        return names;
    }

    // `gpurt ARGS` with environment assignments `env` ("VAR=value ...") in front.
    GpurtRun gpurt(const std::string& args, const std::string& env = "") const {
        const fs::path out = base_ / "stdout", err = base_ / "stderr";
        const std::string command = env + " " + GPURT_BINARY + " " + args + " >" +
                                    shellQuote(out.string()) + " 2>" + shellQuote(err.string());
        const int status = std::system(command.c_str());
        GpurtRun run;
        run.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        run.out = readFile(out);
        run.err = readFile(err);
        return run;
    }

    // The contract for bad input (CONTRACT.md, exit codes): `code` (1, or 2 for the
    // environment), exactly one line on stderr that contains every string of `mentions`, and
    // nothing written: the scratch folder holds the same files as before.
    void expectRefused(const std::string& args, std::initializer_list<std::string> mentions,
                       int code = 1) const {
        const std::set<std::string> before = files();
        const GpurtRun run = gpurt(args);
        EXPECT_EQ(run.code, code) << "gpurt " << args << "\nstderr: " << run.err;
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1)
            << "gpurt " << args << "\nstderr is not one line: " << run.err;
        EXPECT_TRUE(!run.err.empty() && run.err.back() == '\n') << run.err;
        for (const std::string& mention : mentions)
            EXPECT_NE(run.err.find(mention), std::string::npos)
                << "gpurt " << args << "\n'" << mention << "' not in stderr: " << run.err;
        EXPECT_EQ(files(), before) << "gpurt " << args << " left files behind";
        EXPECT_TRUE(run.out.empty()) << run.out;
    }

    fs::path dir;

  private:
    fs::path base_;
};

}  // namespace gpurt::test
