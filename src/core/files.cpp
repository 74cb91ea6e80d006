#include "core/files.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

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

std::string read_small_file(const std::string& path, const std::string& where, uint64_t max_bytes,
                            const std::string& what) {
    require_readable_file(path, where);
    struct stat st;
    if (stat(path.c_str(), &st) == 0 && uint64_t(st.st_size) > max_bytes)
        throw InputError(where + ": " + path + " is " + std::to_string(st.st_size) + " bytes; " + what + " is at most " +
                         std::to_string(max_bytes) + " bytes");
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    if (in) text << in.rdbuf();
    if (!in) throw InputError(where + ": cannot read " + path + ": " + std::strerror(errno));
    return text.str();
}

std::string directory_of(const std::string& path) {
    size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

}  // namespace pt
