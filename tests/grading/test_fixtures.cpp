// The power of the grader: each deliberately wrong implementation under
// fixtures/ fails exactly its task and passes every other one.
#include <doctest/doctest.h>

#include "fixtures/fixtures.h"
#include "grade/report.h"
#include "grading_helpers.h"

using namespace pt;
using namespace pt::testing;

namespace {

void check_fails_exactly_its_task(const fixtures::Fixture& f, uint64_t seed) {
    Stages student = fixtures::stages_with(f);
    GradeReport report = grade_all({part1_manifest()}, environment(student, seed));
    for (const TaskResult& t : report.tasks) {
        INFO("fixture '" << f.name << "', seed " << seed << ", task " << t.id << ": " << t.message);
        if (t.id == f.failing_task) {
            CHECK(t.status == TaskStatus::fail);
            CHECK(t.points == 0);
        } else {
            CHECK(t.status == TaskStatus::pass);
        }
    }
}

}  // namespace

TEST_CASE("each Part 1 fixture fails exactly its task") {
    for (const fixtures::Fixture& f : fixtures::part1_fixtures()) {
        SUBCASE(f.name.c_str()) {
            for (uint64_t seed : {1, 2, 3})
                check_fails_exactly_its_task(f, seed);
        }
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
    CHECK(j["tasks"][1]["images"].size() == 2);
}
