// The test cache of converged references (grading_helpers.h), filled once
// before the grading tests that read it: ctest runs this file first (the
// fixture "grade_cache", tests/CMakeLists.txt). Without it test_fixtures
// and test_full_marks, which ctest starts together, would each render every
// image case's 1024-spp reference (about a minute of both cores each).
//
// It checks what every image task relies on: each reference is finite,
// holds the samples it claims, and comes back from the disk cache bit for
// bit once the process has forgotten it.
#include <doctest/doctest.h>

#include <cmath>

#include "grade/image_case.h"
#include "grade/reference_renders.h"
#include "grading_helpers.h"

using namespace pt;
using namespace pt::testing;

namespace {

bool all_finite(const Image& image, bool non_negative) {
    for (float v : image.data())
        if (!std::isfinite(v) || (non_negative && v < 0)) return false;
    return true;
}

/// Calls `f(case, label)` for every case of every image task of every part.
template <class F>
void for_each_image_case(F f) {
    for (int part : graded_parts())
        for (const TaskSpec& spec : manifest(part).tasks) {
            if (spec.type != TaskType::image) continue;
            const nlohmann::json& cases = spec.params.at("cases");
            for (size_t i = 0; i < cases.size(); ++i) {
                const std::string label = spec.id + " case " + std::to_string(i + 1);
                f(parse_image_case(cases[i], label), label);
            }
        }
}

}  // namespace

TEST_CASE("every image case's converged reference: finite, its samples, cached bit for bit") {
    const GradeEnvironment env = environment(reference_stages(), 1);
    std::vector<Image> rendered;
    for_each_image_case([&](const ImageCase& c, const std::string& label) {
        INFO(label);
        ReferenceRenders r = reference_renders(load_case_scene(c, env.assets_dir), c, 0, env);
        CHECK(all_finite(r.converged, false));
        CHECK(all_finite(r.sample_variance, true));
        // 64 batches of converged_spp / 64 (all of them when fewer than 64).
        CHECK(r.converged_spp <= c.converged_spp);
        CHECK(r.converged_spp > c.converged_spp - 64);
        rendered.push_back(r.converged);
    });
    CHECK(rendered.size() >= 20);

    size_t i = 0;
    for_each_image_case([&](const ImageCase& c, const std::string& label) {
        INFO(label);
        forget_converged_in_memory();  // read from disk, not from this process's memory
        ReferenceRenders r = reference_renders(load_case_scene(c, env.assets_dir), c, 0, env);
        CHECK(r.from_cache);
        CHECK(r.converged.data() == rendered.at(i++).data());
    });
}
