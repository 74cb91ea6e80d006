// Writing output files so that nobody ever sees half of one, and a failed
// write is never reported as a success.
//
// EVERY FILE THE PROJECT WRITES GOES THROUGH HERE: images (image/image_io.cpp),
// --stats JSON, bench tables, plots and caches, imgdiff heat maps. If you add
// a writer (EXR output, a new bench plot, a report), call
// write_file_atomically() or use AtomicFile, and check_output_path() before
// the long computation; never fopen or std::ofstream an output yourself.
//
// How it works: the bytes go to a temporary file ".NAME.XXXXXX" in the
// target's own folder (so rename(2) is atomic: same file system); every
// fwrite, fflush and fclose is checked, and only then is the temporary
// renamed over the target. On any failure, or an exception before commit(),
// the temporary is removed, the old target is left as it was, and
// InputError "cannot write PATH: REASON" is thrown (exit code 2 in the apps).
//
// - A symbolic link is followed: the file it points to is replaced, the link stays.
// - A target under /dev/ or /proc/, or one that is not a regular file (a
//   fifo), is written in place, still checked: there is nothing to rename
//   over (and /dev/stdout must stay the shell's redirection). /dev/full
//   therefore fails with "No space left on device".
// - Not fsync'ed: atomic against a killed process or a full disk, not
//   against a power cut. A process killed mid-write leaves its ".NAME.XXXXXX"
//   behind (the target itself is never truncated).
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace pt {

/// One output file being written: write(), then commit(). Destroyed
/// without commit() (an exception, an early return), it removes its
/// temporary file and the target is untouched.
class AtomicFile {
public:
    /// Opens the temporary file; throws InputError "cannot write PATH: REASON".
    explicit AtomicFile(const std::string& path);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    void write(const void* bytes, size_t size);
    void write(std::string_view text) { write(text.data(), text.size()); }
    /// Flushes, closes and renames over the target; throws on any failure.
    void commit();

    const std::string& path() const { return path_; }

private:
    [[noreturn]] void fail(const std::string& reason);

    std::string path_;    ///< as the caller spelled it (for messages)
    std::string target_;  ///< the file to replace, symbolic links followed
    std::string temp_;    ///< "" when writing the target directly
    std::FILE* file_ = nullptr;
    bool committed_ = false;
};

/// Writes `bytes` to `path` atomically (AtomicFile in one call).
void write_file_atomically(const std::string& path, std::string_view bytes);

/// Before a long computation: throws InputError "WHAT: cannot write PATH:
/// REASON" unless a file can be written there now (its folder exists and
/// takes a new file, it is not a folder, an existing file is writable).
/// `what` names the flag ("-f", "--hdr") or the role of the file.
void check_output_path(const std::string& path, const std::string& what);

/// Throws InputError "WHAT: PATH is also an input (INPUT); ..." when
/// `output` is the same file as one of `inputs` (compared by device and
/// inode, so "./a.png" or a link to it is caught as well). Inputs that do
/// not exist and empty paths are ignored.
void refuse_overwriting_input(const std::string& output, const std::string& what,
                              const std::vector<std::string>& inputs);

}  // namespace pt
