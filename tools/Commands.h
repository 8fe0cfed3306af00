// The subcommands of the gpurt program; each returns the process exit code (CONTRACT.md).
#pragma once

#include <CLI/CLI.hpp>

#include <functional>

namespace gpurt {

// Adds a subcommand to `app`; `run` is set to the function to call when it was chosen.
void addInfoCommand(CLI::App& app, std::function<int()>& run);
void addRenderCommand(CLI::App& app, std::function<int()>& run);
void addBenchCommand(CLI::App& app, std::function<int()>& run);
void addPackCommand(CLI::App& app, std::function<int()>& run);
void addViewCommand(CLI::App& app, std::function<int()>& run);
void addStitchCommand(CLI::App& app, std::function<int()>& run);
void addDenoiseCommand(CLI::App& app, std::function<int()>& run);

}  // namespace gpurt
