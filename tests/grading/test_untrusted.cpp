// The trusted and untrusted halves (grade/student_calls.h, isolation.h):
// grading through a child that only records the student's outputs gives
// exactly the verdicts and figures of grading in-process, and nothing the
// child writes is taken as a verdict.
#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>

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
    double direct_seconds = 0, replayed_seconds = 0;
    for (int part : graded_parts()) {
        for (const TaskSpec& spec : manifest(part).tasks) {
            Timer timer;
            TaskResult direct = grade_task(spec, environment(reference_stages(), 1));
            direct_seconds += timer.seconds();
            timer = Timer();
            TaskResult replayed = grade_task_isolated(spec, environment(reference_stages(), 1), 120);
            replayed_seconds += timer.seconds();
            INFO(spec.id << ": " << replayed.message);
            CHECK(replayed.status == TaskStatus::pass);
            if (spec.check == "bvh_performance") {
                // Its times differ run to run (and replayed, they are the whole
                // runner's); the grader's count on the student's tree does not.
                CHECK(replayed.value == direct.value);
                continue;
            }
            CHECK(verdict(direct).dump() == verdict(replayed).dump());
        }
    }
    // With a warm disk cache the converged references cost nothing to
    // either; the replay reuses the in-process run's reference renders at
    // the student's spp (8 renders of 64x64 pixels per case).
    MESSAGE("in-process " << direct_seconds << " s, recorded in a child and replayed "
                          << replayed_seconds << " s");
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

namespace {

/// `nm -S` of `binary`: the size of the global function whose demangled name
/// starts with `name`, or -1.
long symbol_size(const std::string& binary, const std::string& name) {
    std::string command = "nm -S -C --defined-only '" + binary + "' 2>/dev/null";
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return -1;
    char line[4096];
    long size = -1;
    while (std::fgets(line, sizeof line, pipe)) {
        char address[64], hex[64], kind[8];
        int used = 0;
        if (std::sscanf(line, "%63s %63s %7s %n", address, hex, kind, &used) != 3) continue;
        if ((std::string(kind) == "T" || std::string(kind) == "W") &&
            std::string(line + used).rfind(name, 0) == 0)
            size = std::strtol(hex, nullptr, 16);
    }
    pclose(pipe);
    return size;
}

}  // namespace

TEST_CASE("the binaries: grade holds no student code; a runner no reference of what it grades") {
    const std::string bin = PT_BIN_DIR;
    // grade's student functions are the placeholders that throw (a second
    // definition, from assignments/, would not link).
    auto contains = [](const std::string& file, const std::string& text) {
        return std::system(("grep -q -a -F '" + text + "' '" + file + "'").c_str()) == 0;
    };
    CHECK(contains(bin + "/grade", "grade holds no student code, yet called"));
    CHECK_FALSE(contains(bin + "/grade_runner_generate_ray", "grade holds no student code"));
    CHECK(contains(bin + "/grade_runner_generate_ray", "is not available to the code it grades"));
    // Each runner's withheld reference function is the stand-in that throws,
    // not the reference's body (which `grade` holds): another size.
    const std::pair<std::string, std::string> withheld[] = {
        {"generate_ray", "pt::reference::generate_ray("},
        {"intersect_triangle", "pt::reference::intersect_triangle("},
        {"intersect_triangle", "pt::reference::intersect_triangle_watertight("},
        {"intersect_sphere", "pt::reference::intersect_sphere("},
        {"construct_bvh", "pt::reference::construct_bvh("},
        {"bbox_intersect", "pt::reference::bbox_intersect("},
        {"bbox_intersect", "pt::reference::bvh_intersect("},
        {"grid_intersect", "pt::reference::grid_intersect("},
        {"estimate_direct_lighting_hemisphere", "pt::reference::one_bounce_radiance("},
        {"zero_bounce_radiance", "pt::reference::estimate_direct_lighting_hemisphere("},
        {"has_converged", "pt::reference::has_converged("},
        {"at_least_one_bounce_radiance", "pt::reference::at_least_one_bounce_radiance("},
        {"random_walk", "pt::reference::random_walk("},
        {"connect", "pt::reference::connect("},
        {"mis_weight", "pt::reference::mis_weight("},
        {"bdpt", "pt::reference::connect("},
        // engine helpers that would answer a task whole (scripts/weaken_reference.sh)
        {"estimate_direct_lighting_importance", "pt::sample_lights_mis("},
        {"estimate_direct_lighting_mis", "pt::sample_lights_mis("},
        {"estimate_direct_lighting_mis", "pt::bsdf_sample_mis_weight("},
    };
    for (const auto& [key, f] : withheld) {
        INFO(key << ": " << f);
        long in_runner = symbol_size(bin + "/grade_runner_" + key, f);
        long in_grade = symbol_size(bin + "/grade", f);
        CHECK(in_runner > 0);
        CHECK(in_grade > 0);
        CHECK(in_runner != in_grade);
    }
    // ... and the runners keep the reference of what they do not grade.
    CHECK(symbol_size(bin + "/grade_runner_generate_ray", "pt::reference::intersect_triangle(") ==
          symbol_size(bin + "/grade", "pt::reference::intersect_triangle("));
}
