// grade --class, --shard and --merge (docs/grading.md, "Grading a class"):
// a class of four generated submissions, graded on three function tasks
// of two parts (cheap: three runners per submission, no renders):
//   alice  the TODO-steps solution (tests/grading/solution)     25 25 20 = 70
//   bob    the same, with t_min ignored in intersect_triangle   25  0 20 = 45
//   carol  the handout with a syntax error in part1/camera.cpp   0  0  0 (does not compile)
//   dave   the solution's part1/ only                           25 25  0 (part 2 not submitted)
// Graded once whole and once as two shards merged: the two gradebooks must
// be the same bytes. The workers' build folder is shared by the three runs,
// so only the first compiles.
#include <doctest/doctest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "grade/sandbox.h"

namespace fs = std::filesystem;

namespace {

const std::string kRoot = std::string(PT_TEST_OUTPUT_DIR) + "/grade_class";
const std::string kTasks = "part1.1,part1.3,part2.2";

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void replace_in_file(const std::string& path, const std::string& from, const std::string& to) {
    std::string text = slurp(path);
    const size_t at = text.find(from);
    REQUIRE_MESSAGE(at != std::string::npos, path << " no longer holds: " << from);
    text.replace(at, from.size(), to);
    std::ofstream(path, std::ios::binary) << text;
}

/// Runs `grade ARGS`; returns the exit code, stdout+stderr in *output.
int grade(const std::string& args, std::string* output = nullptr) {
    const std::string log = kRoot + "/last_command.txt";
    int status = std::system((std::string(PT_BIN_DIR) + "/grade " + args + " > " + log + " 2>&1").c_str());
    if (output) *output = slurp(log);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

void make_class(const std::string& dir) {
    const std::string src = PT_SOURCE_DIR;
    const std::string solution = src + "/tests/grading/solution";
    fs::remove_all(dir);
    fs::create_directories(dir);
    fs::copy(solution, dir + "/alice", fs::copy_options::recursive);
    fs::copy(solution, dir + "/bob", fs::copy_options::recursive);
    replace_in_file(dir + "/bob/part1/intersect.cpp",
                    "if (t < ray.t_min || t > ray.t_max) return std::nullopt;",
                    "if (t > ray.t_max) return std::nullopt;  // t_min forgotten");
    fs::create_directories(dir + "/carol/part1");
    fs::create_directories(dir + "/carol/part2");
    for (const char* f : {"part1/camera.cpp", "part1/intersect.cpp", "part2/bvh.cpp"})
        fs::copy(src + "/assignments/" + f, dir + "/carol/" + f);
    std::ofstream(dir + "/carol/part1/camera.cpp", std::ios::app) << "\nint broken(\n";
    fs::create_directories(dir + "/dave");
    fs::copy(solution + "/part1", dir + "/dave/part1", fs::copy_options::recursive);
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        out.push_back(line);
    return out;
}

}  // namespace

TEST_CASE("grade --class: gradebook, reports, Gradescope results; two shards merged give the same gradebook") {
    fs::create_directories(kRoot);
    const std::string subs = kRoot + "/submissions", work = kRoot + "/work";
    make_class(subs);
    for (const char* d : {"/whole", "/shard1", "/shard2", "/merged"})
        fs::remove_all(kRoot + d);
    const std::string common = " --task " + kTasks + " --build-dir " + work + " -j 2 -q";

    std::string output;
    REQUIRE_MESSAGE(grade("--class " + subs + " --out " + kRoot + "/whole" + common, &output) == 0, output);
    const std::string whole = slurp(kRoot + "/whole/gradebook.csv");
    const std::vector<std::string> rows = lines(whole);
    REQUIRE(rows.size() == 5);
    CHECK(rows[0] == "student,part1.1,part1.3,part2.2,total,max,outcome,note");
    CHECK(rows[1] == "alice,25,25,20,70,70,graded,");
    CHECK(rows[2] == "bob,25,0,20,45,70,graded,");
    CHECK(rows[3].rfind("carol,0,0,0,0,70,does not compile,", 0) == 0);
    CHECK(rows[3].find("part1/camera.cpp:") != std::string::npos);  // the compiler's first error,
    CHECK(rows[3].find("error:") != std::string::npos);              // its path relative to the submission
    CHECK(rows[4] == "dave,25,25,0,50,70,graded,not submitted: part2");

    // Per student: the three reports, results.json in Gradescope's format.
    for (const char* name : {"alice", "bob", "carol", "dave"})
        for (const char* f : {"report.md", "report.json", "report.html", "results.json", "class.json"})
            CHECK_MESSAGE(fs::exists(kRoot + "/whole/" + name + "/" + f), name << "/" << f);
    nlohmann::json gs = nlohmann::json::parse(slurp(kRoot + "/whole/bob/results.json"));
    CHECK(gs["score"].get<double>() == 45);
    REQUIRE(gs["tests"].size() == 3);
    CHECK(gs["tests"][1]["number"] == "part1.3");
    CHECK(gs["tests"][1]["score"].get<double>() == 0);
    CHECK(gs["tests"][1]["max_score"].get<double>() == 25);
    CHECK(gs["tests"][1]["visibility"] == "visible");
    CHECK(gs["tests"][1]["output"].get<std::string>().rfind("fail: ", 0) == 0);
    nlohmann::json dave = nlohmann::json::parse(slurp(kRoot + "/whole/dave/report.json"));
    CHECK(dave["tasks"][2]["status"] == "not submitted");
    const std::string summary = slurp(kRoot + "/whole/summary.md");
    CHECK(summary.find("- students: 4 (3 graded, 1 do not compile") != std::string::npos);
    CHECK(summary.find("| part1.3 | Ray-triangle intersection (intersect_triangle) | 25 | 2 (50%) | 1 |") !=
          std::string::npos);
    CHECK(fs::exists(kRoot + "/whole/summary.html"));

    // Two shards (alice, carol | bob, dave), then merged.
    REQUIRE_MESSAGE(grade("--class " + subs + " --out " + kRoot + "/shard1 --shard 1/2" + common, &output) == 0,
                    output);
    REQUIRE_MESSAGE(grade("--class " + subs + " --out " + kRoot + "/shard2 --shard 2/2" + common, &output) == 0,
                    output);
    CHECK(lines(slurp(kRoot + "/shard1/gradebook.csv")).size() == 3);
    REQUIRE_MESSAGE(grade("--merge " + kRoot + "/shard1 " + kRoot + "/shard2 --out " + kRoot + "/merged -q",
                          &output) == 0,
                    output);
    CHECK(slurp(kRoot + "/merged/gradebook.csv") == whole);
    CHECK(slurp(kRoot + "/merged/summary.md") == summary);
    CHECK(fs::exists(kRoot + "/merged/dave/report.html"));

    // A student in two shards is refused.
    CHECK(grade("--merge " + kRoot + "/shard1 " + kRoot + "/whole --out " + kRoot + "/twice -q", &output) == 2);
    CHECK(output.find("alice") != std::string::npos);
}

TEST_CASE("grade --class and --merge: bad arguments are one line and exit 2") {
    fs::create_directories(kRoot);
    std::string output;
    for (const std::string& args :
         {std::string("--class ") + kRoot + "/no_such_folder --out " + kRoot + "/x",
          std::string("--class ") + PT_SOURCE_DIR + "/assignments",  // no --out
          std::string("--class ") + PT_SOURCE_DIR + " --out " + kRoot + "/x --shard 3/2",
          std::string("--class ") + PT_SOURCE_DIR + " --out " + kRoot + "/x --shard two",
          std::string("-j 2 --out ") + kRoot + "/x",
          std::string("--merge --out ") + kRoot + "/x",
          std::string("--merge ") + kRoot + "/no_such_folder --out " + kRoot + "/x"}) {
        CHECK_MESSAGE(grade(args, &output) == 2, args);
        CHECK_MESSAGE(lines(output).size() == 1, args << ": " << output);
        CHECK_MESSAGE(output.rfind("grade: error: ", 0) == 0, args << ": " << output);
    }
}

TEST_CASE("scripts/gradescope/run_autograder: an upload in either layout gives results.json") {
    // Gradescope's layout in a temporary root: submission/ holds part 1's
    // files side by side, part2/bvh.cpp in its folder and a stray file.
    const std::string src = PT_SOURCE_DIR, solution = src + "/tests/grading/solution";
    const std::string root = kRoot + "/autograder";
    fs::remove_all(root);
    fs::create_directories(root + "/submission/part2");
    fs::copy(solution + "/part1/camera.cpp", root + "/submission/camera.cpp");
    fs::copy(solution + "/part1/intersect.cpp", root + "/submission/intersect.cpp");
    fs::copy(solution + "/part2/bvh.cpp", root + "/submission/part2/bvh.cpp");
    std::ofstream(root + "/submission/notes.txt") << "not a handout file\n";
    const std::string run = "PT_AUTOGRADER_ROOT='" + root + "' PT_GRADE='" + PT_BIN_DIR +
                            "/grade' PT_GRADE_ARGS='--task " + kTasks + " --build-dir " + kRoot +
                            "/work' " + src + "/scripts/gradescope/run_autograder";
    REQUIRE(std::system((run + " > " + root + "/log.txt 2>&1").c_str()) == 0);
    nlohmann::json r = nlohmann::json::parse(slurp(root + "/results/results.json"));
    CHECK(r["score"].get<double>() == 70);
    REQUIRE(r["tests"].size() == 3);
    CHECK(r["tests"][2]["number"] == "part2.2");

    // An upload without any handout file: a score of 0 that says why.
    fs::remove_all(root + "/submission");
    fs::create_directories(root + "/submission");
    std::ofstream(root + "/submission/notes.txt") << "nothing\n";
    REQUIRE(std::system((run + " > " + root + "/log.txt 2>&1").c_str()) == 0);
    r = nlohmann::json::parse(slurp(root + "/results/results.json"));
    CHECK(r["score"].get<double>() == 0);
    CHECK(r["output"].get<std::string>().find("none of the handout's files") != std::string::npos);
}

namespace {

/// part1/camera.cpp that compiles the reference's camera.cpp under another
/// name (`reference` renamed by the preprocessor) and returns its answers:
/// the link's withheld stand-ins cannot see it, only what the compile reads.
const char* kStolenCamera = R"(// The reference's camera, compiled here under another name.
#define reference stolen
#include "INCLUDED"
#undef reference

namespace pt::student {
Ray generate_ray(const Camera& camera, double x, double y, Vec2 lens_sample) {
    return stolen::generate_ray(camera, x, y, lens_sample);
}
PixelResult raytrace_pixel(const RenderContext& context, int x, int y) {
    return stolen::raytrace_pixel(context, x, y);
}
}  // namespace pt::student
)";

/// A class of three: gina includes the reference's src/stages/camera.cpp
/// through the include path, hank through a symbolic link in his folder
/// that a header name points at it, alice is the honest solution.
std::string make_thieves(const std::string& dir) {
    const std::string src = PT_SOURCE_DIR;
    fs::remove_all(dir);
    fs::create_directories(dir);
    fs::create_directories(dir + "/alice");
    fs::copy(src + "/tests/grading/solution/part1", dir + "/alice/part1", fs::copy_options::recursive);
    for (const char* name : {"gina", "hank"}) {
        fs::create_directories(dir + "/" + name + "/part1");
        fs::copy(src + "/assignments/part1/intersect.cpp", dir + "/" + name + "/part1/intersect.cpp");
        std::string text = kStolenCamera;
        text.replace(text.find("INCLUDED"), 8, name == std::string("gina") ? "stages/camera.cpp" : "camera_impl.h");
        std::ofstream(dir + "/" + name + "/part1/camera.cpp") << text;
    }
    fs::create_symlink(src + "/src/stages/camera.cpp", dir + "/hank/part1/camera_impl.h");
    return dir;
}

}  // namespace

TEST_CASE("grade --class: a submission cannot compile a reference .cpp of src/ under another name") {
    // Inside bubblewrap the compile sees a headers-only view of src/; with
    // --no-sandbox the compiler's dependency lists are checked after the
    // build (there gina's stolen camera compiles and links: the check is
    // what refuses it). A symbolic link is refused in both.
    const std::string dir = make_thieves(kRoot + "/thieves");
    const bool bwrap = !pt::build_sandbox_prefix({}, {}, true).empty();
    for (const std::string mode : {"", " --no-sandbox"}) {
        INFO("mode:" << mode);
        std::string output;
        const int code = grade("--class " + dir + " --out " + kRoot + "/thieves_out --task part1.1 --build-dir " +
                                   kRoot + "/work -q" + mode,
                               &output);
        REQUIRE_MESSAGE(code == 0, output);
        const std::vector<std::string> rows = lines(slurp(kRoot + "/thieves_out/gradebook.csv"));
        REQUIRE(rows.size() == 4);
        INFO(rows[2] << "\n" << rows[3]);
        CHECK(rows[1] == "alice,25,25,25,graded,");  // honest: unaffected
        CHECK(rows[2].rfind("gina,0,0,25,does not compile,", 0) == 0);
        if (mode.empty() && bwrap)
            CHECK(rows[2].find("fatal error: stages/camera.cpp: No such file or directory (the compile sees "
                               "only the project's headers: a .cpp of src/ cannot be included)") !=
                  std::string::npos);
        else
            CHECK(rows[2].find("part1/camera.cpp includes src/stages/camera.cpp, a source file of the "
                               "project: only its headers may be included") != std::string::npos);
        CHECK(rows[3].rfind("hank,0,0,25,does not compile,", 0) == 0);
        CHECK(rows[3].find("the submission holds a symbolic link, part1/camera_impl.h (a link to ") !=
              std::string::npos);
    }
}

TEST_CASE("grade --class: a hostile compile fails that student's build with its reason") {
    // erin includes /dev/zero (the compiler reads without end: the memory
    // limit stops it); frank includes a file of the grader's (the sandbox
    // does not have it; outside bubblewrap the compiler would quote it).
    const std::string src = PT_SOURCE_DIR, dir = kRoot + "/hostile";
    fs::remove_all(dir);
    for (const char* name : {"erin", "frank"}) {
        fs::create_directories(dir + "/" + name + "/part1");
        for (const char* f : {"camera.cpp", "intersect.cpp"})
            fs::copy(src + "/assignments/part1/" + f, dir + "/" + name + "/part1/" + f);
    }
    std::ofstream(dir + "/erin/part1/camera.cpp", std::ios::app) << "\n#include \"/dev/zero\"\n";
    std::ofstream(dir + "/frank/part1/camera.cpp", std::ios::app) << "\n#include \"/etc/hostname\"\n";
    std::string output;
    const int code = grade("--class " + dir + " --out " + kRoot + "/hostile_out --task part1.1 --build-dir " +
                               kRoot + "/work -q",
                           &output);
    REQUIRE_MESSAGE(code == 0, output);
    const std::vector<std::string> rows = lines(slurp(kRoot + "/hostile_out/gradebook.csv"));
    REQUIRE(rows.size() == 3);
    INFO(rows[1] << "\n" << rows[2]);
    CHECK(rows[1].rfind("erin,0,0,25,does not compile,", 0) == 0);
    CHECK(rows[1].find("out of memory") != std::string::npos);
    CHECK(rows[2].rfind("frank,0,0,25,does not compile,", 0) == 0);
    if (!pt::build_sandbox_prefix({}, {}, true).empty())
        CHECK(rows[2].find("/etc/hostname: No such file or directory") != std::string::npos);
}

namespace {

/// Gives `path` a modification time of 2000-01-01, older than any object
/// a build folder can hold (as unzip, tar or cp -p keep a file's time).
void make_old(const std::string& path) {
    REQUIRE(std::system(("touch -d 2000-01-01 '" + path + "'").c_str()) == 0);
}

/// part1/intersect.cpp of the solution, or with `bug` (from -> to) in it, made old.
void write_intersect(const std::string& dir, const std::pair<std::string, std::string>* bug) {
    fs::create_directories(dir + "/part1");
    fs::copy_file(std::string(PT_SOURCE_DIR) + "/tests/grading/solution/part1/intersect.cpp",
                  dir + "/part1/intersect.cpp", fs::copy_options::overwrite_existing);
    if (bug) replace_in_file(dir + "/part1/intersect.cpp", bug->first, bug->second);
    make_old(dir + "/part1/intersect.cpp");
}

}  // namespace

TEST_CASE("grade --class: files older than the build folder's objects are still compiled") {
    // make and ninja rebuild an object only when its source is newer. One
    // worker (-j 1) grades amy, then ben, whose file is dated 2000; then
    // both resubmit into the same folders (dated 2000 again, as unzip keeps
    // them) and the class is graded again with the same build folder. Each
    // report must be that of the code submitted at the time.
    const std::pair<std::string, std::string> barycentric = {"b1 + b2 > 1", "b1 > 1 || b2 > 1"};
    const std::pair<std::string, std::string> t_min = {"if (t < ray.t_min || t > ray.t_max) return std::nullopt;",
                                                       "if (t > ray.t_max) return std::nullopt;"};
    const std::string dir = kRoot + "/old_files", out = kRoot + "/old_files_out";
    fs::remove_all(dir);
    fs::remove_all(out);
    write_intersect(dir + "/amy", nullptr);
    fs::last_write_time(dir + "/amy/part1/intersect.cpp", fs::file_time_type::clock::now());
    write_intersect(dir + "/ben", &barycentric);
    const std::string args = "--class " + dir + " --out " + out + " --task part1.3 -j 1 -q";
    std::string output;
    REQUIRE_MESSAGE(grade(args, &output) == 0, output);
    std::vector<std::string> rows = lines(slurp(out + "/gradebook.csv"));
    REQUIRE(rows.size() == 3);
    CHECK(rows[1] == "amy,25,25,25,graded,");
    CHECK(rows[2] == "ben,0,0,25,graded,");  // ben's own bug, not amy's objects

    // The resubmissions: amy now forgets t_min, ben is right.
    write_intersect(dir + "/amy", &t_min);
    write_intersect(dir + "/ben", nullptr);
    REQUIRE_MESSAGE(grade(args, &output) == 0, output);
    rows = lines(slurp(out + "/gradebook.csv"));
    REQUIRE(rows.size() == 3);
    CHECK(rows[1] == "amy,0,0,25,graded,");
    CHECK(rows[2] == "ben,25,25,25,graded,");
    const nlohmann::json amy = nlohmann::json::parse(slurp(out + "/amy/report.json"));
    CHECK(amy["tasks"][0]["status"] == "fail");
}

TEST_CASE("grade --class: a student's static initializers run only in the sandboxed runner") {
    // ivan: the solution's camera with a static initializer that writes into
    // the reports folder and registers an atexit handler that would too
    // (issue 14: once both ran in grade itself); jack: one that raises
    // SIGSEGV before main. ivan's verdict must be the honest one and no file
    // of his may appear (the runner sees no reports folder and ends with
    // _exit); jack fails his task with the signal, and the run still writes
    // every report.
    const std::string src = PT_SOURCE_DIR, dir = kRoot + "/static_init", out = kRoot + "/static_init_out";
    fs::remove_all(dir);
    fs::remove_all(out);
    for (const char* name : {"ivan", "jack"}) {
        fs::create_directories(dir + "/" + name);
        fs::copy(src + "/tests/grading/solution/part1", dir + "/" + name + "/part1", fs::copy_options::recursive);
    }
    std::ofstream(dir + "/ivan/part1/camera.cpp", std::ios::app)
        << "\n#include <cstdio>\n#include <cstdlib>\nnamespace {\nconst int forged = [] {\n"
        << "    std::atexit([] { if (FILE* f = std::fopen(\"" << out << "/forged_atexit\", \"w\")) std::fclose(f); });\n"
        << "    if (FILE* f = std::fopen(\"" << out << "/forged_static\", \"w\")) std::fclose(f);\n"
        << "    return 0;\n}();\n}  // namespace\n";
    std::ofstream(dir + "/jack/part1/camera.cpp", std::ios::app)
        << "\n#include <csignal>\nnamespace {\nconst int crash = (std::raise(SIGSEGV), 0);\n}  // namespace\n";
    std::string output;
    REQUIRE_MESSAGE(grade("--class " + dir + " --out " + out + " --task part1.1 --build-dir " + kRoot + "/work -q",
                          &output) == 0,
                    output);
    const std::vector<std::string> rows = lines(slurp(out + "/gradebook.csv"));
    REQUIRE(rows.size() == 3);
    CHECK(rows[1] == "ivan,25,25,25,graded,");
    CHECK(rows[2] == "jack,0,0,25,graded,");
    for (const char* name : {"ivan", "jack"})
        for (const char* f : {"report.md", "report.json", "report.html", "results.json"})
            CHECK_MESSAGE(fs::exists(out + "/" + name + "/" + f), name << "/" << f);
    const nlohmann::json jack = nlohmann::json::parse(slurp(out + "/jack/report.json"));
    INFO(jack["tasks"][0]["message"]);
    CHECK(jack["tasks"][0]["status"] == "fail");
    CHECK(jack["tasks"][0]["message"].get<std::string>().find("Segmentation fault") != std::string::npos);
    CHECK_FALSE(fs::exists(out + "/forged_atexit"));  // never run: the runner ends with _exit
    if (!pt::build_sandbox_prefix({}, {}, true).empty())
        CHECK_FALSE(fs::exists(out + "/forged_static"));  // the sandbox has no reports folder
}

TEST_CASE("grade --class: a fork bomb stops at the sandbox's process limit") {
    // kate's static initializer forks up to 1000 children that sleep; it
    // aborts (failing her task) unless fork started failing between 100 and
    // 1000 children: the sandbox allows 256 processes and threads, counted
    // in its own user namespace (root is exempt from the limit: grade runs
    // the sandbox as nobody). Without the limit all 1000 start.
    const std::string src = PT_SOURCE_DIR, dir = kRoot + "/fork_bomb", out = kRoot + "/fork_bomb_out";
    fs::remove_all(dir);
    fs::create_directories(dir + "/kate");
    fs::copy(src + "/tests/grading/solution/part1", dir + "/kate/part1", fs::copy_options::recursive);
    std::ofstream(dir + "/kate/part1/camera.cpp", std::ios::app)
        << "\n#include <cstdlib>\n#include <unistd.h>\nnamespace {\nconst int bomb = [] {\n"
        << "    int made = 0;\n"
        << "    for (int i = 0; i < 1000; ++i) {\n"
        << "        const pid_t p = fork();\n"
        << "        if (p == 0) { sleep(30); _exit(0); }\n"
        << "        if (p > 0) ++made;\n"
        << "    }\n"
        << "    if (made < 100 || made >= 1000) std::abort();\n"
        << "    return made;\n}();\n}  // namespace\n";
    std::string output;
    REQUIRE_MESSAGE(grade("--class " + dir + " --out " + out + " --task part1.1 --build-dir " + kRoot + "/work -q",
                          &output) == 0,
                    output);
    const std::string report = slurp(out + "/kate/report.md");
    const std::vector<std::string> rows = lines(slurp(out + "/gradebook.csv"));
    REQUIRE(rows.size() == 2);
    if (report.find("at most 256 processes and threads") == std::string::npos) {
        MESSAGE("no process limit in this sandbox (no user namespace for it): not checked");
        return;
    }
    INFO(report);
    CHECK(rows[1] == "kate,25,25,25,graded,");
}
