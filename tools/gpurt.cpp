// gpurt: the command-line program. Parses the subcommand, runs it, and maps errors to the
// contract's exit codes: 1 for bad input or options, 2 for an environment that cannot run it.
#include "Commands.h"

#include "stream/StreamErrors.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <functional>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

namespace {

// A big scene's arrays (the mesh, the grid, the BVH, and the GL driver's copies of the scene
// textures, which llvmpipe allocates with malloc and zero-fills) are hundreds of megabytes written
// once: in 4 KiB pages each page's first touch costs a fault of about 10 us on this project's
// machines, in 2 MiB pages almost nothing (docs/PERFORMANCE.md, "A big model's start-up"). glibc
// puts its large allocations in transparent huge pages with the tunable glibc.malloc.hugetlb=1,
// which it reads at start only: so a command given a file of kBigFile bytes or more runs itself
// again with the tunable set, once (a start costs ~0.1 s, the faults of the dragon ~1.2 s). Not
// where the user set the tunable, nor where the kernel gives no transparent huge pages.
constexpr off_t kBigFile = off_t(16) << 20;

void runWithHugePageMalloc(char** argv) {
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    if (tunables && std::strstr(tunables, "glibc.malloc.hugetlb")) return;
    bool big = false;
    for (char** a = argv + 1; *a && !big; ++a) {
        struct stat st;
        big = ::stat(*a, &st) == 0 && S_ISREG(st.st_mode) && st.st_size >= kBigFile;
    }
    if (!big) return;
    std::ifstream thp("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string modes;
    std::getline(thp, modes);
    if (modes.find("[never]") != std::string::npos || modes.empty()) return;
    const std::string value = std::string(tunables ? tunables : "") + (tunables && *tunables ? ":" : "") +
                              "glibc.malloc.hugetlb=1";
    if (::setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0) return;
    ::execv("/proc/self/exe", argv);
    ::unsetenv("GLIBC_TUNABLES");  // exec failed: run on as we are
    if (tunables) ::setenv("GLIBC_TUNABLES", tunables, 1);
}

}  // namespace

int main(int argc, char** argv) {
    runWithHugePageMalloc(argv);
    CLI::App app{"gpurt: a GPGPU ray tracer built from OpenGL stream kernels", "gpurt"};
    app.require_subcommand(1);
    std::function<int()> run;
    gpurt::addInfoCommand(app, run);
    gpurt::addRenderCommand(app, run);
    gpurt::addBenchCommand(app, run);
    gpurt::addPackCommand(app, run);
    gpurt::addViewCommand(app, run);
    gpurt::addStitchCommand(app, run);
    gpurt::addDenoiseCommand(app, run);
    std::string names;  // "render, pack, bench or info"
    const auto subcommands = app.get_subcommands([](CLI::App*) { return true; });
    for (size_t i = 0; i < subcommands.size(); ++i)
        names += (i == 0 ? "" : i + 1 == subcommands.size() ? " or " : ", ") + subcommands[i]->get_name();
    if (argc < 2) {
        std::fprintf(stderr, "gpurt: a subcommand is required: %s (gpurt --help)\n", names.c_str());
        return 1;
    }
    const std::string first = argv[1];
    bool known = false;
    for (const CLI::App* sub : subcommands) known = known || sub->check_name(first);
    if (first.empty() || (first[0] != '-' && !known)) {
        std::fprintf(stderr, "gpurt: unknown subcommand '%s': %s (gpurt --help)\n", first.c_str(),
                     names.c_str());
        return 1;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "gpurt: %s\n", e.what());
        return 1;
    }
    try {
        return run ? run() : 1;
    } catch (const gpurt::EnvironmentError& e) {
        std::fprintf(stderr, "gpurt: %s\n", e.what());
        return 2;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "gpurt: out of memory\n");
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "gpurt: %s\n", e.what());
        return 1;
    }
}
