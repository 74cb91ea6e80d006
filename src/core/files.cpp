#include "core/files.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace pt {

void require_readable_file(const std::string& path, const std::string& where) {
    struct stat st;
    if (stat(path.c_str(), &st) != 0)
        throw InputError(where + ": cannot read " + path + ": " + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) throw InputError(where + ": cannot read " + path + ": not a regular file");
    if (access(path.c_str(), R_OK) != 0)
        throw InputError(where + ": cannot read " + path + ": " + std::strerror(errno));
}

std::string directory_of(const std::string& path) {
    size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

}  // namespace pt
