// Output files that appear whole or not at all (CONTRACT.md, exit codes): the data goes to a
// temporary file in the target's folder, which is renamed over the target only once complete.
#pragma once

#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace gpurt {

// Runs `write` on a fresh temporary file next to `path` (mode 0644), then renames it to `path`.
// On any failure, including an exception from `write`, the temporary file is removed; failures
// of the file system throw InputError("<path>: cannot ...").
void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::FILE*)>& write);

// Throws InputError("<path>: ...") when `path` cannot be an output file: its folder does not
// exist, or it names a folder.
void checkOutputPath(const std::filesystem::path& path);
// checkOutputPath for each, and no file named twice. Lets a command refuse its outputs before
// doing the work.
void checkOutputPaths(const std::vector<std::filesystem::path>& paths);

// The file name's extension in lower case (".exr" for OUT.EXR; "" when none): how readers and
// writers choose a format by name.
std::string lowerExtension(const std::filesystem::path& path);

// Several output files that appear together or not at all (the PNG and the AOVs of a render):
// add() writes each to its temporary file at once, commit() renames them all over their targets.
// Whatever is not committed, because add() or the work in between threw, is removed by the
// destructor, so a failed command leaves nothing behind.
class AtomicFileSet {
  public:
    AtomicFileSet() = default;
    ~AtomicFileSet();
    AtomicFileSet(const AtomicFileSet&) = delete;
    AtomicFileSet& operator=(const AtomicFileSet&) = delete;

    // Writes the file's temporary copy as writeFileAtomically does. Throws InputError for a
    // target that is not a possible output (checkOutputPath) or already in the set.
    void add(const std::filesystem::path& path, const std::function<void(std::FILE*)>& write);
    // Renames every temporary file to its target.
    void commit();

  private:
    std::vector<std::pair<std::string, std::string>> staged_;  // (temporary, target)
};

}  // namespace gpurt
