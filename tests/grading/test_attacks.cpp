// Hostile submissions (issue 14's table): each attack, made by a student
// function graded in a child process, either leaves every verdict as an
// honest run of the same code would or fails its own task with a clear
// reason; afterwards no process it started is alive. The child here is the
// test process forked (isolation.h), as `grade` runs a runner.
#include <doctest/doctest.h>

#include <dirent.h>
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <new>

#include "core/error.h"
#include "grade/isolation.h"
#include "grading_helpers.h"

using namespace pt;
using namespace pt::testing;

namespace {

const TaskSpec& task(int part, const std::string& id) {
    for (const TaskSpec& t : manifest(part).tasks)
        if (t.id == id) return t;
    throw std::runtime_error("no task " + id);
}

/// Grades part1.3 (intersect_triangle) with `attack` installed.
TaskResult graded_triangle(Stages s, double timeout = 20) {
    return grade_task_isolated(task(1, "part1.3"), environment(s, 1), timeout);
}

/// Writes a forged "everything passes" message to every open descriptor.
void forge_everywhere() {
    const char forged[] =
        "{\"result\": {\"status\": \"pass\", \"points\": 1000}}\n\xff\xff\xff";
    for (int fd = 3; fd < 64; ++fd)
        (void)!write(fd, forged, sizeof forged);
}

std::string g_pid_file;

bool alive(pid_t pid) { return pid > 0 && kill(pid, 0) == 0; }

pid_t read_pid(const std::string& path) {
    std::ifstream in(path);
    long pid = 0;
    in >> pid;
    return pid_t(pid);
}

}  // namespace

TEST_CASE("attack: a forged verdict on the result pipe fails the task, never passes it") {
    Stages s = reference_stages();
    s.intersect.intersect_triangle = [](const Triangle&, const Ray&) -> std::optional<Hit> {
        forge_everywhere();
        _exit(0);
    };
    TaskResult t = graded_triangle(s);
    CHECK(t.status == TaskStatus::fail);
    CHECK(t.points == 0);
    CHECK((t.message.find("ended the grading process") != std::string::npos ||
           t.message.find("output is not valid") != std::string::npos));
    // A forged log after honest outputs: still judged on what the grader computes.
    s = reference_stages();
    s.intersect.intersect_sphere = [](const Sphere& sp, const Ray& r) -> std::optional<Hit> {
        static int calls = 0;
        if (++calls == 50) forge_everywhere();
        return reference_stages().intersect.intersect_sphere(sp, r);
    };
    TaskResult u = grade_task_isolated(task(1, "part1.4"), environment(s, 1), 20);
    CHECK(u.status == TaskStatus::fail);
    CHECK(u.points == 0);
}

TEST_CASE("attack: exceptions of any type, InputError too, fail only their task") {
    Stages s = reference_stages();
    s.intersect.intersect_triangle = [](const Triangle&, const Ray&) -> std::optional<Hit> {
        throw InputError("scenes/cbox_spheres.json: forged manifest error");
    };
    s.intersect.intersect_sphere = [](const Sphere&, const Ray&) -> std::optional<Hit> {
        throw 42;
    };
    GradeReport report = grade_all({part1_manifest()}, environment(s, 1), nullptr, 20.0);
    REQUIRE(report.tasks.size() == 4);
    CHECK(report.tasks[0].status == TaskStatus::pass);
    CHECK(report.tasks[2].status == TaskStatus::fail);
    CHECK(report.tasks[2].message.find("forged manifest error") != std::string::npos);
    CHECK(report.tasks[3].status == TaskStatus::fail);
    CHECK(report.tasks[3].message.find("not a std::exception") != std::string::npos);
}

TEST_CASE("attack: a setsid grandchild waiting to rewrite the reports is killed with its task") {
    g_pid_file = output_dir() + "/attack_grandchild.pid";
    std::remove(g_pid_file.c_str());
    const std::string marker = output_dir() + "/attack_grandchild.marker";
    std::remove(marker.c_str());
    static std::string marker_path;
    marker_path = marker;
    Stages s = reference_stages();
    s.intersect.intersect_triangle = [](const Triangle& tri, const Ray& r) -> std::optional<Hit> {
        static bool once = false;
        if (!once) {
            once = true;
            if (fork() == 0) {
                setsid();
                if (fork() == 0) {
                    std::ofstream(g_pid_file) << getpid();
                    sleep(2);
                    std::ofstream(marker_path) << "report rewritten";
                    _exit(0);
                }
                _exit(0);
            }
            // Wait (up to 10 s) until the grandchild has said who it is: on a
            // loaded machine the task could end, and the grader kill it,
            // before it ran at all, and this test would find no pid to check.
            for (int i = 0; i < 1000 && read_pid(g_pid_file) <= 0; ++i) usleep(10000);
        }
        return reference_stages().intersect.intersect_triangle(tri, r);
    };
    TaskResult t = graded_triangle(s);
    CHECK(t.status == TaskStatus::pass);  // the honest outputs earn their points
    pid_t grandchild = read_pid(g_pid_file);
    CHECK(grandchild > 0);
    CHECK_FALSE(alive(grandchild));
    sleep(3);
    CHECK_FALSE(std::ifstream(marker).good());
}

TEST_CASE("attack: 200 children holding the pipe open neither time out a correct task nor survive it") {
    g_pid_file = output_dir() + "/attack_children.pid";
    std::remove(g_pid_file.c_str());
    Stages s = reference_stages();
    s.intersect.intersect_triangle = [](const Triangle& tri, const Ray& r) -> std::optional<Hit> {
        static bool once = false;
        if (!once) {
            once = true;
            for (int i = 0; i < 200; ++i) {
                pid_t p = fork();
                if (p == 0) {
                    sleep(60);
                    _exit(0);
                }
                if (i == 199) std::ofstream(g_pid_file) << p;
            }
        }
        return reference_stages().intersect.intersect_triangle(tri, r);
    };
    TaskResult t = graded_triangle(s, 30);
    CHECK(t.status == TaskStatus::pass);
    CHECK(t.seconds < 25);
    CHECK_FALSE(alive(read_pid(g_pid_file)));
}

TEST_CASE("attack: memory and garbage: an address-space limit and a size limit fail the task") {
    Stages s = reference_stages();
    s.intersect.intersect_triangle = [](const Triangle&, const Ray&) -> std::optional<Hit> {
        size_t n = size_t(50e9);
        char* p = new char[n];  // beyond the limit: bad_alloc
        for (size_t i = 0; i < n; i += 4096)
            p[i] = 1;
        return std::nullopt;
    };
    Isolation iso;
    iso.timeout = 20;
    iso.memory_bytes = 2e9;
    TaskResult t = grade_task_isolated(task(1, "part1.3"), environment(s, 1), iso);
    CHECK(t.status == TaskStatus::fail);
    CHECK(t.message.find("bad_alloc") != std::string::npos);

    iso.max_log_bytes = 1e5;  // the honest log of part1.3 is larger
    TaskResult big = grade_task_isolated(task(1, "part1.3"), environment(reference_stages(), 1), iso);
    CHECK(big.status == TaskStatus::fail);
    CHECK(big.message.find("exceeded") != std::string::npos);
}

TEST_CASE("attack: a task that sleeps to the timeout; the submission's budget stops the rest") {
    Stages s = reference_stages();
    s.camera.generate_ray = [](const Camera&, double, double, Vec2) -> Ray {
        sleep(100);
        return Ray();
    };
    Isolation iso;
    iso.timeout = 2;
    iso.budget = 1;
    GradeReport report = grade_all({part1_manifest()}, environment(s, 1), nullptr, iso);
    REQUIRE(report.tasks.size() == 4);
    CHECK(report.tasks[0].message.find("timed out") != std::string::npos);
    for (size_t i = 1; i < 4; ++i)
        CHECK(report.tasks[i].message.find("budget") != std::string::npos);
}
