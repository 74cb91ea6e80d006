// Building one submission's runners for `grade --class` (docs/grading.md,
// "Grading a class"). Each worker owns a folder configured once from the
// small project cmake/grade_class with the main build's initial cache
// (BUILD/grade_class/initial_cache.cmake): the compiler, its flags and the
// trusted objects of the runners. Per submission the folder is configured
// again with that submission's sources and built: only the student's files
// are compiled, every time whatever their file times (a handout stub's
// object stays up to date from one student to the next), and only the
// runners of the submitted parts are linked.
#pragma once

#include <string>
#include <vector>

#include "grade/child_process.h"
#include "grade/submission.h"

namespace pt {

struct ClassBuildTools {
    std::string cmake;          ///< the cmake executable the main build was made with
    std::string generator;      ///< and its generator
    std::string project_dir;    ///< cmake/grade_class
    std::string initial_cache;  ///< BUILD/grade_class/initial_cache.cmake
    std::string handout_dir;    ///< the project's assignments/: the stubs
    int jobs = 1;               ///< compiler processes per build
    double timeout = 600;       ///< seconds per configure and per build
    /// The compile of the student's sources runs inside bubblewrap where it
    /// can (sandbox.h build_sandbox_prefix), reading only these folders (the
    /// project's CMake files, the main build), the project's headers, the
    /// submission and the system, writing only its build folder; false:
    /// limits only.
    bool sandbox = true;
    std::vector<std::string> readable = {};
    /// The project's src/ (include paths point there) and its headers-only
    /// view (header_view.h), which the sandbox binds at src/'s path: a
    /// submission cannot #include a reference .cpp. Outside the sandbox
    /// the compiler's dependency lists are checked instead (compile_deps.h).
    std::string project_src = {};
    std::string header_view = {};
    /// Per compiler process: a source that includes /dev/zero or
    /// instantiates without end fails its build with the reason.
    ChildLimits limits{4e9, 1e9, 120};
};

struct ClassBuildResult {
    bool ok = false;
    /// The build failed without a compiler or linker error to show (a
    /// timeout, a missing trusted object): the grader's problem, not the student's.
    bool internal = false;
    std::string first_error;  ///< the compiler's (or linker's) first error, paths made relative
    std::string runner_dir;   ///< where grade_runner_KEY are, when ok
    bool sandboxed = false;   ///< the compile ran inside bubblewrap
    double seconds = 0;
};

/// Builds the runners `keys` of `s` in `work_dir`; the configure and build
/// output goes to `log_path`. Never throws for the student's code.
ClassBuildResult build_submission(const ClassBuildTools& tools, const std::string& work_dir,
                                  const Submission& s, const std::vector<std::string>& keys,
                                  const std::string& log_path);

/// The first error line of a build log (compiler "error:", linker
/// "undefined reference" or "multiple definition"), with `strip` prefixes
/// removed from paths; "" when there is none.
std::string first_build_error(const std::string& log, const std::vector<std::string>& strip);

}  // namespace pt
