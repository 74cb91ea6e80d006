// The false-failure check of the grader, shared by test_full_marks.cpp and
// test_full_marks_later_parts.cpp: a correct implementation earns full
// marks on 20 of 20 seeds (DESIGN.md: Monte Carlo noise never fails a
// correct submission).
#pragma once

#include <doctest/doctest.h>

#include <algorithm>

#include "core/timer.h"
#include "grading_helpers.h"

namespace pt::testing {

/// Grades `part` with `student` on seeds 1 to 20; every task must pass.
inline void full_marks_on_20_seeds(int part, const Stages& student) {
    Timer timer;
    int full_marks = 0;
    double worst_ratio = 0;  // image tasks: student relMSE / limit, the closest call
    for (uint64_t seed = 1; seed <= 20; ++seed) {
        GradeReport report = grade_all({manifest(part)}, environment(student, seed));
        for (const TaskResult& t : report.tasks) {
            INFO("part " << part << ", seed " << seed << ", " << t.id << ": " << t.message);
            CHECK(t.status == TaskStatus::pass);
            if (t.type == TaskType::image && t.threshold > 0)
                worst_ratio = std::max(worst_ratio, t.value / t.threshold);
        }
        if (report.all_passed() && report.points() == report.max_points()) ++full_marks;
    }
    MESSAGE("part " << part << ": full marks on " << full_marks << " of 20 seeds ("
                    << timer.seconds() << " s); image tasks' closest call: relMSE at "
                    << worst_ratio * 100 << "% of its limit");
    CHECK(full_marks == 20);
}

}  // namespace pt::testing
