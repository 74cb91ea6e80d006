// Shared set-up of the grading tests: the project's Part 1 manifest, an
// environment that grades a given table against the reference, and the
// test cache of converged references.
#pragma once

#include <cstring>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

#include "grade/grade_environment.h"
#include "grade/grader.h"
#include "grade/manifest.h"
#include "grade/stage_mix.h"

namespace pt::testing {

inline std::string source_dir() {
    return PT_SOURCE_DIR;
}
inline std::string output_dir() {
    return PT_TEST_OUTPUT_DIR;
}

/// The project's manifest of `part` (assignments/partN/grading.json).
inline const PartManifest& manifest(int part) {
    static std::map<int, PartManifest> read;
    auto it = read.find(part);
    if (it == read.end())
        it = read.emplace(part, read_manifest(source_dir() + "/assignments/part" +
                                                  std::to_string(part) + "/grading.json",
                                              part))
                 .first;
    return it->second;
}

inline const PartManifest& part1_manifest() {
    return manifest(1);
}

/// The parts with a manifest, in order.
inline std::vector<int> graded_parts() {
    return {1, 2, 3, 4, 5, 6, 7, 8, 9};
}

inline const Stages& reference_stages() {
    static const Stages s = make_stages(StageSet::none());
    return s;
}

/// Grades `student` against the reference with `seed`; images go to
/// `out_dir` only when it is given.
inline GradeEnvironment environment(const Stages& student, uint64_t seed,
                                    const std::string& out_dir = "") {
    return GradeEnvironment{student, reference_stages(),       seed,
                            2,       source_dir() + "/assets", output_dir() + "/grade_cache",
                            out_dir};
}

/// Whether two tables of one stage hold the same functions. Each stage is a
/// plain struct of function pointers, so equal bytes are equal functions;
/// padding, should a stage ever get some, could only make equal tables
/// compare unequal (a task graded that need not be), never the reverse.
template <class StageTable>
bool same_functions(const StageTable& a, const StageTable& b) {
    static_assert(std::is_trivially_copyable_v<StageTable>);
    return std::memcmp(&a, &b, sizeof(StageTable)) == 0;
}

inline bool same_functions(const Stages& a, const Stages& b) {
    return a.student == b.student && same_functions(a.camera, b.camera) &&
           same_functions(a.intersect, b.intersect) && same_functions(a.bvh, b.bvh) &&
           same_functions(a.adaptive, b.adaptive) && same_functions(a.direct, b.direct) &&
           same_functions(a.global, b.global) && same_functions(a.sampler, b.sampler) &&
           same_functions(a.media, b.media) && same_functions(a.photon, b.photon) &&
           same_functions(a.bdpt, b.bdpt);
}

/// Whether grading the image task `spec` with `student` runs the reference
/// only. An image task mixes just its student_functions into the reference
/// table (grade/stage_mix.h); when `student` left those as the reference's,
/// the task renders exactly what grading the reference as the student
/// renders, and test_full_marks proves that passes on seeds 1 to 20. The
/// fixture tests skip such tasks: they were most of the suite's time.
inline bool image_task_runs_only_reference(const TaskSpec& spec, const Stages& student) {
    if (spec.type != TaskType::image || !spec.params.contains("student_functions")) return false;
    const auto slots = spec.params["student_functions"].get<std::vector<std::string>>();
    return same_functions(mix_stages(reference_stages(), student, slots, spec.id),
                          mix_stages(reference_stages(), reference_stages(), slots, spec.id));
}

}  // namespace pt::testing
