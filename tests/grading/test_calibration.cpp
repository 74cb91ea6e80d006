// Calibration of the image rule, skipped in the normal suite (it grades
// hundreds of seeds). Run it with
//     build/tests/test_grading -tc="calibration*" --no-skip
// Environment: PT_CALIBRATION_SEEDS=N (default 1000) seeds for the
// reference, PT_CALIBRATION_PARTS=1,3,5 (default 1) the parts whose image
// tasks are measured, PT_CALIBRATION_STUDENT=textbook to grade CS184's
// has_converged (no rare-event guard) instead of the reference,
// PT_CALIBRATION_TASKS=part3.5,... to measure only these tasks,
// PT_CALIBRATION_CASES='sky|every kind' only the cases whose label contains
// one of these (a task with none keeps all its cases),
// PT_CALIBRATION_ALPHA and PT_CALIBRATION_BIAS_SPP to try other rules,
// PT_CALIBRATION_FIRST_SEED=S to grade seeds S..S+N-1 (scripts/false_failure.sh
// splits a run over processes so), PT_CALIBRATION_FIXTURES=0 to skip the fixtures,
// PT_CALIBRATION_FUNCTIONS=1 to measure the selected function tasks too (their
// task failures: deterministic checks whose cases are drawn from the seed).
// It prints, per image case, the distribution of the two statistics of the
// noise rule (error ratio and worst tile |z|) for the reference graded as a
// student, and then the failure count of every fixture of those parts over
// min(N, 50) seeds with the same figures for image tasks: the
// false-failure rate and the power in docs/grading.md.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>

#include "fixtures/fixtures.h"
#include "grading_helpers.h"

using namespace pt;
using namespace pt::testing;

namespace pt::fixtures {
bool textbook_has_converged(const PixelStatistics& s, double tol);
}

namespace {

struct Figures {
    std::vector<double> ratio;     ///< student relMSE / reference relMSE
    std::vector<double> worst_z;   ///< largest |z| of the tile test
    std::vector<double> mean_spp;  ///< mean samples per pixel (adaptive cases)
    int failures = 0;
};

double parse_figure(const std::string& text, const std::string& after) {
    size_t at = text.find(after);
    return at == std::string::npos ? NAN : std::atof(text.c_str() + at + after.size());
}

/// A task with PT_CALIBRATION_ALPHA and PT_CALIBRATION_BIAS_SPP applied.
TaskSpec calibrated(TaskSpec t) {
    if (t.type != TaskType::image) return t;
    if (const char* only = std::getenv("PT_CALIBRATION_CASES")) {  // label substrings, '|'-separated
        nlohmann::json kept = nlohmann::json::array();
        std::string list = std::string("|") + only + "|";
        for (const auto& c : t.params["cases"]) {
            const std::string label = c.value("label", std::string());
            for (size_t a = 0, b; (b = list.find('|', a + 1)) != std::string::npos; a = b)
                if (b > a + 1 && label.find(list.substr(a + 1, b - a - 1)) != std::string::npos) {
                    kept.push_back(c);
                    break;
                }
        }
        if (!kept.empty()) t.params["cases"] = kept;
    }
    if (const char* a = std::getenv("PT_CALIBRATION_ALPHA")) t.params["alpha"] = std::atof(a);
    if (const char* b = std::getenv("PT_CALIBRATION_BIAS_SPP"))
        for (auto& c : t.params["cases"])
            if (c.value("converged_spp", 1024) != c["spp"].get<int>()) c["bias_spp"] = std::atoi(b);
    return t;
}

/// Grades `task` on seeds first..first+seeds-1; figures per case (by case index).
std::map<size_t, Figures> measure(const TaskSpec& task, const Stages& student, int seeds,
                                  int* task_failures, int first = 1) {
    std::map<size_t, Figures> f;
    *task_failures = 0;
    for (int seed = first; seed < first + seeds; ++seed) {
        TaskResult r = grade_task(task, environment(student, uint64_t(seed)));
        *task_failures += r.status != TaskStatus::pass;
        if (r.status != TaskStatus::pass)  // which seed, and why: to find what fails
            std::printf("  seed %d fails: %s\n", seed, r.message.c_str());
        for (size_t i = 0; i < r.images.size(); ++i) {
            Figures& c = f[i];
            c.failures += !r.images[i].pass;
            for (const auto& [name, value] : r.images[i].numbers) {
                if (name == "student / reference relMSE")
                    c.ratio.push_back(std::atof(value.c_str()));
                if (name == "worst tile") c.worst_z.push_back(parse_figure(value, "|z| = "));
                if (name == "mean samples per pixel (student)")
                    c.mean_spp.push_back(std::atof(value.c_str()));
            }
        }
    }
    return f;
}

std::string summary(std::vector<double> v) {
    if (v.empty()) return "-";
    std::sort(v.begin(), v.end());
    double mean = 0, var = 0;
    for (double x : v)
        mean += x / v.size();
    for (double x : v)
        var += (x - mean) * (x - mean) / std::max<size_t>(v.size() - 1, 1);
    char buf[200];
    size_t n = v.size();
    std::snprintf(buf, sizeof buf,
                  "min %.3f, median %.3f, mean %.3f, sd %.3f, 99%% %.3f, top three %.3f %.3f %.3f",
                  v.front(), v[n / 2], mean, std::sqrt(var), v[size_t(0.99 * (n - 1))],
                  v[n - std::min<size_t>(n, 3)], v[n - std::min<size_t>(n, 2)], v.back());
    return buf;
}

void print(const std::string& who, const TaskSpec& task, const std::map<size_t, Figures>& f,
           int seeds, int task_failures) {
    std::printf("%s, %s, %d seeds: %d task failures\n", who.c_str(), task.id.c_str(), seeds,
                task_failures);
    for (const auto& [i, c] : f) {
        std::printf("  case %zu (%s): %d failures\n    ratio:   %s\n    worst z: %s\n", i + 1,
                    task.params["cases"][i].value("label", std::string("?")).c_str(), c.failures,
                    summary(c.ratio).c_str(), summary(c.worst_z).c_str());
        if (!c.mean_spp.empty()) std::printf("    mean spp: %s\n", summary(c.mean_spp).c_str());
    }
    std::fflush(stdout);
}

bool selected(const std::string& id) {
    const char* list = std::getenv("PT_CALIBRATION_TASKS");
    return !list || ("," + std::string(list) + ",").find("," + id + ",") != std::string::npos;
}

std::vector<int> parts_to_measure() {
    std::vector<int> parts;
    std::stringstream list(std::getenv("PT_CALIBRATION_PARTS") ? std::getenv("PT_CALIBRATION_PARTS")
                                                               : "1");
    std::string item;
    while (std::getline(list, item, ','))
        parts.push_back(std::atoi(item.c_str()));
    return parts;
}

}  // namespace

TEST_CASE("calibration: the reference and the fixtures over many seeds" * doctest::skip()) {
    const char* env_seeds = std::getenv("PT_CALIBRATION_SEEDS");
    const int seeds = env_seeds ? std::atoi(env_seeds) : 1000;
    const char* env_first = std::getenv("PT_CALIBRATION_FIRST_SEED");
    const int first = env_first ? std::atoi(env_first) : 1;
    const char* env_fixtures = std::getenv("PT_CALIBRATION_FIXTURES");
    const bool with_fixtures = !env_fixtures || std::string(env_fixtures) != "0";
    const char* env_functions = std::getenv("PT_CALIBRATION_FUNCTIONS");
    const bool with_functions = env_functions && std::string(env_functions) == "1";
    Stages reference = reference_stages();
    std::string who = "reference as student";
    if (const char* s = std::getenv("PT_CALIBRATION_STUDENT"); s && std::string(s) == "textbook") {
        reference.adaptive.has_converged = fixtures::textbook_has_converged;
        who = "textbook has_converged as student";
    }
    for (int part : parts_to_measure()) {
        for (const TaskSpec& t : manifest(part).tasks) {
            if ((t.type != TaskType::image && !with_functions) || !selected(t.id)) continue;
            int failures = 0;
            TaskSpec task = calibrated(t);
            auto f = measure(task, reference, seeds, &failures, first);
            print(who, task, f, seeds, failures);
        }
        if (!with_fixtures) continue;
        const int n = std::min(seeds, 50);
        for (const fixtures::Fixture& fx : fixtures::fixtures_of_part(part)) {
            for (const TaskSpec& t : manifest(part).tasks) {
                if (!fx.fails(t.id) || !selected(t.id)) continue;
                int failures = 0;
                TaskSpec task = calibrated(t);
                auto f = measure(task, fixtures::stages_with(fx), n, &failures);
                if (task.type == TaskType::image)
                    print("fixture '" + fx.name + "'", task, f, n, failures);
                else
                    std::printf("fixture '%s', %s, %d seeds: %d task failures\n", fx.name.c_str(),
                                task.id.c_str(), n, failures);
            }
        }
    }
}
