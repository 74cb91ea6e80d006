// Running a task's student code in another process, so that nothing the
// student code does (a crash, an endless loop, an exit, a forged message,
// a process left behind) can change a verdict or end the grading run.
//
// The child runs the task's check with recording student functions
// (student_calls.h) and sends the raw log through a pipe; the parent
// replays it and computes the verdict itself. The child is either this
// process forked (tests: the student table is env.student) or a runner
// executable, built with the student's code and without the reference of
// the functions the task grades (grade, docs/grading.md), optionally inside
// bubblewrap (sandbox.h). Either way it gets its own session and process
// group, resource limits, and at most `timeout` seconds; afterwards every
// process it left is killed (the grader is their subreaper). A child killed
// by a signal fails the task with the signal's name; one that exits
// without a complete log fails it with its exit status; a log larger than
// `max_log_bytes` or one that does not follow the grader's calls fails it
// with that reason. POSIX only (Debian is the platform).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "grade/grade_environment.h"
#include "grade/task.h"

namespace pt {

struct Isolation {
    double timeout = 600;  ///< wall-clock seconds per task
    /// The command that runs a task's runner (see grade_main.cpp); empty
    /// function: fork this process and record env.student.
    std::function<std::vector<std::string>(const TaskSpec&)> runner;
    /// Put before the runner's command: the bwrap sandbox (sandbox.h); empty: none.
    std::vector<std::string> sandbox_prefix;
    /// The user and group the child becomes before it runs the prefix
    /// (Sandbox::uid, gid); -1: this process's.
    int uid = -1, gid = -1;
    /// Wall-clock seconds for all the tasks of one submission (0 = none):
    /// once spent, the remaining tasks fail without running.
    double budget = 0;
    /// Resource limits of the child (setrlimit; 0 = unlimited).
    double memory_bytes = 8e9;       ///< address space
    double file_bytes = 256e6;       ///< largest file it may write
    int open_files = 256;            ///< file descriptors
    double max_log_bytes = 512e6;    ///< the largest log the parent accepts
};

TaskResult grade_task_isolated(const TaskSpec& spec, const GradeEnvironment& env,
                               const Isolation& isolation);
/// The fork variant with default limits (tests, and `grade` without runners).
TaskResult grade_task_isolated(const TaskSpec& spec, const GradeEnvironment& env,
                               double timeout_seconds);

/// Kills every child process of this one that is not in this process's
/// session (what a task left behind) and reaps it. Called after every task.
/// Returns the CPU seconds (user + system) the reaped processes used.
double kill_leftover_children();

}  // namespace pt
