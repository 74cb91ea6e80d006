// Running a task in a child process, so that a student's crash or endless
// loop costs that task its points instead of ending the grading run.
//
// The child (fork) grades the task exactly as grade_task does and sends
// the TaskResult back as JSON through a pipe. The parent waits at most
// `timeout_seconds`; a child that is still running then is killed and the
// task fails with "timed out"; a child killed by a signal fails the task
// with the signal's name (e.g. "segmentation fault"). An InputError in the
// child (a bad manifest or scene: the grader's problem) is re-thrown in
// the parent. POSIX only (Debian is the platform).
#pragma once

#include "grade/grade_environment.h"
#include "grade/task.h"

namespace pt {

TaskResult grade_task_isolated(const TaskSpec& spec, const GradeEnvironment& env,
                               double timeout_seconds);

}  // namespace pt
