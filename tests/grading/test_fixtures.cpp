// The power of the grader: each deliberately wrong implementation under
// fixtures/ fails exactly its task (or tasks, fixtures.h) and passes every
// other task of its part.
#include <doctest/doctest.h>

#include <cstdio>

#include "fixtures/fixtures.h"
#include "grade/report.h"
#include "grading_helpers.h"

using namespace pt;
using namespace pt::testing;

namespace {

/// The fixture's failing tasks on seeds 1 to 3 (the hidden set's on seed 1
/// only, to keep the suite short); every other task of the part on seed 1,
/// but for the image tasks that run none of the fixture's code
/// (image_task_runs_only_reference).
void check_fails_exactly_its_tasks(int part, const fixtures::Fixture& f) {
    Stages student = fixtures::stages_with(f);
    const uint64_t last_seed = f.name.rfind("hidden:", 0) == 0 ? 1 : 3;
    for (uint64_t seed = 1; seed <= last_seed; ++seed) {
        for (const TaskSpec& spec : manifest(part).tasks) {
            if (seed > 1 && !f.fails(spec.id)) continue;
            if (!f.fails(spec.id) && image_task_runs_only_reference(spec, student)) continue;
            TaskResult t = grade_task(spec, environment(student, seed));
            INFO("fixture '" << f.name << "', seed " << seed << ", task " << t.id << ": "
                             << t.message);
            if (f.fails(t.id)) {
                CHECK(t.status == TaskStatus::fail);
                CHECK(t.points < t.max_points);  // 0, or the share of the families that pass
            } else {
                CHECK(t.status == TaskStatus::pass);
            }
        }
    }
}

}  // namespace

TEST_CASE("each fixture fails exactly its task") {
    for (int part : graded_parts()) {
        for (const fixtures::Fixture& f : fixtures::fixtures_of_part(part)) {
            SUBCASE(("part " + std::to_string(part) + ": " + f.name).c_str()) {
                check_fails_exactly_its_tasks(part, f);
            }
        }
    }
}

TEST_CASE("a slab test wrong on one case family loses that family's points, and says why") {
    // entry < exit instead of <=: right everywhere except where the exact
    // answer is a single point (flat boxes crossed head-on, touching rays).
    const std::string name = "hidden: bbox_intersect: entry < exit (touching rays and flat boxes miss)";
    const fixtures::Fixture* f = nullptr;
    std::vector<fixtures::Fixture> all = fixtures::fixtures_of_part(2);
    for (const fixtures::Fixture& x : all)
        if (x.name == name) f = &x;
    REQUIRE(f);
    for (const TaskSpec& spec : manifest(2).tasks) {
        if (spec.id != "part2.2") continue;
        TaskResult t = grade_task(spec, environment(fixtures::stages_with(*f), 1));
        INFO(t.message);
        CHECK(t.status == TaskStatus::fail);
        CHECK(t.points == 17);
        CHECK(t.message.rfind("17 of 20 points: family \"exact answers: flat boxes, touching rays, "
                              "origins on faces\" loses its 3 points",
                              0) == 0);
    }
}

TEST_CASE("part2.5 gives no speed credit to a traversal wrong on a minority of rays") {
    // Each skips part of the tree on a few percent of rays and is faster for
    // it: until this rule, up to 25% of wrong answers kept the speed's 20
    // points (part2.3 alone failed them).
    const PartManifest& part2 = manifest(2);
    const TaskSpec* spec = nullptr;
    for (const TaskSpec& x : part2.tasks)
        if (x.id == "part2.5") spec = &x;
    REQUIRE(spec);
    const std::vector<fixtures::Fixture> all = fixtures::fixtures_of_part(2);
    for (const std::string name :
         {"bvh_intersect: skips the farther child when the hit lies before its box's exit",
          "bvh_intersect: the first child with a hit wins",
          "hidden: bvh_intersect: a leaf returns its first hit, not the closest"}) {
        const fixtures::Fixture* f = nullptr;
        for (const fixtures::Fixture& x : all)
            if (x.name == name) f = &x;
        REQUIRE_MESSAGE(f, name);
        TaskResult t = grade_task(*spec, environment(fixtures::stages_with(*f), 1));
        INFO(name << ": " << t.message);
        CHECK(t.status == TaskStatus::fail);
        CHECK(t.points == 0);
        const std::string said = "no speed credit: the student's traversal missed the closest hit on ";
        REQUIRE(t.message.rfind(said, 0) == 0);
        // "N of M timed rays": a minority, counted, and the first one shown.
        size_t wrong = 0, answered = 0;
        REQUIRE(std::sscanf(t.message.c_str() + said.size(), "%zu of %zu timed rays", &wrong, &answered) == 2);
        CHECK(wrong > 0);
        CHECK(double(wrong) < 0.25 * double(answered));
        CHECK(t.message.find("(first: ray o = ") != std::string::npos);
        MESSAGE(name << ": " << wrong << " of " << answered << " timed rays wrong (seed 1)");
    }
}

TEST_CASE("a fixture's report shows the failure with images and numbers") {
    // The y-flipped pixel loop: the report a grader would open.
    fixtures::Fixture f;
    for (const fixtures::Fixture& x : fixtures::part1_fixtures())
        if (x.name == "raytrace_pixel: y axis flipped") f = x;
    REQUIRE(bool(f.install));
    Stages student = fixtures::stages_with(f);
    std::string out = output_dir() + "/grade_fixture_report";
    GradeReport report = grade_all({part1_manifest()}, environment(student, 1, out));
    report.student_dir = "fixture: " + f.name;
    write_reports(report, out);
    CHECK(report.points() == 75);
    CHECK_FALSE(report.all_passed());
    std::string html = html_report(report, out);
    CHECK(html.find("data:image/png;base64,") != std::string::npos);
    CHECK(html.find("FAIL") != std::string::npos);
    nlohmann::json j = json_report(report);
    CHECK(j["tasks"][1]["status"] == "fail");
    CHECK(j["tasks"][1]["images"].size() == 3);
}
