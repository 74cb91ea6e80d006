// Calibration of the image rule, skipped in the normal suite (it grades
// hundreds of seeds). Run it with
//     build/tests/test_grading -tc="calibration*" --no-skip
// (PT_CALIBRATION_SEEDS=N changes the number of seeds, default 1000). It
// prints the distribution of the two statistics of the noise rule for the
// reference graded as a student, and the same figures for the Part 1
// fixtures: the false-failure rate and the margins in docs/grading.md.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "fixtures/fixtures.h"
#include "grading_helpers.h"

using namespace pt;
using namespace pt::testing;

namespace {

struct Figures {
    std::vector<double> ratio;    ///< student relMSE / reference relMSE, noisy case
    std::vector<double> worst_z;  ///< largest |z| of the tile test, noisy case
    int failures = 0;
};

double parse_figure(const std::string& text, const std::string& after) {
    size_t at = text.find(after);
    return at == std::string::npos ? NAN : std::atof(text.c_str() + at + after.size());
}

/// The manifest's image task, with PT_CALIBRATION_ALPHA and
/// PT_CALIBRATION_BIAS_SPP (noisy case) applied when they are set.
TaskSpec image_task() {
    TaskSpec image;
    for (const TaskSpec& t : part1_manifest().tasks)
        if (t.type == TaskType::image) image = t;
    if (const char* a = std::getenv("PT_CALIBRATION_ALPHA")) image.params["alpha"] = std::atof(a);
    if (const char* b = std::getenv("PT_CALIBRATION_BIAS_SPP"))
        image.params["cases"][1]["bias_spp"] = std::atoi(b);
    return image;
}

Figures measure(const Stages& student, int seeds) {
    Figures f;
    TaskSpec image = image_task();
    for (int seed = 1; seed <= seeds; ++seed) {
        TaskResult r = grade_task(image, environment(student, uint64_t(seed)));
        f.failures += r.status != TaskStatus::pass;
        const ImageCaseResult& noisy = r.images.back();
        for (const auto& [name, value] : noisy.numbers) {
            if (name == "student / reference relMSE") f.ratio.push_back(std::atof(value.c_str()));
            if (name == "worst tile") f.worst_z.push_back(parse_figure(value, "|z| = "));
        }
    }
    return f;
}

std::string summary(std::vector<double> v) {
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

}  // namespace

TEST_CASE("calibration: the reference and the fixtures over many seeds" * doctest::skip()) {
    int seeds =
        std::getenv("PT_CALIBRATION_SEEDS") ? std::atoi(std::getenv("PT_CALIBRATION_SEEDS")) : 1000;
    Figures ref = measure(reference_stages(), seeds);
    TaskSpec image = image_task();
    std::printf(
        "alpha %g, bias_spp %s\n", image.params["alpha"].get<double>(),
        image.params["cases"][1].value("bias_spp", nlohmann::json("default")).dump().c_str());
    std::printf("reference as student, %d seeds: %d failures\n  ratio:   %s\n  worst z: %s\n",
                seeds, ref.failures, summary(ref.ratio).c_str(), summary(ref.worst_z).c_str());
    for (const fixtures::Fixture& fx : fixtures::part1_fixtures()) {
        int n = std::min(seeds, 50);
        if (fx.failing_task == "part1.2") {
            Figures f = measure(fixtures::stages_with(fx), n);
            std::printf("%s, %d seeds: %d failures\n  ratio:   %s\n  worst z: %s\n",
                        fx.name.c_str(), n, f.failures, summary(f.ratio).c_str(),
                        summary(f.worst_z).c_str());
            continue;
        }
        int failures = 0;
        Stages student = fixtures::stages_with(fx);
        for (const TaskSpec& t : part1_manifest().tasks)
            if (t.id == fx.failing_task)
                for (int seed = 1; seed <= n; ++seed)
                    failures += grade_task(t, environment(student, uint64_t(seed))).status !=
                                TaskStatus::pass;
        std::printf("%s, %d seeds: %d failures of %s\n", fx.name.c_str(), n, failures,
                    fx.failing_task.c_str());
    }
}
