// GradeEnvironment: what every check receives besides its TaskSpec: the
// two implementations to compare, and where things live.
//
// The student and reference tables are parameters, never globals, so that
// tests can grade any implementation in-process: the reference graded as a
// student (it must earn full marks) and deliberately wrong fixtures
// (tests/grading/fixtures/), which must fail exactly their task.
#pragma once

#include <cstdint>
#include <string>

#include "stages/stages.h"

namespace pt {

struct GradeEnvironment {
    const Stages&
        student;  ///< the implementation under test (make_stages(StageSet::all()) in `grade`)
    const Stages& reference;  ///< the reference (make_stages(StageSet::none()))
    uint64_t seed = 1;        ///< seeds the random inputs and the student's renders (--seed)
    int threads = 1;          ///< render threads (-t); results do not depend on it
    std::string assets_dir;   ///< scene paths in manifests are relative to this folder
    std::string cache_dir;    ///< converged reference renders are cached here ("" = no cache)
    std::string
        out_dir;  ///< the report folder: image checks write PNGs to out_dir/images ("" = none)
};

}  // namespace pt
