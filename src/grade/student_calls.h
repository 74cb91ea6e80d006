// Student calls recorded in the untrusted process, replayed in the trusted
// one (docs/grading.md "Trusted and untrusted halves").
//
// A task runs twice. The runner (a process that holds the student's code)
// runs the task's check with a stage table whose student functions record
// what they return: every outermost call appends its raw output (a ray, a
// hit, a tree, a colour, an exception's message) to a log, and an image
// task's renders append their float buffers. The runner computes no verdict
// that anyone reads. The grader (a process without student code) then runs
// the same check, on the same inputs, with a table whose student functions
// return the log's next output instead of running anything, and computes
// every figure and status itself. Because the grader generates the inputs,
// a log can only say what the student's functions returned; a log that
// does not follow the grader's calls (garbage, a truncated or forged log)
// throws RunnerOutputError, which fails the task.
//
// Only outermost calls are logged: the student functions that a student
// function calls in turn (through the stage table) run inside the runner
// and are part of its output. Renders and timings pause the log (their
// result is logged as a whole).
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "grade/image_case.h"
#include "render/renderer.h"
#include "stages/stages.h"

namespace pt {

struct TraversalTiming;

/// The log does not match the grader's calls or breaks a size limit.
class RunnerOutputError : public std::runtime_error {
  public:
    explicit RunnerOutputError(const std::string& message) : std::runtime_error(message) {}
};

enum class CallMode {
    direct,  ///< in-process grading: student functions run here (tests)
    record,  ///< the runner: run them and log their outputs
    replay,  ///< the grader: return the logged outputs
};
CallMode call_mode();

/// Starts recording: `student` is the table whose functions run; returns
/// the table to grade with (its functions log their outermost calls).
Stages start_recording(const Stages& student);
/// The log recorded so far, ended by an end marker; resets the log.
std::string finish_recording();

/// The reference table for the runner: the slots in `withheld` (stage_mix
/// slot names) run the student's function instead, without logging. The
/// runner's link holds no reference code for them; the check's comparisons
/// in the runner are then meaningless, but its calls are the grader's.
Stages stand_in_reference(const Stages& reference, const std::vector<std::string>& withheld);

/// Starts replaying `log` (as finish_recording wrote it; checked as it is
/// read); returns the student table to grade with. Throws RunnerOutputError
/// when the log lacks its end marker.
Stages start_replay(std::string log);
/// Back to direct mode (after a task, in the grader).
void stop_replay();

/// The hooks of image and performance checks: in direct mode they render
/// (time); in record mode they render (time) with the log paused and log
/// the result; in replay mode they return the logged one, checked against
/// the case's film size (the rays). A logged timing holds the answers
/// only: its seconds are the runner's CPU time, set_runner_cpu_seconds.
RenderResult student_render(const Scene& scene, const ImageCase& c, const Stages& stages, int spp,
                            uint64_t seed, int threads);
TraversalTiming student_traversal_timing(const BVHTree& tree, BvhIntersectFn traverse,
                                         const std::vector<Ray>& rays, double max_seconds);

/// The CPU seconds (user + system) of the runner whose log is replayed
/// next, with every process it started, as the kernel counted them
/// (isolation.cpp, wait4): the time of a timing in replay mode.
void set_runner_cpu_seconds(double seconds);

/// `text` with bytes other than printable ASCII replaced by '?', at most
/// `limit` bytes: what a report may quote from untrusted output.
std::string printable(const std::string& text, size_t limit = 2000);

}  // namespace pt
