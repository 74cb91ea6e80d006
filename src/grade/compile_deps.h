// What a compile of a submission read, from the compiler's own dependency
// lists (grade --class, docs/grading.md "How a submission is built").
//
// Where bubblewrap runs, the compile sees only the project's headers
// (header_view.h); where it cannot (--no-sandbox, no user namespaces), the
// grader asks the compiler afterwards instead: every file a source
// included, as GCC wrote it for make (`-MD`: CMake's Makefile generators
// keep these .d files) or as Ninja stored it (`ninja -t deps`). The paths
// are resolved (symbolic links too, so a link in the submission that
// points at a reference .cpp is found) and a source that read a file of
// the project's src/ other than a header is refused. Student code cannot
// run while it compiles, so the lists are the compiler's, not the student's.
#pragma once

#include <string>
#include <vector>

namespace pt {

struct CompileDeps {
    std::string source;              ///< the file compiled (the first prerequisite)
    std::vector<std::string> files;  ///< every file it read, the source first
};

/// Makefile-format dependency text ("obj.o: a.cpp \\\n b.h", spaces in a
/// path escaped as "\ "), as GCC's -MD writes it.
CompileDeps parse_make_deps(const std::string& text);

/// The output of `ninja -t deps`: per object, "obj.o: #deps N, ..." and
/// then one indented path per line.
std::vector<CompileDeps> parse_ninja_deps(const std::string& text);

/// Every .d file under `build_dir`/CMakeFiles, parsed.
std::vector<CompileDeps> read_make_deps(const std::string& build_dir);

/// The first of `files` (relative ones to `cwd`) that resolves to a file
/// under `src` that is not a header, resolved (absolute, links followed);
/// "" when there is none.
std::string project_source_read(const std::vector<std::string>& files, const std::string& src,
                                const std::string& cwd);

}  // namespace pt
