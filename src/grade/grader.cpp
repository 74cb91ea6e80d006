#include "grade/grader.h"

#include <algorithm>
#include <cmath>
#include <ctime>

#include "core/error.h"
#include "core/stub_fallback.h"
#include "core/timer.h"
#include "grade/check_registry.h"
#include "grade/isolation.h"
#include "grade/student_calls.h"

namespace pt {

double GradeReport::points() const {
    double p = 0;
    for (const TaskResult& t : tasks)
        p += t.points;
    return p;
}

double GradeReport::max_points() const {
    double p = 0;
    for (const TaskResult& t : tasks)
        p += t.max_points;
    return p;
}

bool GradeReport::all_passed() const {
    if (tasks.empty()) return false;
    for (const TaskResult& t : tasks)
        if (t.status != TaskStatus::pass) return false;
    return true;
}

TaskResult grade_task(const TaskSpec& spec, const GradeEnvironment& env) {
    Timer timer;
    const CheckInfo* check = find_check(spec.check);
    if (!check)
        throw InputError(spec.manifest + ": task " + spec.id + ": unknown check \"" + spec.check +
                         "\"");
    TaskResult r;
    try {
        // A handout stub's slow fallback (Part 2's linear scan) must not earn
        // the points of the code it stands in for: it throws NotImplemented.
        StubFallbacksAreNotImplemented strict;
        r = check->run(spec, env);
    } catch (const NotImplemented& e) {
        r = TaskResult{};
        r.status = TaskStatus::not_implemented;
        r.value = NAN;
        r.message = printable(e.what());
    } catch (const InputError&) {
        throw;
    } catch (const RunnerOutputError& e) {
        r = TaskResult{};
        r.status = TaskStatus::fail;
        r.value = NAN;
        r.message = printable(e.what());
    } catch (const std::exception& e) {
        r = TaskResult{};
        r.status = TaskStatus::fail;
        r.value = NAN;
        r.message = "the student code threw an exception: " + printable(e.what());
    }
    r.part = spec.part;
    r.id = spec.id;
    r.name = spec.name;
    r.check = spec.check;
    r.type = spec.type;
    r.max_points = spec.points;
    r.points = r.status == TaskStatus::pass ? spec.points
                                            : std::min(std::max(r.family_points, 0.0), spec.points);
    r.seconds = timer.seconds();
    return r;
}

GradeReport grade_all(const std::vector<PartManifest>& manifests, const GradeEnvironment& env,
                      void (*on_task)(const TaskResult&), double isolate_timeout) {
    if (isolate_timeout > 0) {
        Isolation iso;
        iso.timeout = isolate_timeout;
        return grade_all(manifests, env, on_task, iso);
    }
    Isolation in_process;  // timeout 0: no limit
    in_process.timeout = 0;
    return grade_all(manifests, env, on_task, in_process);
}

GradeReport grade_all(const std::vector<PartManifest>& manifests, const GradeEnvironment& env,
                      void (*on_task)(const TaskResult&), const Isolation& isolation) {
    Timer timer;
    GradeReport report;
    report.seed = env.seed;
    std::time_t now = std::time(nullptr);
    char date[64];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S", std::localtime(&now));
    report.date = date;
    for (const PartManifest& m : manifests) {
        report.parts.push_back("Part " + std::to_string(m.part) +
                               (m.title.empty() ? "" : ": " + m.title));
        for (const TaskSpec& spec : m.tasks) {
            if (isolation.budget > 0 && timer.seconds() > isolation.budget) {
                TaskResult r;
                r.part = spec.part, r.id = spec.id, r.name = spec.name, r.check = spec.check;
                r.type = spec.type, r.max_points = spec.points, r.value = NAN;
                r.message = "not run: the submission's time budget of " +
                            std::to_string(long(isolation.budget)) + " s is spent";
                report.tasks.push_back(r);
                if (on_task) on_task(report.tasks.back());
                continue;
            }
            report.tasks.push_back(isolation.timeout > 0
                                       ? grade_task_isolated(spec, env, isolation)
                                       : grade_task(spec, env));
            if (on_task) on_task(report.tasks.back());
        }
    }
    report.seconds = timer.seconds();
    return report;
}

}  // namespace pt
