// The image check: renders the graded scenes with the student's functions
// switched in (params.student_functions, see stage_mix.h) and the
// reference everywhere else, and compares each render with a converged
// reference by the noise-aware rule of noise_rule.h. It is generic: a
// part's image tasks are manifest entries, no code.
//
// Manifest params:
//   "student_functions": ["camera.raytrace_pixel"]   the slots under test
//   "cases": [ ... ]            image cases (image_case.h)
//   "k", "floor", "alpha", "tile", "tau_rel"   the rule (noise_rule.h)
//   "reference_runs": 8         K, reference renders at the student's spp
//   "heatmap_low", "heatmap_high"   the heat map's relMSE scale
//
// The task passes when every case passes. Its figure is the worst case's
// student relMSE against that case's limit.
#pragma once

#include "grade/grade_environment.h"
#include "grade/task.h"

namespace pt {

TaskResult check_image(const TaskSpec& spec, const GradeEnvironment& env);

}  // namespace pt
