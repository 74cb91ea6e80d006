// The grader: runs every task of every manifest against a student
// implementation and collects the results for the reports.
//
// A check that throws NotImplemented (a handout stub) makes its task "not
// implemented" with 0 points (stubs with a slow fallback throw it too while
// a task is graded: core/stub_fallback.h); any other exception from student code fails
// the task with the exception's message. Neither stops the other tasks.
// InputError (a bad manifest or a missing scene) is the grader's problem,
// not the student's: it propagates, and `grade` exits with code 2.
#pragma once

#include <string>
#include <vector>

#include "grade/grade_environment.h"
#include "grade/manifest.h"
#include "grade/task.h"

namespace pt {

struct GradeReport {
    std::vector<TaskResult> tasks;
    std::vector<std::string> notes;  ///< e.g. parts skipped for want of a manifest
    std::vector<std::string>
        parts;  ///< "Part 1: Ray generation and scene intersection", graded parts
    uint64_t seed = 0;
    std::string student_dir;  ///< the PT_STUDENT_DIR the build was made with
    std::string date;         ///< when grading started, local time
    double seconds = 0;       ///< total grading time

    double points() const;
    double max_points() const;
    /// True when there is at least one task and every task passed.
    bool all_passed() const;
};

/// Grades one task; never throws for student behaviour (see file comment).
TaskResult grade_task(const TaskSpec& spec, const GradeEnvironment& env);

/// Grades every task of `manifests` (in order); `on_task` (may be null) is
/// called after each task, for progress lines. With isolate_timeout > 0
/// every task runs in a child process with that many seconds to finish
/// (isolation.h); with 0 they run in this process.
GradeReport grade_all(const std::vector<PartManifest>& manifests, const GradeEnvironment& env,
                      void (*on_task)(const TaskResult&) = nullptr, double isolate_timeout = 0);

struct Isolation;
/// grade_all with every task in a child process as `isolation` says
/// (isolation.h): `grade` runs each task's runner executable.
GradeReport grade_all(const std::vector<PartManifest>& manifests, const GradeEnvironment& env,
                      void (*on_task)(const TaskResult&), const Isolation& isolation);

}  // namespace pt
