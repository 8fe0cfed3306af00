// gpurt: the command-line program. Parses the subcommand, runs it, and maps errors to the
// contract's exit codes: 1 for bad input or options, 2 for an environment that cannot run it.
#include "Commands.h"

#include "stream/StreamErrors.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <functional>
#include <string>

int main(int argc, char** argv) {
    CLI::App app{"gpurt: a GPGPU ray tracer built from OpenGL stream kernels", "gpurt"};
    app.require_subcommand(1);
    std::function<int()> run;
    gpurt::addInfoCommand(app, run);
    gpurt::addRenderCommand(app, run);
    gpurt::addBenchCommand(app, run);
    gpurt::addPackCommand(app, run);
    gpurt::addViewCommand(app, run);
    gpurt::addStitchCommand(app, run);
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
