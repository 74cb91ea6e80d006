// The Gradescope autograder's results.json for one student (the format
// Gradescope documents for autograders: a top-level score and output, and
// per test its name, number, score, max_score, status, output and
// visibility), written by `grade --class` beside the student's reports.
#pragma once

#include <nlohmann/json.hpp>

#include "grade/grader.h"

namespace pt {

/// `summary` is the top-level output (e.g. a compile error); "" for none.
nlohmann::json gradescope_results(const GradeReport& report, const std::string& summary);

}  // namespace pt
