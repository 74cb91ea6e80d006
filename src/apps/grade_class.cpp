// grade --class SUBMISSIONS/ --out REPORTS/ [-j N] [--shard K/N], and
// grade --merge R1/ R2/ ... --out ALL/ (docs/grading.md, "Grading a
// class"). Per submission a worker builds its runners (grade/class_build.h)
// and runs this `grade` on them in a child process, which writes the
// student's reports; the worker adds results.json (Gradescope) and
// class.json. At the end the class's gradebook.csv and summary are made
// from what the student folders hold, which is also what --merge reads.
#include <unistd.h>

#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <thread>

#include "apps/grade_options.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/timer.h"
#include "grade/child_process.h"
#include "grade/class_build.h"
#include "grade/gradebook.h"
#include "grade/gradescope.h"
#include "grade/header_view.h"
#include "grade/manifest.h"
#include "grade/report.h"
#include "grade/runners.h"
#include "grade/submission.h"

namespace fs = std::filesystem;

namespace pt {
namespace {

std::string self_exe() {
    std::error_code ec;
    fs::path self = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw std::runtime_error("cannot find this executable (/proc/self/exe)");
    return self.string();
}

std::string join_parts(const std::vector<int>& parts, const std::string& prefix, const char* sep) {
    std::string out;
    for (int p : parts)
        out += (out.empty() ? "" : sep) + prefix + std::to_string(p);
    return out;
}

/// A folder as the user typed it, without trailing slashes, for messages.
std::string shown(std::string dir) {
    while (dir.size() > 1 && dir.back() == '/') dir.pop_back();
    return dir;
}

std::string duration(double s) {
    char buf[32];
    long t = long(std::lround(s));
    if (t >= 3600)
        std::snprintf(buf, sizeof buf, "%ldh%02ldm", t / 3600, (t / 60) % 60);
    else
        std::snprintf(buf, sizeof buf, "%ldm%02lds", t / 60, t % 60);
    return buf;
}

/// The manifests with --part and --task applied (as grade_main.cpp does).
std::vector<PartManifest> class_manifests(const GradeOptions& o) {
    std::vector<std::string> notes;
    std::vector<PartManifest> ms = read_manifests(o.manifests_dir, &notes);
    if (ms.empty()) throw InputError(o.manifests_dir + ": no partN/grading.json manifest in any part");
    std::vector<PartManifest> out;
    for (const PartManifest& m : ms) {
        if (!o.parts.empty() && std::find(o.parts.begin(), o.parts.end(), m.part) == o.parts.end())
            continue;
        PartManifest kept = m;
        if (!o.tasks.empty())
            kept.tasks.erase(std::remove_if(kept.tasks.begin(), kept.tasks.end(),
                                            [&](const TaskSpec& t) {
                                                return std::find(o.tasks.begin(), o.tasks.end(),
                                                                 t.id) == o.tasks.end();
                                            }),
                             kept.tasks.end());
        for (const TaskSpec& t : kept.tasks)
            runner_key(t);  // InputError (exit 2) for a task no runner grades
        if (!kept.tasks.empty()) out.push_back(kept);
    }
    for (const std::string& id : o.tasks)
        if (std::none_of(out.begin(), out.end(), [&](const PartManifest& m) {
                return std::any_of(m.tasks.begin(), m.tasks.end(),
                                   [&](const TaskSpec& t) { return t.id == id; });
            }))
            throw InputError("--task: no task '" + id + "' in the manifests");
    for (int p : o.parts)
        if (std::none_of(out.begin(), out.end(), [&](const PartManifest& m) { return m.part == p; }))
            throw InputError("--part: part " + std::to_string(p) + " has no manifest");
    return out;
}

/// A report written by this process, not by a grade of the student's code:
/// every task "not submitted" or failed with `why`.
GradeReport made_report(const std::vector<PartManifest>& manifests, const Submission& s,
                        const GradeOptions& o, const std::string& why) {
    GradeReport r;
    r.seed = o.seed;
    r.student_dir = s.dir;
    std::time_t now = std::time(nullptr);
    char date[64];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S", std::localtime(&now));
    r.date = date;
    for (const PartManifest& m : manifests) {
        r.parts.push_back("Part " + std::to_string(m.part) + (m.title.empty() ? "" : ": " + m.title));
        const bool submitted = std::find(s.parts.begin(), s.parts.end(), m.part) != s.parts.end();
        for (const TaskSpec& spec : m.tasks) {
            TaskResult t;
            t.part = spec.part, t.id = spec.id, t.name = spec.name, t.check = spec.check;
            t.type = spec.type, t.max_points = spec.points, t.value = NAN;
            t.status = submitted ? TaskStatus::fail : TaskStatus::not_submitted;
            t.message = submitted ? why
                                  : "not submitted: the submission has no part" +
                                        std::to_string(spec.part) + "/ folder with a .cpp file";
            r.tasks.push_back(t);
        }
    }
    return r;
}

struct ClassRun {
    const GradeOptions& o;
    std::vector<PartManifest> manifests;
    std::vector<Submission> todo;
    ClassBuildTools tools;
    std::string grade_exe, out_dir, build_dir;
    int child_threads = 1;
    bool progress = false;

    std::mutex mutex;
    std::condition_variable changed;
    size_t next = 0, done = 0;
    std::set<std::string> running;
    std::vector<StudentRecord> records;
    int internal_failures = 0;
    Timer timer;

    explicit ClassRun(const GradeOptions& options) : o(options) {}

    void clear_progress() {
        if (progress) std::fprintf(stderr, "\r\033[K");
    }
    /// One line on stderr, redrawn in place: done, running, elapsed, ETA.
    void draw_progress() {
        if (!progress) return;
        const double elapsed = timer.seconds();
        std::string eta = done ? duration(elapsed / double(done) * double(todo.size() - done)) : "?";
        std::string names;
        for (const std::string& n : running)
            names += (names.empty() ? "" : ", ") + n;
        if (names.size() > 40) names = names.substr(0, 37) + "...";
        std::fprintf(stderr, "\r\033[Kgrade: %zu/%zu submissions, %s elapsed, ETA %s%s%s", done,
                     todo.size(), duration(elapsed).c_str(), eta.c_str(),
                     names.empty() ? "" : "; now: ", names.c_str());
        std::fflush(stderr);
    }

    StudentRecord grade_one(const Submission& s, int slot) {
        StudentRecord rec;
        rec.name = s.name;
        const std::string dir = out_dir + "/" + s.name;
        std::error_code ec;
        fs::remove_all(dir, ec);
        fs::create_directories(dir, ec);

        std::vector<int> missing;
        std::vector<std::string> keys;
        for (const PartManifest& m : manifests) {
            if (std::find(s.parts.begin(), s.parts.end(), m.part) == s.parts.end()) {
                missing.push_back(m.part);
                continue;
            }
            for (const TaskSpec& t : m.tasks)
                if (std::find(keys.begin(), keys.end(), runner_key(t)) == keys.end())
                    keys.push_back(runner_key(t));
        }
        if (!missing.empty()) rec.note = "not submitted: " + join_parts(missing, "part", ", ");

        GradeReport report;
        if (keys.empty()) {
            report = made_report(manifests, s, o, "");
            write_reports(report, dir);
        } else {
            const std::string work = build_dir + "/slot" + std::to_string(slot);
            ClassBuildResult b = build_submission(tools, work, s, keys, dir + "/build.log");
            if (!b.ok && b.internal) {
                rec.outcome = "grading failed";
                rec.note = "the build of the runners failed (" + b.first_error + "; see build.log)";
                report = made_report(manifests, s, o, "not graded: " + rec.note);
                write_reports(report, dir);
                std::lock_guard<std::mutex> lock(mutex);
                ++internal_failures;
            } else if (!b.ok) {
                rec.outcome = "does not compile";
                rec.note = b.first_error + (missing.empty() ? "" : "; " + rec.note);
                report = made_report(manifests, s, o, "does not compile: " + b.first_error);
                report.notes.push_back("the submission does not compile; the build's output is in build.log");
                write_reports(report, dir);
            } else {
                std::vector<std::string> args = {grade_exe, "--runners", b.runner_dir, "--out", dir,
                                                 "--student-dir", s.dir, "-q",
                                                 "-t", std::to_string(child_threads),
                                                 "--seed", std::to_string(o.seed),
                                                 "--timeout", std::to_string(long(o.timeout)),
                                                 "--budget", std::to_string(long(o.budget)),
                                                 "--manifests", fs::absolute(o.manifests_dir).string(),
                                                 "--assets", fs::absolute(o.assets_dir).string()};
                if (!o.sandbox) args.push_back("--no-sandbox");
                if (o.cache_dir.empty()) args.push_back("--no-cache");
                else args.insert(args.end(), {"--cache", fs::absolute(o.cache_dir).string()});
                std::vector<int> graded;
                for (const PartManifest& m : manifests)
                    graded.push_back(m.part);
                args.insert(args.end(), {"--part", join_parts(graded, "", ",")});
                if (!o.tasks.empty()) {
                    std::string list;
                    for (const std::string& t : o.tasks)
                        list += (list.empty() ? "" : ",") + t;
                    args.insert(args.end(), {"--task", list});
                }
                if (!missing.empty()) args.insert(args.end(), {"--not-submitted", join_parts(missing, "", ",")});
                ChildOutcome c = run_child(args, dir + "/grade.log", 0);
                bool ok = c.started && (c.exit_code == 0 || c.exit_code == 1);
                if (ok) {
                    try {
                        StudentRecord from_disk;
                        write_class_json(rec, dir);
                        from_disk = read_student_record(dir);
                        report.tasks = from_disk.tasks;
                    } catch (const std::exception&) {
                        ok = false;
                    }
                }
                if (!ok) {
                    std::ifstream log(dir + "/grade.log");
                    std::string line, last;
                    while (std::getline(log, line))
                        if (!line.empty()) last = line;
                    rec.outcome = "grading failed";
                    rec.note = "grade failed on this submission (exit " + std::to_string(c.exit_code) +
                               (c.signal ? ", signal " + std::to_string(c.signal) : "") + ")" +
                               (last.empty() ? "" : ": " + last);
                    report = made_report(manifests, s, o, "not graded: " + rec.note);
                    write_reports(report, dir);
                    std::lock_guard<std::mutex> lock(mutex);
                    ++internal_failures;
                }
            }
        }
        write_class_json(rec, dir);
        write_file_atomically(dir + "/results.json",
                              gradescope_results(report, rec.outcome == "graded" ? "" : rec.outcome + ": " + rec.note)
                                      .dump(2) +
                                  "\n");
        rec.tasks = read_student_record(dir).tasks;
        return rec;
    }

    void worker(int slot) {
        for (;;) {
            size_t i;
            {
                std::lock_guard<std::mutex> lock(mutex);
                if (next >= todo.size()) return;
                i = next++;
                running.insert(todo[i].name);
                draw_progress();
            }
            Timer t;
            StudentRecord rec;
            try {
                rec = grade_one(todo[i], slot);
            } catch (const std::exception& e) {
                rec.name = todo[i].name;
                rec.outcome = "grading failed";
                rec.note = e.what();
                std::lock_guard<std::mutex> lock(mutex);
                ++internal_failures;
            }
            std::lock_guard<std::mutex> lock(mutex);
            running.erase(todo[i].name);
            ++done;
            if (!o.quiet) {
                clear_progress();
                std::printf("grade: %-20s %5s / %-4s %s%s%s (%.1f s)\n", rec.name.c_str(),
                            format_points(rec.points()).c_str(), format_points(rec.max_points()).c_str(),
                            rec.outcome.c_str(), rec.note.empty() ? "" : ": ", rec.note.c_str(),
                            t.seconds());
                std::fflush(stdout);
            }
            records.push_back(rec);
            draw_progress();
            changed.notify_all();
        }
    }
};

}  // namespace

int run_class(const GradeOptions& o) {
    if (!o.out_given) throw InputError("--class: --out DIR is required (where the reports go)");
    ClassRun run(o);
    run.manifests = class_manifests(o);
    std::vector<Submission> all = list_submissions(o.class_dir);
    for (size_t i = 0; i < all.size(); ++i)
        if (int(i % size_t(o.shards)) == o.shard - 1) run.todo.push_back(all[i]);
    run.out_dir = fs::absolute(o.out_dir).lexically_normal().string();
    std::error_code ec;
    fs::create_directories(run.out_dir, ec);
    if (!fs::is_directory(run.out_dir)) throw InputError("--out: cannot create the folder " + o.out_dir);
    run.build_dir = o.build_dir.empty() ? run.out_dir + "/.build"
                                        : fs::absolute(o.build_dir).lexically_normal().string();
    std::error_code ec2;
    if (!fs::exists(PT_CLASS_INITIAL_CACHE, ec2))
        throw InputError(std::string(PT_CLASS_INITIAL_CACHE) +
                         " is missing: configure the build folder of this grade again (cmake -S . -B BUILD)");

    const int hw = int(std::max(1u, std::thread::hardware_concurrency()));
    const int jobs = std::max(1, std::min<int>(o.jobs, int(std::max<size_t>(1, run.todo.size()))));
    run.tools = ClassBuildTools{PT_CMAKE_COMMAND, PT_CMAKE_GENERATOR, PT_CLASS_PROJECT_DIR,
                                PT_CLASS_INITIAL_CACHE, PT_DEFAULT_ASSIGNMENTS_DIR,
                                std::max(1, hw / jobs), o.build_timeout};
    // What a sandboxed compile reads besides the submission: the project's
    // headers (a copy of them only, bound at src/'s path: header_view.h)
    // and CMake files, the main build's trusted objects.
    const fs::path source = fs::path(PT_CLASS_PROJECT_DIR).parent_path().parent_path();
    const fs::path main_build = fs::path(PT_CLASS_INITIAL_CACHE).parent_path().parent_path();
    run.tools.sandbox = o.sandbox;
    run.tools.readable = {(source / "cmake").string(), (main_build / "src").string(),
                          (main_build / "grade_class").string()};
    run.tools.project_src = (source / "src").string();
    run.tools.header_view = run.build_dir + "/src_headers";
    make_header_view(run.tools.project_src, run.tools.header_view);
    run.child_threads = o.threads_given ? o.threads : std::max(1, hw / jobs);
    run.grade_exe = self_exe();
    run.progress = isatty(2) != 0 && !o.quiet;  // as the renderers' progress bar
    if (!o.quiet)
        std::printf("grade: %zu of %zu submissions in %s (shard %d/%d), %d at a time\n", run.todo.size(),
                    all.size(), shown(o.class_dir).c_str(), o.shard, o.shards, jobs);
    std::vector<std::thread> workers;
    for (int k = 0; k < jobs; ++k)
        workers.emplace_back([&run, k] { run.worker(k); });
    {
        // Redraw once a second so that the elapsed time and ETA move.
        std::unique_lock<std::mutex> lock(run.mutex);
        while (run.done < run.todo.size()) {
            run.changed.wait_for(lock, std::chrono::seconds(1));
            run.draw_progress();
        }
        run.clear_progress();
    }
    for (std::thread& w : workers)
        w.join();
    write_class_outputs(run.records, run.out_dir);
    if (!o.quiet)
        std::printf("grade: %zu submissions graded in %.1f s; gradebook %s/gradebook.csv, summary "
                    "%s/summary.html\n",
                    run.todo.size(), run.timer.seconds(), shown(o.out_dir).c_str(),
                    shown(o.out_dir).c_str());
    if (run.internal_failures)
        std::fprintf(stderr, "grade: %d submissions could not be graded (see the gradebook's note column)\n",
                     run.internal_failures);
    return run.internal_failures ? kExitFailure : kExitOk;
}

int run_merge(const GradeOptions& o) {
    if (!o.out_given) throw InputError("--merge: --out DIR is required (where the joined gradebook goes)");
    const fs::path out = fs::absolute(o.out_dir).lexically_normal();
    std::error_code ec;
    fs::create_directories(out, ec);
    if (!fs::is_directory(out)) throw InputError("--out: cannot create the folder " + o.out_dir);
    std::vector<StudentRecord> records;
    std::set<std::string> seen;
    for (const std::string& d : o.merge_dirs) {
        if (!fs::is_directory(d, ec)) throw InputError("--merge: " + d + " is not a folder");
        std::vector<fs::path> students;
        for (const fs::directory_entry& e : fs::directory_iterator(d, ec))
            if (e.is_directory(ec) && e.path().filename().string()[0] != '.' &&
                fs::exists(e.path() / "class.json", ec))
                students.push_back(e.path());
        if (students.empty())
            throw InputError("--merge: " + d + " holds no student folder of grade --class (NAME/class.json)");
        std::sort(students.begin(), students.end());
        for (const fs::path& p : students) {
            StudentRecord r = read_student_record(p.string());
            if (!seen.insert(r.name).second)
                throw InputError("--merge: student " + r.name + " is in more than one folder (again in " + d + ")");
            const fs::path target = out / p.filename();
            if (!fs::equivalent(p, target, ec)) {
                fs::remove_all(target, ec);
                fs::copy(p, target, fs::copy_options::recursive, ec);
                if (ec) throw InputError("--out: cannot copy " + p.string() + " to " + target.string() + ": " + ec.message());
            }
            records.push_back(r);
        }
    }
    write_class_outputs(records, out.string());
    if (!o.quiet)
        std::printf("grade: %zu students from %zu folders; gradebook %s/gradebook.csv, summary %s/summary.html\n",
                    records.size(), o.merge_dirs.size(), shown(o.out_dir).c_str(), shown(o.out_dir).c_str());
    return kExitOk;
}

}  // namespace pt
