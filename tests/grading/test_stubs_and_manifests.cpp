// The handout stubs grade as "not implemented" (0 points, no crash), and
// manifests are read strictly.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "grade/check_registry.h"
#include "grading_helpers.h"
#include "stages/camera.h"

using namespace pt;
using namespace pt::testing;

namespace {

/// A table whose every Part 1 function throws like a handout stub.
Stages stub_stages() {
    Stages s = reference_stages();
    s.camera.generate_ray = [](const Camera&, double, double, Vec2) -> Ray {
        throw NotImplemented(1, "1", "generate_ray");
    };
    s.camera.raytrace_pixel = [](const RenderContext&, int, int) -> PixelResult {
        throw NotImplemented(1, "2", "raytrace_pixel");
    };
    s.intersect.intersect_triangle = [](const Triangle&, const Ray&) -> std::optional<Hit> {
        throw NotImplemented(1, "3", "intersect_triangle");
    };
    s.intersect.intersect_sphere = [](const Sphere&, const Ray&) -> std::optional<Hit> {
        throw NotImplemented(1, "4", "intersect_sphere");
    };
    return s;
}

std::string write_manifest(const std::string& name, const std::string& text) {
    std::string dir = output_dir() + "/manifests/" + name + "/part1";
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/grading.json") << text;
    return dir + "/grading.json";
}

}  // namespace

TEST_CASE("stubs earn 0 points with 'not implemented' on every task") {
    Stages stubs = stub_stages();
    GradeReport report = grade_all({part1_manifest()}, environment(stubs, 1));
    REQUIRE(report.tasks.size() == 4);
    for (const TaskResult& t : report.tasks) {
        INFO(t.id << ": " << t.message);
        CHECK(t.status == TaskStatus::not_implemented);
        CHECK(t.points == 0);
        CHECK(t.message.find("not implemented yet") != std::string::npos);
    }
    CHECK(report.points() == 0);
    CHECK(report.max_points() == 100);
    CHECK_FALSE(report.all_passed());
}

TEST_CASE("the stubs of this build (when it is the handout) grade as not implemented") {
    Stages student = make_stages(StageSet::all());
    bool handout = false;
    try {
        Camera c;
        c.finalize();
        student::generate_ray(c, 0.5, 0.5, Vec2(0.5, 0.5));
    } catch (const NotImplemented&) {
        handout = true;
    }
    if (!handout) {
        MESSAGE("this build has a student's generate_ray, not the handout stub: skipped");
        return;
    }
    GradeReport report = grade_all({part1_manifest()}, environment(student, 1));
    for (const TaskResult& t : report.tasks)
        CHECK(t.status == TaskStatus::not_implemented);
}

TEST_CASE("a student function that throws something else fails its task with the message") {
    Stages s = reference_stages();
    s.intersect.intersect_sphere = [](const Sphere&, const Ray&) -> std::optional<Hit> {
        throw std::out_of_range("vector::at");
    };
    for (const TaskSpec& spec : part1_manifest().tasks) {
        if (spec.id != "part1.4") continue;
        TaskResult r = grade_task(spec, environment(s, 1));
        CHECK(r.status == TaskStatus::fail);
        CHECK(r.message.find("vector::at") != std::string::npos);
    }
}

TEST_CASE(
    "the Part 1 manifest names registered checks, and every part without a manifest is noted") {
    const PartManifest& m = part1_manifest();
    CHECK(m.part == 1);
    CHECK(m.tasks.size() == 4);
    double points = 0;
    for (const TaskSpec& t : m.tasks) {
        CHECK(find_check(t.check) != nullptr);
        CHECK(t.id.rfind("part1.", 0) == 0);
        points += t.points;
    }
    CHECK(points == 100);
    std::vector<std::string> notes;
    std::string dir = output_dir() + "/manifests/only_part1";
    std::filesystem::create_directories(dir + "/part1");
    std::filesystem::copy_file(source_dir() + "/assignments/part1/grading.json",
                               dir + "/part1/grading.json",
                               std::filesystem::copy_options::overwrite_existing);
    std::vector<PartManifest> all = read_manifests(dir, &notes);
    CHECK(all.size() == 1);
    CHECK(notes.size() == 4);
    CHECK(notes[0].find("Part 2") != std::string::npos);
}

TEST_CASE("manifest errors name the file and the key") {
    auto fails_with = [](const std::string& name, const std::string& text,
                         const std::string& expected) {
        std::string path = write_manifest(name, text);
        INFO(name);
        try {
            read_manifest(path, 1);
            FAIL("no error for " << name);
        } catch (const InputError& e) {
            std::string what = e.what();
            INFO(what);
            CHECK(what.find(path) != std::string::npos);
            CHECK(what.find(expected) != std::string::npos);
        }
    };
    const std::string head = R"({"part": 1, "tasks": [)";
    fails_with("not_json", "{", "not valid JSON");
    fails_with("unknown_top_key", R"({"part": 1, "tasks": [], "taks": []})",
               "unknown key \"taks\"");
    fails_with(
        "unknown_check",
        head +
            R"({"id": "a", "name": "n", "check": "generate_rays", "type": "function", "points": 1}]})",
        "unknown check \"generate_rays\"");
    fails_with(
        "wrong_type",
        head +
            R"({"id": "a", "name": "n", "check": "generate_ray", "type": "image", "points": 1}]})",
        "is a function check");
    fails_with(
        "unknown_param",
        head +
            R"({"id": "a", "name": "n", "check": "generate_ray", "type": "function", "points": 1, "params": {"rel_toll": 1}}]})",
        "unknown key \"rel_toll\"");
    fails_with(
        "negative_points",
        head +
            R"({"id": "a", "name": "n", "check": "generate_ray", "type": "function", "points": -1}]})",
        "non-negative");
    fails_with(
        "duplicate_id",
        head +
            R"({"id": "a", "name": "n", "check": "generate_ray", "type": "function", "points": 1},)" +
            R"({"id": "a", "name": "n", "check": "generate_ray", "type": "function", "points": 1}]})",
        "appears twice");
    fails_with("wrong_part", R"({"part": 2, "tasks": []})", "is 2 but the file is in part1/");
}

TEST_CASE("bad task parameters are the grader's error (InputError), not the student's") {
    std::string path = write_manifest("bad_image_case", R"({"part": 1, "tasks": [
        {"id": "x", "name": "n", "check": "image", "type": "image", "points": 1,
         "params": {"student_functions": ["camera.raytrace_pixl"],
                    "cases": [{"scene": "scenes/cbox_spheres.json", "integrator": "normals", "spp": 1}]}}]})");
    PartManifest m = read_manifest(path, 1);
    CHECK_THROWS_AS(grade_task(m.tasks[0], environment(reference_stages(), 1)), InputError);
}

TEST_CASE("isolated tasks: a crash or an endless loop fails only its task") {
    Stages s = reference_stages();
    s.intersect.intersect_sphere = [](const Sphere&, const Ray&) -> std::optional<Hit> {
        volatile int* null = nullptr;
        Hit hit;
        hit.t = *null;  // a segmentation fault
        return hit;
    };
    s.intersect.intersect_triangle = [](const Triangle&, const Ray&) -> std::optional<Hit> {
        for (volatile int i = 0;; i = i + 1) {
        }
    };
    GradeReport report = grade_all({part1_manifest()}, environment(s, 1), nullptr, 3.0);
    REQUIRE(report.tasks.size() == 4);
    CHECK(report.tasks[0].status == TaskStatus::pass);
    CHECK(report.tasks[1].status == TaskStatus::pass);
    CHECK(report.tasks[1].images.size() == 2);  // the result survives the trip through the pipe
    CHECK(report.tasks[2].status == TaskStatus::fail);
    CHECK(report.tasks[2].message.find("timed out") != std::string::npos);
    CHECK(report.tasks[3].status == TaskStatus::fail);
    CHECK(report.tasks[3].message.find("crashed") != std::string::npos);
    // Not implemented survives the trip too.
    Stages stubs = stub_stages();
    GradeReport stub_report = grade_all({part1_manifest()}, environment(stubs, 1), nullptr, 30.0);
    for (const TaskResult& t : stub_report.tasks)
        CHECK(t.status == TaskStatus::not_implemented);
}
