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

#include <map>
#include <tuple>

#include "core/counters.h"
#include "core/error.h"
#include "grade/bvh_inputs.h"
#include "grade/isolation.h"
#include "grade/random_inputs.h"
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

namespace {

/// part2.5 with fewer timed rays, so that a slow traversal costs the test little.
TaskSpec quick_performance_task() {
    TaskSpec spec = task(2, "part2.5");
    spec.params["timed_rays"] = 2000;
    spec.params["max_timed_seconds"] = 0.5;
    return spec;
}

using RayKey = std::tuple<double, double, double, double, double, double>;
RayKey key(const Ray& r) { return {r.o.x, r.o.y, r.o.z, r.d.x, r.d.y, r.d.z}; }
std::map<RayKey, std::optional<Hit>> g_answers;

/// The reference tree, after computing (by brute force, outside any timed
/// loop) the closest hit of every ray the check will time: the seed and the
/// ray generator are public, as they are to a student.
std::unique_ptr<BVHNode> construct_and_precompute(std::vector<BVHPrimitive>& p, size_t start,
                                                  size_t end, size_t max_leaf) {
    if (g_answers.empty()) {
        GradeEnvironment env = environment(reference_stages(), 1);
        Scene scene = load_graded_scene(env, "scenes/cbox_knot.json");
        Rng rng = check_rng(1, "bvh_performance");
        std::unique_ptr<Accelerator> scan = make_linear_scan(scene, reference_stages().intersect);
        for (const Ray& r : scene_rays(scene, reference_stages(), 2000, rng))
            g_answers[key(r)] = scan->intersect(r);
    }
    return reference::construct_bvh(p, start, end, max_leaf);
}

/// Answers from the table: no box or primitive test while it is timed.
std::optional<Hit> traverse_from_table(const BVHTree& bvh, const Ray& ray, const BVHNode* node) {
    auto it = g_answers.find(key(ray));
    return it != g_answers.end() ? it->second : reference::bvh_intersect(bvh, ray, node);
}

/// Tests every primitive under the node (never prunes), then rewinds the
/// counters that the runner used to read, so that it claims no work.
std::optional<Hit> traverse_all_and_rewind(const BVHTree& bvh, const Ray& ray,
                                           const BVHNode* node) {
    const RayCounters before = thread_counters();
    std::optional<Hit> best;
    for (size_t i = 0; i < bvh.primitives.size(); ++i) {
        std::optional<Hit> hit = bvh.intersect_primitive(i, ray);
        if (hit && BVHTree::closer(*hit, best)) best = hit;
    }
    thread_counters() = before;
    (void)node;
    return best;
}

}  // namespace

TEST_CASE("attack: part2.5's speed and counts cannot be forged inside the runner") {
    // Before the grader measured them itself, the runner timed the student's
    // traversal and read its counters: a table of precomputed answers made
    // the timed loop free (0 tests per ray), and a traversal that rewinds
    // the counters claimed no primitive tests. Now the counts come from the
    // grader's own traversal of the recorded tree and the time is the
    // runner's CPU time as the kernel counted it, precomputation included.
    Stages s = reference_stages();
    s.bvh.tree.construct_bvh = construct_and_precompute;
    s.bvh.tree.bvh_intersect = traverse_from_table;
    TaskResult t = grade_task_isolated(quick_performance_task(), environment(s, 1), 60);
    INFO(t.message);
    CHECK(t.status == TaskStatus::fail);
    CHECK(t.message.find("speedup") != std::string::npos);
    CHECK(t.message.find("counted by the kernel") != std::string::npos);
    CHECK(t.value > 1);  // the grader's count on the reference tree, not the table's 0

    s.bvh.tree.construct_bvh = reference::construct_bvh;
    s.bvh.tree.bvh_intersect = traverse_all_and_rewind;
    TaskResult u = grade_task_isolated(quick_performance_task(), environment(s, 1), 60);
    INFO(u.message);
    CHECK(u.status == TaskStatus::fail);
    CHECK(u.message.find("speedup") != std::string::npos);
    CHECK(u.value == t.value);  // the same tree: the same count, whatever the traversal claims

    // The honest reference passes the same task through the same path.
    TaskResult honest =
        grade_task_isolated(quick_performance_task(), environment(reference_stages(), 1), 60);
    INFO(honest.message);
    CHECK(honest.status == TaskStatus::pass);
    CHECK(honest.value == t.value);
}
