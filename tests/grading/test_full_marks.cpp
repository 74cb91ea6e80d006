// The false-failure test of the grader: the reference implementation,
// graded as if it were a student's, must earn full marks on every one of
// 20 seeds, part by part (DESIGN.md: Monte Carlo noise never fails a
// correct submission). Also correct implementations written differently
// from the reference (textbook formulas) must pass: the tolerances are not
// tuned to the reference's exact arithmetic.
#include <doctest/doctest.h>

#include <cstdio>

#include "fixtures/fixtures.h"
#include "full_marks.h"
#include "global/handout_steps.h"
#include "grading_helpers.h"

using namespace pt;
using namespace pt::testing;

namespace pt::fixtures::part1 {
std::optional<Hit> moller_trumbore(const Triangle& tri, const Ray& ray, bool check_t_min,
                                   bool swap);
std::optional<Hit> quadratic(const Sphere& sphere, const Ray& ray, bool far_first, bool near_only);
}  // namespace pt::fixtures::part1

namespace pt::fixtures {
bool textbook_has_converged(const PixelStatistics& s, double tol);
}  // namespace pt::fixtures

// Parts 4 to 9: test_full_marks_later_parts.cpp (two files, so that ctest
// runs the halves on both cores).
TEST_CASE("the reference graded as the student earns full marks on 20 of 20 seeds, parts 1 to 3") {
    for (int part : {1, 2, 3}) {
        SUBCASE(("part " + std::to_string(part)).c_str()) {
            full_marks_on_20_seeds(part, reference_stages());
        }
    }
}

TEST_CASE("textbook intersection routines (not the reference's formulas) pass") {
    Stages student = reference_stages();
    student.intersect.intersect_triangle = [](const Triangle& t, const Ray& r) {
        return fixtures::part1::moller_trumbore(t, r, true, false);
    };
    student.intersect.intersect_sphere = [](const Sphere& s, const Ray& r) {
        return fixtures::part1::quadratic(s, r, false, false);
    };
    for (uint64_t seed = 1; seed <= 5; ++seed) {
        for (const TaskSpec& spec : part1_manifest().tasks) {
            if (spec.check != "intersect_triangle" && spec.check != "intersect_sphere") continue;
            TaskResult r = grade_task(spec, environment(student, seed));
            INFO("seed " << seed << ", " << spec.id << ": " << r.message);
            CHECK(r.status == TaskStatus::pass);
        }
    }
}

TEST_CASE("correct BVHs written differently from the reference pass every Part 2 task") {
    for (const fixtures::Fixture& f : fixtures::part2_correct_alternatives()) {
        Stages student = fixtures::stages_with(f);
        for (uint64_t seed = 1; seed <= 3; ++seed) {
            GradeReport report = grade_all({manifest(2)}, environment(student, seed));
            for (const TaskResult& t : report.tasks) {
                INFO(f.name << ", seed " << seed << ", " << t.id << ": " << t.message);
                CHECK(t.status == TaskStatus::pass);
            }
        }
    }
}

TEST_CASE("CS184's textbook has_converged (no rare-event guard) earns full marks on Part 5") {
    Stages student = reference_stages();
    student.adaptive.has_converged = fixtures::textbook_has_converged;
    full_marks_on_20_seeds(5, student);
}

TEST_CASE("a path tracer written from the TODO steps (recursive) passes every Part 4 task") {
    Stages student = reference_stages();
    student.global = {handout_steps::bounce<handout_steps::Bug::none>,
                      handout_steps::camera_ray<handout_steps::CameraBug::none>};
    // Two seeds: it draws the reference's random numbers, so the 20-seed
    // test of the reference covers the noise; this covers the recursion.
    for (uint64_t seed = 1; seed <= 2; ++seed) {
        GradeReport report = grade_all({manifest(4)}, environment(student, seed));
        for (const TaskResult& t : report.tasks) {
            INFO("seed " << seed << ", " << t.id << ": " << t.message);
            CHECK(t.status == TaskStatus::pass);
        }
    }
}

TEST_CASE("the hidden set's correct solutions written differently pass every task of their part") {
    for (int part : graded_parts()) {
        for (const fixtures::Fixture& f : fixtures::hidden_set_alternatives(part)) {
            Stages student = fixtures::stages_with(f);
            for (uint64_t seed = 1; seed <= 2; ++seed) {
                for (const TaskSpec& spec : manifest(part).tasks) {
                    // The first test case covers the tasks that run none of f's code.
                    if (image_task_runs_only_reference(spec, student)) continue;
                    TaskResult t = grade_task(spec, environment(student, seed));
                    INFO(f.name << ", seed " << seed << ", " << t.id << ": " << t.message);
                    CHECK(t.status == TaskStatus::pass);
                }
            }
        }
    }
}
