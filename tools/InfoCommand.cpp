// `gpurt info`: the GL vendor, renderer, version, and every limit the tracer relies on.
#include "Commands.h"
#include "CommonOptions.h"

#include "stream/GLContext.h"

#include <cstdio>
#include <memory>

namespace gpurt {

void addInfoCommand(CLI::App& app, std::function<int()>& run) {
    auto* cmd = app.add_subcommand("info", "Print the OpenGL renderer and the limits gpurt relies on");
    auto options = std::make_shared<ContextOptions>();
    addContextOptions(*cmd, *options);
    cmd->callback([&run, options] {
        run = [options] {
            GLContext context = options->makeContext();
            std::printf("%-32s %s\n", "context", context.platform().c_str());
            for (const auto& [name, value] : glInfo())
                std::printf("%-32s %s\n", name.c_str(), value.c_str());
            return 0;
        };
    });
}

}  // namespace gpurt
