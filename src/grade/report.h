// The three reports `grade` writes into its output folder:
//
//   report.md    for a terminal, a pull request or an LMS comment
//   report.json  for scripts: per task part, id, name, type, status,
//                points, max_points, metric, value, comparison, threshold,
//                message, details, images (schema in docs/grading.md)
//   report.html  for graders: one self-contained page (images embedded as
//                data URIs) with the task table in colour and, for image
//                tasks, the student's render, the reference and the heat
//                map side by side with the numbers
//
// Image files referenced by the results (images/*.png) stay in the folder
// too, so that graders can run imgdiff on them.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "grade/grader.h"

namespace pt {

std::string markdown_report(const GradeReport& report);
nlohmann::json json_report(const GradeReport& report);
/// `out_dir` is where the images/ the results name are read from, to embed them.
std::string html_report(const GradeReport& report, const std::string& out_dir);

/// Writes report.md, report.json and report.html into `out_dir` (created
/// if needed); throws InputError when it cannot.
void write_reports(const GradeReport& report, const std::string& out_dir);

/// "12.5" or "25": points without trailing zeros.
std::string format_points(double points);
/// "3 <= 0", "relMSE 0.012 <= 0.03": the figure of a result, for tables.
std::string format_figure(const TaskResult& r);

}  // namespace pt
