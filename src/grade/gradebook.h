// The class outputs of `grade --class` and `grade --merge`: one record per
// student, read back from the student's folder (report.json and class.json),
// and from the records the gradebook (gradebook.csv: one row per student,
// one column per task, the total) and the class summary (summary.md and
// summary.html: score histogram, per-task pass rates, the most common
// failure message per task). Both depend only on the records, sorted by
// name, so that shards merged give the same bytes as one run.
#pragma once

#include <string>
#include <vector>

#include "grade/task.h"

namespace pt {

struct StudentRecord {
    std::string name;
    /// "graded", "does not compile" or "grading failed" (grade itself failed:
    /// not the student's doing; the row is 0 and says why).
    std::string outcome = "graded";
    std::string note;  ///< the compiler's first error, the parts not submitted, ...
    std::vector<TaskResult> tasks;
    double points() const;
    double max_points() const;
};

/// class.json in a student's report folder: name, outcome, note.
void write_class_json(const StudentRecord& r, const std::string& student_out_dir);
/// The record of a student's folder; throws InputError naming the file when
/// report.json or class.json is missing or malformed.
StudentRecord read_student_record(const std::string& student_out_dir);

std::string gradebook_csv(const std::vector<StudentRecord>& records);
std::string summary_markdown(const std::vector<StudentRecord>& records);
std::string summary_html(const std::vector<StudentRecord>& records);

/// gradebook.csv, summary.md and summary.html into `out_dir` (records
/// sorted by name first).
void write_class_outputs(std::vector<StudentRecord> records, const std::string& out_dir);

}  // namespace pt
