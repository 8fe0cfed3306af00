// Running the gpurt program from tests: a scratch folder per test, the program's exit status,
// stdout and stderr, and the files it left behind.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

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

// A process started in the background, its output in files; killed by pid if still running.
class Background {
  public:
    // ours: gpurt (it keeps the sanitizer build's preloads and options); else another program,
    // which gets neither.
    Background(const std::vector<std::string>& argv, const fs::path& out, const fs::path& err,
               const std::string& display, bool ours = true) {
        std::vector<std::string> env;
        for (char** e = environ; *e; ++e) {
            const std::string var(*e);
            const bool sanitizer = var.rfind("LD_PRELOAD=", 0) == 0 || var.rfind("ASAN_OPTIONS=", 0) == 0 ||
                                   var.rfind("LSAN_OPTIONS=", 0) == 0 || var.rfind("UBSAN_OPTIONS=", 0) == 0;
            if (var.rfind("DISPLAY=", 0) != 0 && (ours || !sanitizer)) env.push_back(var);
        }
        if (!display.empty()) env.push_back("DISPLAY=" + display);
        std::vector<char*> args, envp;
        for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
        args.push_back(nullptr);
        for (const std::string& e : env) envp.push_back(const_cast<char*>(e.c_str()));
        envp.push_back(nullptr);
        posix_spawn_file_actions_t files;
        posix_spawn_file_actions_init(&files);
        posix_spawn_file_actions_addopen(&files, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        posix_spawn_file_actions_addopen(&files, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (posix_spawn(&pid_, args[0], &files, nullptr, args.data(), envp.data()) != 0) pid_ = -1;
        posix_spawn_file_actions_destroy(&files);
    }
    ~Background() { stop(); }
    bool started() const { return pid_ > 0; }
    bool running() {
        if (pid_ <= 0) return false;
        int status = 0;
        const pid_t r = waitpid(pid_, &status, WNOHANG);
        if (r == pid_) {
            code_ = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
            pid_ = -1;
            return false;
        }
        return true;
    }
    // The exit status, waiting at most `timeout`; -2 when it is still running then.
    int wait(std::chrono::seconds timeout) {
        const auto end = std::chrono::steady_clock::now() + timeout;
        while (running() && std::chrono::steady_clock::now() < end) std::this_thread::sleep_for(std::chrono::milliseconds(20));
        return running() ? -2 : code_;
    }
    // SIGKILL now (as a scheduler ends a task past its time), and reaped.
    void killNow() {
        if (!running()) return;
        kill(pid_, SIGKILL);
        waitpid(pid_, nullptr, 0);
        pid_ = -1;
        code_ = -1;
    }
    void stop() {
        if (running()) {
            kill(pid_, SIGTERM);
            if (wait(std::chrono::seconds(5)) == -2) {
                kill(pid_, SIGKILL);
                waitpid(pid_, nullptr, 0);
            }
        }
        pid_ = -1;
    }

  private:
    pid_t pid_ = -1;
    int code_ = -1;
};

// A fresh folder for each test (named after it), removed afterwards; runs gpurt with its output
// captured in files outside that folder, so that the folder holds only what gpurt wrote.
class GpurtTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        // A parameterised test's names hold '/': one folder, not a folder in a folder left behind.
        std::string name = std::string(info->test_suite_name()) + "-" + info->name();
        std::replace(name.begin(), name.end(), '/', '-');
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
