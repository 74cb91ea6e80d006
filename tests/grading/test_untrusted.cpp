// The trusted and untrusted halves (grade/student_calls.h, isolation.h):
// grading through a child that only records the student's outputs gives
// exactly the verdicts and figures of grading in-process, and nothing the
// child writes is taken as a verdict.
#include <doctest/doctest.h>

#include "core/timer.h"
#include "fixtures/fixtures.h"
#include "grade/isolation.h"
#include "grade/student_calls.h"
#include "grade/task_json.h"
#include "grading_helpers.h"

using namespace pt;
using namespace pt::testing;

namespace {

/// The task's result without its timing (the one figure that differs).
nlohmann::json verdict(TaskResult t) {
    t.seconds = 0;
    return task_to_json(t);
}

}  // namespace

TEST_CASE("recorded and replayed: the same verdicts and figures as in-process, every part") {
    for (int part : graded_parts()) {
        for (const TaskSpec& spec : manifest(part).tasks) {
            if (spec.check == "bvh_performance") continue;  // wall-clock figures differ run to run
            TaskResult direct = grade_task(spec, environment(reference_stages(), 1));
            TaskResult replayed = grade_task_isolated(spec, environment(reference_stages(), 1), 120);
            INFO(spec.id << ": " << replayed.message);
            CHECK(replayed.status == TaskStatus::pass);
            CHECK(verdict(direct).dump() == verdict(replayed).dump());
        }
    }
}

TEST_CASE("recorded and replayed: a fixture per part fails its own task, with the same message") {
    for (int part : graded_parts()) {
        for (const fixtures::Fixture& f : {fixtures::fixtures_of_part(part).front()}) {
            Stages student = fixtures::stages_with(f);
            for (const TaskSpec& spec : manifest(part).tasks) {
                if (!f.fails(spec.id)) continue;
                TaskResult direct = grade_task(spec, environment(student, 1));
                TaskResult replayed = grade_task_isolated(spec, environment(student, 1), 120);
                INFO(f.name << ", " << spec.id << ": " << replayed.message);
                CHECK(replayed.status == TaskStatus::fail);
                if (spec.check != "bvh_performance") CHECK(direct.message == replayed.message);
            }
        }
    }
}
