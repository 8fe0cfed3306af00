// Atomic output through mkstemp and rename (POSIX rename replaces the target in one step).
#include "raytrace/AtomicFile.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include "raytrace/InputError.h"

namespace gpurt {
namespace {

std::string errnoText() { return std::strerror(errno); }

}  // namespace

void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::FILE*)>& write) {
    const std::string target = path.string();
    std::string temp = target + ".tmp-XXXXXX";
    const int fd = mkstemp(temp.data());
    if (fd < 0) throw InputError(target + ": cannot create file (" + errnoText() + ")");
    // mkstemp creates the file 0600; an output file should be readable like any other file.
    fchmod(fd, 0644);
    std::FILE* file = fdopen(fd, "wb");
    if (!file) {
        const std::string why = errnoText();
        close(fd);
        unlink(temp.c_str());
        throw InputError(target + ": cannot write file (" + why + ")");
    }
    try {
        write(file);
        if (std::fflush(file) != 0 || std::ferror(file))
            throw InputError(target + ": cannot write file (" + errnoText() + ")");
    } catch (...) {
        std::fclose(file);
        unlink(temp.c_str());
        throw;
    }
    if (std::fclose(file) != 0) {
        const std::string why = errnoText();
        unlink(temp.c_str());
        throw InputError(target + ": cannot write file (" + why + ")");
    }
    if (std::rename(temp.c_str(), target.c_str()) != 0) {
        const std::string why = errnoText();
        unlink(temp.c_str());
        throw InputError(target + ": cannot write file (" + why + ")");
    }
}

}  // namespace gpurt
