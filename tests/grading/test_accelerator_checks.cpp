// The Part 2 checks, ready before the BVH lands: the linear scan passes
// bvh_intersect; accelerators with the classic bugs fail it; the nodes
// visited per ray are measured (hardware-independent) for bvh_performance.
#include <doctest/doctest.h>

#include "fixtures/fixtures.h"
#include "grade/grader.h"
#include "grading_helpers.h"

using namespace pt;
using namespace pt::testing;

namespace {

TaskSpec spec(const std::string& check, TaskType type, nlohmann::json params) {
    TaskSpec t;
    t.part = 2;
    t.id = check;
    t.name = check;
    t.check = check;
    t.type = type;
    t.points = 10;
    t.params = std::move(params);
    t.manifest = "test";
    return t;
}

}  // namespace

TEST_CASE("bvh_intersect: the linear scan passes, the wrong trees fail") {
    TaskSpec intersect = spec("bvh_intersect", TaskType::function, {{"rays", 2000}});
    CHECK(grade_task(intersect, environment(reference_stages(), 1)).status == TaskStatus::pass);
    for (const fixtures::Fixture& f : fixtures::part2_fixtures()) {
        Stages student = fixtures::stages_with(f);
        TaskResult r = grade_task(intersect, environment(student, 1));
        INFO(f.name << ": " << r.message);
        CHECK((r.status == TaskStatus::fail) == (f.failing_task == "bvh_intersect"));
    }
}

TEST_CASE("bvh_performance: nodes visited per ray against a limit") {
    TaskSpec perf =
        spec("bvh_performance", TaskType::performance,
             {{"rays", 2000}, {"repeats", 1}, {"min_speedup", 0.0}, {"max_nodes_per_ray", 100}});
    TaskResult linear = grade_task(perf, environment(reference_stages(), 1));
    INFO(linear.message);
    CHECK(linear.status == TaskStatus::pass);
    for (const fixtures::Fixture& f : fixtures::part2_fixtures()) {
        Stages student = fixtures::stages_with(f);
        TaskResult r = grade_task(perf, environment(student, 1));
        INFO(f.name << ": " << r.message);
        CHECK((r.status == TaskStatus::fail) == (f.failing_task == "bvh_performance"));
    }
    TaskSpec fast = spec("bvh_performance", TaskType::performance,
                         {{"rays", 2000}, {"repeats", 1}, {"min_speedup", 50}});
    TaskResult r = grade_task(fast, environment(reference_stages(), 1));
    CHECK(r.status == TaskStatus::fail);  // the linear scan is no faster than itself
    CHECK(r.message.find("speedup") != std::string::npos);
}
