// Performance checks (Part 2): how much the student's BVH saves.
//
// The hardware-independent figure is primitive tests per ray
// (core/counters.h; BVHTree::intersect_primitive counts them for the
// student's tree); nodes visited per ray are limited only for accelerators
// that count them (the engine's BVH; the student's tree cannot: see
// performance_checks.cpp). The speedup over the linear scan is measured on
// the grader's machine (the fastest of `repeats` runs, so that a busy
// machine hurts less).
//
// Manifest params of `bvh_performance`: "scene" (scenes/cbox_knot.json),
// "rays" (2000), "linear_rays" (200: the linear scan is timed on these
// and compared per ray), "repeats" (3), "max_leaf" (4), "min_speedup" (2),
// "max_tests_per_ray" and "max_nodes_per_ray" (no limit unless given).
#pragma once

#include <vector>

#include "core/ray.h"
#include "grade/grade_environment.h"
#include "grade/task.h"
#include "stages/accelerator.h"

namespace pt {

struct AcceleratorMeasurement {
    double seconds = 0;        ///< the fastest run over all rays
    double nodes_per_ray = 0;  ///< BVH nodes visited per closest-hit query
    double tests_per_ray = 0;  ///< primitive tests per closest-hit query
    size_t hits = 0;           ///< rays that hit something
};

/// Closest-hit queries of every ray, `repeats` times, on the calling thread.
AcceleratorMeasurement measure_accelerator(const Accelerator& accelerator,
                                           const std::vector<Ray>& rays, int repeats);

TaskResult check_bvh_performance(const TaskSpec& spec, const GradeEnvironment& env);

}  // namespace pt
