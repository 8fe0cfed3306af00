// Output files that appear whole or not at all (CONTRACT.md, exit codes): the data goes to a
// temporary file in the target's folder, which is renamed over the target only once complete.
#pragma once

#include <cstdio>
#include <filesystem>
#include <functional>

namespace gpurt {

// Runs `write` on a fresh temporary file next to `path` (mode 0644), then renames it to `path`.
// On any failure, including an exception from `write`, the temporary file is removed; failures
// of the file system throw InputError("<path>: cannot ...").
void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::FILE*)>& write);

}  // namespace gpurt
