// Running a trusted tool (cmake, the compiler, a `grade` for one student)
// from `grade --class`, whose worker threads each wait for their own child.
// The child gets its own process group, stdin from /dev/null and its
// output appended to a log file; after `timeout` seconds the whole group is
// killed. Not a sandbox: student code never runs in these children
// directly (the `grade` they start isolates it, isolation.h).
#pragma once

#include <string>
#include <vector>

namespace pt {

/// Resource limits of the child and everything it starts (setrlimit before
/// exec; 0 = unlimited). For the compiler on a student's sources: a file
/// that includes /dev/zero asks for memory without end.
struct ChildLimits {
    double memory_bytes = 0;  ///< address space of each process
    double file_bytes = 0;    ///< the largest file it may write
    double cpu_seconds = 0;   ///< CPU time of each process
};

struct ChildOutcome {
    bool started = false;    ///< false: the program could not be run at all
    bool timed_out = false;  ///< killed after the timeout
    int exit_code = -1;      ///< the exit status, or -1 when killed by a signal
    int signal = 0;          ///< the signal that ended it, 0 if none
};

/// Runs argv[0] (a path, or a name looked up on PATH) with `argv`, output appended to `log_path` ("" =
/// /dev/null), for at most `timeout` seconds (0 = no limit), with `limits`.
/// Thread-safe.
ChildOutcome run_child(const std::vector<std::string>& argv, const std::string& log_path,
                       double timeout, const ChildLimits& limits = {});

}  // namespace pt
