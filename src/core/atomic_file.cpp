#include "core/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>

#include "core/error.h"
#include "core/files.h"

namespace pt {
namespace {

std::string reason() { return std::strerror(errno); }

std::string folder_of(const std::string& path) {
    std::string dir = directory_of(path);
    if (dir.size() > 1) dir.pop_back();  // "a/b/" -> "a/b", "/" stays
    return dir.empty() ? "." : dir;
}

/// Device and process files (/dev/null, /dev/stdout, /proc/self/fd/1) are
/// written in place and never resolved: a rename there is impossible, and
/// following /dev/stdout to a redirected file would cut the shell's link to it.
bool is_device_path(const std::string& path) { return path.rfind("/dev/", 0) == 0 || path.rfind("/proc/", 0) == 0; }

/// True when a write to `target` goes through a temporary and a rename.
bool is_replaceable(const std::string& target) {
    struct stat st;
    return !is_device_path(target) && (stat(target.c_str(), &st) != 0 || S_ISREG(st.st_mode));
}

/// The file a write to `path` lands in: symbolic links followed. Throws
/// `fail(reason)` for a dangling link or a folder.
template <typename Fail>
std::string resolve_target(const std::string& path, Fail fail) {
    if (path.empty()) fail("empty file name");
    if (is_device_path(path)) return path;
    struct stat st;
    if (lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode)) {
        char resolved[PATH_MAX];
        if (!realpath(path.c_str(), resolved)) fail("a symbolic link to a missing file (" + reason() + ")");
        return resolved;
    }
    if (stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) fail("is a folder");
    return path;
}

/// The permissions a plain fopen would give a new file (0666 minus umask);
/// mkstemp's 0600 would otherwise make every output private.
mode_t new_file_mode() {
    static const mode_t mode = [] {
        mode_t mask = umask(0);
        umask(mask);
        return mode_t(0666 & ~mask);
    }();
    return mode;
}

/// Creates the temporary ".NAME.XXXXXX" beside `target`; returns its fd.
int make_temp(const std::string& target, std::string* temp) {
    std::string name = target.substr(directory_of(target).size());
    std::string pattern = directory_of(target) + "." + name + ".XXXXXX";
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    int fd = mkstemp(buffer.data());
    if (fd >= 0) *temp = buffer.data();
    return fd;
}

}  // namespace

AtomicFile::AtomicFile(const std::string& path) : path_(path) {
    target_ = resolve_target(path, [&](const std::string& r) { fail(r); });
    if (!is_replaceable(target_)) {
        file_ = std::fopen(target_.c_str(), "wb");  // a device or fifo: write it directly
        if (!file_) fail(reason());
        return;
    }
    int fd = make_temp(target_, &temp_);
    if (fd < 0) fail(reason() + " (cannot create a file in '" + folder_of(target_) + "')");
    if (fchmod(fd, new_file_mode()) != 0 || !(file_ = fdopen(fd, "wb"))) {
        std::string why = reason();
        close(fd);
        fail(why);
    }
}

AtomicFile::~AtomicFile() {
    if (file_) std::fclose(file_);
    if (!committed_ && !temp_.empty()) std::remove(temp_.c_str());
}

void AtomicFile::fail(const std::string& why) {
    if (file_) std::fclose(file_);
    file_ = nullptr;
    if (!temp_.empty()) std::remove(temp_.c_str());
    temp_.clear();
    throw InputError("cannot write " + path_ + ": " + why);
}

void AtomicFile::write(const void* bytes, size_t size) {
    if (!file_) fail("the file is already closed");
    if (size > 0 && std::fwrite(bytes, 1, size, file_) != size) fail(reason());
}

void AtomicFile::commit() {
    if (!file_) fail("the file is already closed");
    // fflush and fclose report what a buffered fwrite could not (a full disk).
    if (std::fflush(file_) != 0 || std::ferror(file_)) fail(reason());
    std::FILE* f = file_;
    file_ = nullptr;
    if (std::fclose(f) != 0) fail(reason());
    if (!temp_.empty() && std::rename(temp_.c_str(), target_.c_str()) != 0) fail(reason());
    committed_ = true;
}

void write_file_atomically(const std::string& path, std::string_view bytes) {
    AtomicFile file(path);
    file.write(bytes);
    file.commit();
}

void check_output_path(const std::string& path, const std::string& what) {
    auto fail = [&](const std::string& why) {
        throw InputError(what + ": cannot write " + path + ": " + why);
    };
    std::string target = resolve_target(path, fail);
    if (!is_replaceable(target)) {
        if (access(target.c_str(), W_OK) != 0) fail(reason());
        return;
    }
    if (access(target.c_str(), F_OK) == 0 && access(target.c_str(), W_OK) != 0) fail(reason());
    // The only sure test that the folder takes a new file is to make one
    // (access() says yes to root on a read-only or virtual file system).
    std::string temp;
    int fd = make_temp(target, &temp);
    if (fd < 0) fail(reason() + " (cannot create a file in '" + folder_of(target) + "')");
    close(fd);
    std::remove(temp.c_str());
}

void refuse_overwriting_input(const std::string& output, const std::string& what,
                              const std::vector<std::string>& inputs) {
    struct stat out;
    if (output.empty() || stat(output.c_str(), &out) != 0) return;
    for (const std::string& input : inputs) {
        struct stat in;
        if (input.empty() || stat(input.c_str(), &in) != 0) continue;
        if (in.st_dev != out.st_dev || in.st_ino != out.st_ino) continue;
        throw InputError(what + ": " + output + (input == output ? " is" : " is the same file as " + input + ",") +
                         " an input of this run; writing it would destroy the input (choose another name)");
    }
}

}  // namespace pt
