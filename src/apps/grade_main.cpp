// grade: grades the student stages of this build (made with
// -DPT_STUDENT_DIR=...) against the reference, task by task, from the
// manifests assignments/partN/grading.json, and writes report.md,
// report.json and report.html into --out DIR. Exit codes: 0 every task
// passes, 1 some task fails or is not implemented, 2 bad input (flags,
// manifests, scenes). See docs/grading.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <thread>

#include "apps/grade_options.h"
#include "apps/number_flags.h"
#include "core/error.h"
#include "grade/check_registry.h"
#include "grade/grader.h"
#include "grade/isolation.h"
#include "grade/manifest.h"
#include "grade/runners.h"
#include "grade/sandbox.h"
#include "grade/report.h"

namespace pt {
namespace {

const char* kUsage =
    "usage: grade [--out DIR] [--seed N] [--part N,...] [--task ID,...] [-t N] [-q] [--timeout S]\n"
    "             [--budget S] [--no-sandbox]\n"
    "             [--cache DIR | --no-cache] [--manifests DIR] [--assets DIR] [--list-checks]\n"
    "       grade --class SUBMISSIONS/ --out REPORTS/ [-j N] [--shard K/N] [--build-dir DIR]\n"
    "             [--build-timeout S] [the flags above]\n"
    "       grade --merge REPORTS1/ REPORTS2/ ... --out ALL/\n"
    "Grades the student code this build was made with (-DPT_STUDENT_DIR) against the reference;\n"
    "with --class, every subfolder of SUBMISSIONS/ (one student's copy of assignments/, or of\n"
    "some of its parts), each built against this build (docs/grading.md).\n"
    "  --out DIR        where report.md, report.json, report.html and images/ go    "
    "[grade_report]\n"
    "  --seed N         seeds the random inputs and the student's renders           [1]\n"
    "  --part N,...     grade only these parts                                      [all with a "
    "manifest]\n"
    "  --task ID,...    grade only these tasks, e.g. part1.3                        [all]\n"
    "  -t N             render threads (results do not depend on it)               [all cores]\n"
    "  -q               no per-task lines\n"
    "  --timeout S      each task runs in a runner process (with the student code,\n"
    "                   never in grade) and fails after S seconds; 0 = no limit    [600]\n"
    "  --budget S       wall-clock seconds for all tasks; later tasks fail unrun [no limit]\n"
    "  --no-sandbox     no bubblewrap around the runners (setrlimit and a process group\n"
    "                   only; used anyway where bwrap cannot run)\n"
    "  --cache DIR      converged reference renders are cached here                 "
    "[BUILD/grade_cache]\n"
    "  --no-cache       render the references anew\n"
    "  --manifests DIR  the folder with partN/grading.json                          [the project's "
    "assignments/]\n"
    "  --assets DIR     scene paths in the manifests are relative to it             [the project's "
    "assets/]\n"
    "  --list-checks    list the registered checks and their parameters\n"
    "  --class DIR      grade every subfolder of DIR into --out DIR/NAME/, plus gradebook.csv\n"
    "                   and summary.{md,html} in --out\n"
    "  -j N             --class: submissions built and graded at a time              [1]\n"
    "  --shard K/N      --class: grade only every N-th submission (by name), from the K-th\n"
    "  --build-timeout S  --class: seconds per configure and build of a submission   [600]\n"
    "  --build-dir DIR  --class: the workers' build folders (reused by later runs;\n"
    "                   never two runs at once)                                   [OUT/.build]\n"
    "  --merge DIR...   join the --out folders of shards into --out: one gradebook\n"
    "  --runners DIR, --student-dir DIR, --not-submitted N,...   (what --class passes to the\n"
    "                   grade of one submission: its runners, its folder, its missing parts)\n"
    "Exit codes: 0 every task passes, 1 some task fails or is not implemented, 2 bad input.\n";

std::vector<std::string> split(const std::string& list) {
    std::vector<std::string> out;
    std::stringstream s(list);
    std::string item;
    while (std::getline(s, item, ','))
        if (!item.empty()) out.push_back(item);
    return out;
}

GradeOptions parse(const std::vector<std::string>& args) {
    GradeOptions o;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        auto value = [&]() -> const std::string& {
            if (i + 1 >= args.size()) throw InputError(a + ": missing value");
            return args[++i];
        };
        if (a == "-h" || a == "--help") {
            o.help = true;
        } else if (a == "--list-checks") {
            o.list_checks = true;
        } else if (a == "-q") {
            o.quiet = true;
        } else if (a == "--out") {
            o.out_dir = value();
            o.out_given = true;
        } else if (a == "--class") {
            o.class_dir = value();
        } else if (a == "-j") {
            o.jobs = int(parse_whole_number(a, value(), 1, 256));
        } else if (a == "--shard") {
            const std::string v = value();
            const size_t slash = v.find('/');
            if (slash == std::string::npos)
                throw InputError("--shard: expected K/N (e.g. 2/4), got '" + v + "'");
            o.shards = int(parse_whole_number("--shard N", v.substr(slash + 1), 1, 100000));
            o.shard = int(parse_whole_number("--shard K", v.substr(0, slash), 1, o.shards));
        } else if (a == "--build-dir") {
            o.build_dir = value();
        } else if (a == "--build-timeout") {
            o.build_timeout = double(parse_whole_number(a, value(), 1, 86400));
        } else if (a == "--merge") {
            while (i + 1 < args.size() && !args[i + 1].empty() && args[i + 1][0] != '-')
                o.merge_dirs.push_back(args[++i]);
            if (o.merge_dirs.empty()) throw InputError("--merge: expected one or more report folders");
        } else if (a == "--runners") {
            o.runners_dir = value();
        } else if (a == "--student-dir") {
            o.student_dir = value();
        } else if (a == "--not-submitted") {
            for (const std::string& p : split(value()))
                o.not_submitted.push_back(int(parse_whole_number("--not-submitted", p, 1, 1000)));
        } else if (a == "--seed") {
            o.seed = uint64_t(parse_whole_number(a, value(), 0, (1ll << 62)));
        } else if (a == "-t") {
            o.threads = int(parse_whole_number(a, value(), 1, 1024));
            o.threads_given = true;
        } else if (a == "--timeout") {
            o.timeout = double(parse_whole_number(a, value(), 0, 86400));
        } else if (a == "--budget") {
            o.budget = double(parse_whole_number(a, value(), 0, 864000));
        } else if (a == "--no-sandbox") {
            o.sandbox = false;
        } else if (a == "--cache") {
            o.cache_dir = value();
        } else if (a == "--no-cache") {
            o.cache_dir.clear();
        } else if (a == "--manifests") {
            o.manifests_dir = value();
        } else if (a == "--assets") {
            o.assets_dir = value();
        } else if (a == "--part") {
            for (const std::string& p : split(value()))
                o.parts.push_back(int(parse_whole_number("--part", p, kFirstPart, kLastPart)));
        } else if (a == "--task") {
            o.tasks = split(value());
        } else {
            throw InputError("unknown argument '" + a + "' (grade --help lists the flags)");
        }
    }
    if (o.out_dir.empty()) throw InputError("--out: expected a folder");
    if (!o.class_dir.empty() && !o.merge_dirs.empty())
        throw InputError("--class and --merge: one or the other");
    if (o.class_dir.empty() && (o.jobs != 1 || o.shards != 1))
        throw InputError(o.jobs != 1 ? "-j: only with --class" : "--shard: only with --class");
    return o;
}

/// The folder of this executable: the runners are built next to it.
std::string runner_dir() {
    std::error_code ec;
    std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
    return ec ? std::string(".") : self.parent_path().string();
}

void print_task(const TaskResult& t) {
    const char* word = t.status == TaskStatus::pass   ? "PASS"
                       : t.status == TaskStatus::fail ? "FAIL"
                       : t.status == TaskStatus::not_submitted ? "NOT SUBMITTED"
                                                               : "NOT IMPLEMENTED";
    std::printf("grade: %-8s %-15s %5s / %-4s %s: %s\n", t.id.c_str(), word,
                format_points(t.points).c_str(), format_points(t.max_points).c_str(),
                t.name.c_str(), t.message.c_str());
    std::fflush(stdout);
}

int run(const GradeOptions& o) {
    if (o.list_checks) {
        for (const CheckInfo& c : all_checks()) {
            std::string params;
            for (const std::string& p : c.params)
                params += (params.empty() ? "" : ", ") + p;
            std::printf("%-20s %-12s %s\n%-33s params: %s\n", c.name, to_string(c.type), c.summary,
                        "", params.c_str());
        }
        return kExitOk;
    }
    std::vector<std::string> notes;
    std::vector<PartManifest> manifests = read_manifests(o.manifests_dir, &notes);
    if (manifests.empty())
        throw InputError(o.manifests_dir + ": no partN/grading.json manifest in any part");
    if (!o.parts.empty()) {
        for (int p : o.parts)
            if (std::none_of(manifests.begin(), manifests.end(),
                             [&](const PartManifest& m) { return m.part == p; }))
                throw InputError("--part: part " + std::to_string(p) + " has no manifest");
        manifests.erase(std::remove_if(manifests.begin(), manifests.end(),
                                       [&](const PartManifest& m) {
                                           return std::find(o.parts.begin(), o.parts.end(),
                                                            m.part) == o.parts.end();
                                       }),
                        manifests.end());
    }
    if (!o.tasks.empty()) {
        for (const std::string& id : o.tasks) {
            bool found = false;
            for (const PartManifest& m : manifests)
                for (const TaskSpec& t : m.tasks)
                    found = found || t.id == id;
            if (!found) throw InputError("--task: no task '" + id + "' in the manifests");
        }
        for (PartManifest& m : manifests)
            m.tasks.erase(std::remove_if(m.tasks.begin(), m.tasks.end(),
                                         [&](const TaskSpec& t) {
                                             return std::find(o.tasks.begin(), o.tasks.end(),
                                                              t.id) == o.tasks.end();
                                         }),
                          m.tasks.end());
    }

    // grade holds no student code: `student` is a placeholder that the
    // replay of each runner's log replaces (grade/isolation.h).
    Stages student = make_stages(StageSet::none());
    Stages reference = make_stages(StageSet::none());
    GradeEnvironment env{student,      reference,   o.seed,   o.threads,
                         o.assets_dir, o.cache_dir, o.out_dir};
    for (const PartManifest& m : manifests)
        for (const TaskSpec& t : m.tasks)
            runner_key(t);  // every task has a runner (InputError, exit 2, otherwise)
    Isolation iso;
    iso.timeout = o.timeout > 0 ? o.timeout : 1e9;
    iso.budget = o.budget;
    const std::string runners =
        o.runners_dir.empty() ? runner_dir() : std::filesystem::absolute(o.runners_dir).string();
    const std::string assets = std::filesystem::absolute(o.assets_dir).string();
    Sandbox sandbox = make_sandbox({runners, assets, std::filesystem::absolute(o.manifests_dir).string()},
                                   o.sandbox);
    iso.sandbox_prefix = sandbox.prefix;
    iso.uid = sandbox.uid;
    iso.gid = sandbox.gid;
    notes.push_back("isolation of the student code: " + sandbox.description);
    iso.runner = [&](const TaskSpec& t) {
        return std::vector<std::string>{runners + "/grade_runner_" + runner_key(t),
                                        "--manifest", std::filesystem::absolute(t.manifest).string(),
                                        "--task", t.id,
                                        "--seed", std::to_string(o.seed),
                                        "--threads", std::to_string(o.threads),
                                        "--assets", assets};
    };
    const std::string student_dir = o.student_dir.empty() ? PT_STUDENT_DIR_PATH : o.student_dir;
    if (!o.quiet)
        std::printf("grade: student code %s, seed %llu\n", student_dir.c_str(),
                    (unsigned long long)o.seed);
    // The parts a class submission lacks (--not-submitted, from --class) are
    // not run; their tasks are listed as "not submitted" in manifest order.
    auto missing = [&](int part) {
        return std::find(o.not_submitted.begin(), o.not_submitted.end(), part) != o.not_submitted.end();
    };
    std::vector<PartManifest> submitted;
    for (const PartManifest& m : manifests)
        if (!missing(m.part)) submitted.push_back(m);
    GradeReport report = grade_all(submitted, env, o.quiet ? nullptr : print_task, iso);
    std::vector<TaskResult> all;
    report.parts.clear();
    for (const PartManifest& m : manifests) {
        report.parts.push_back("Part " + std::to_string(m.part) + (m.title.empty() ? "" : ": " + m.title));
        for (const TaskSpec& t : m.tasks) {
            if (!missing(m.part)) {
                for (const TaskResult& r : report.tasks)
                    if (r.id == t.id) all.push_back(r);
                continue;
            }
            TaskResult r;
            r.part = t.part, r.id = t.id, r.name = t.name, r.check = t.check, r.type = t.type;
            r.status = TaskStatus::not_submitted, r.max_points = t.points, r.value = NAN;
            r.message = "not submitted: the submission has no part" + std::to_string(t.part) +
                        "/ folder with a .cpp file";
            all.push_back(r);
            if (!o.quiet) print_task(r);
        }
    }
    report.tasks = all;
    report.notes.insert(report.notes.begin(), notes.begin(), notes.end());
    report.student_dir = student_dir;
    write_reports(report, o.out_dir);
    std::printf(
        "grade: %s / %s points, %s; reports in %s/report.{md,html,json} (%.1f s)\n",
        format_points(report.points()).c_str(), format_points(report.max_points()).c_str(),
        report.all_passed() ? "every task passes" : "some tasks fail or are not implemented",
        o.out_dir.c_str(), report.seconds);
    return report.all_passed() ? kExitOk : kExitFailure;
}

}  // namespace
}  // namespace pt

int main(int argc, char** argv) {
    using namespace pt;
    try {
        GradeOptions o = parse(std::vector<std::string>(argv + 1, argv + argc));
        if (o.help) {
            std::cout << kUsage;
            return kExitOk;
        }
        if (!o.class_dir.empty()) return run_class(o);
        if (!o.merge_dirs.empty()) return run_merge(o);
        return run(o);
    } catch (const InputError& e) {
        std::cerr << "grade: error: " << e.what() << "\n";
        return kExitBadInput;
    } catch (const std::exception& e) {
        std::cerr << "grade: internal error: " << e.what() << "\n";
        return kExitFailure;
    }
}
