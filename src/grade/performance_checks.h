// Performance checks (Part 2): how much the student's BVH saves.
//
// Every figure that decides is measured where the student's code cannot
// reach (docs/grading.md "Part 2's performance task"):
// - primitive tests and nodes visited per ray: the grader traverses the
//   student's tree itself (the tree recorded from construct_bvh, with a
//   fixed traversal, tree_quality.h);
// - the speedup of the student's own traversal over the linear scan: the
//   runner answers distinct rays with it, the grader checks every answer
//   against its own traversal of the same tree, and the time is the
//   runner's whole CPU time as the kernel counted it (wait4), an upper
//   bound on the traversal's that no code in the runner can lower. In
//   process (tests, student code trusted) it is the CPU time of the loop.
//
// Manifest params of `bvh_performance`: "scene" (scenes/cbox_knot.json),
// "rays" (2000: the grader's traversal counts on these), "timed_rays"
// (20000 distinct rays for the student's traversal), "max_timed_seconds"
// (1: the runner stops answering after this much CPU time), "rel_tol"
// (1e-9: part2.3's tolerance on t, hit_compare.h; every timed answer must
// be the closest hit within it, or the task fails with no speed credit:
// a search that skips part of the tree is fast for being wrong),
// "linear_rays" (200: the linear scan is timed on these and compared
// per ray), "repeats" (3: the linear scan's fastest run), "max_leaf" (4),
// "min_speedup" (2), "max_tests_per_ray" and "max_nodes_per_ray" (no limit
// unless given), and the tree-quality limits (tree_quality.h).
#pragma once

#include <optional>
#include <vector>

#include "core/ray.h"
#include "grade/grade_environment.h"
#include "grade/task.h"
#include "stages/accelerator.h"
#include "stages/bvh.h"

namespace pt {

struct AcceleratorMeasurement {
    double seconds = 0;        ///< the fastest run over all rays (CPU seconds)
    double nodes_per_ray = 0;  ///< BVH nodes visited per closest-hit query
    double tests_per_ray = 0;  ///< primitive tests per closest-hit query
    size_t hits = 0;           ///< rays that hit something
};

/// The student's closest-hit traversal of their own tree, timed.
struct TraversalTiming {
    /// CPU seconds: of the loop over the rays (in process), or of the whole
    /// runner process and its children (`whole_runner`; measured by the
    /// kernel, so an upper bound on the loop's).
    double seconds = 0;
    bool whole_runner = false;
    /// One per answered ray, in order: the closest hit (its t and
    /// primitive id are recorded), or nothing.
    std::vector<std::optional<Hit>> answers;
};

/// Answers `rays` in order with `traverse` from the tree's root until all
/// are answered or the calling thread has spent `max_seconds` of CPU time.
TraversalTiming time_traversal(const BVHTree& tree, BvhIntersectFn traverse,
                               const std::vector<Ray>& rays, double max_seconds);

/// Closest-hit queries of every ray, `repeats` times, on the calling
/// thread; seconds are its CPU time (the fastest run).
AcceleratorMeasurement measure_accelerator(const Accelerator& accelerator,
                                           const std::vector<Ray>& rays, int repeats);

TaskResult check_bvh_performance(const TaskSpec& spec, const GradeEnvironment& env);

}  // namespace pt
