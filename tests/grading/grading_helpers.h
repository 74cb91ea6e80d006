// Shared set-up of the grading tests: the project's Part 1 manifest, an
// environment that grades a given table against the reference, and the
// test cache of converged references.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "grade/grade_environment.h"
#include "grade/grader.h"
#include "grade/manifest.h"

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

}  // namespace pt::testing
