// Tasks: what the grader grades (a TaskSpec, read from a part's manifest)
// and what it finds (a TaskResult, written to the reports).
//
// A task is one graded unit of one part, e.g. "part1.3 intersect_triangle".
// Its `check` names the C++ routine that grades it (check_registry.h); its
// `type` says how: a function check (deterministic, thousands of inputs
// against the reference), an image check (renders against a converged
// reference, noise-aware) or a performance check (hardware-independent
// counts and speedups). Points are all or nothing: a task that passes
// earns its points, any other outcome earns 0.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace pt {

enum class TaskType { function, image, performance };
const char* to_string(TaskType type);
/// Parses "function", "image", "performance"; throws InputError naming `where`.
TaskType parse_task_type(const std::string& text, const std::string& where);

/// One task as its part's manifest (assignments/partN/grading.json) describes it.
struct TaskSpec {
    int part = 0;       ///< course part, 1 to 5
    std::string id;     ///< "part1.3", matching the TODO(part1.3) marker of the stub
    std::string name;   ///< what the report calls it
    std::string check;  ///< the registered check that grades it (check_registry.h)
    TaskType type = TaskType::function;
    double points = 0;                                 ///< earned when the task passes
    nlohmann::json params = nlohmann::json::object();  ///< the check's thresholds and inputs
    std::string manifest;  ///< the file it came from, for error messages
};

/// not_submitted: the submission has no folder of the task's part (grade
/// --class); the task is not run.
enum class TaskStatus { pass, fail, not_implemented, not_submitted };
/// "pass", "fail", "not implemented", "not submitted".
const char* to_string(TaskStatus status);

/// One rendered comparison of an image task, with its pictures and figures.
struct ImageCaseResult {
    std::string label;  ///< e.g. "cbox_spheres, normals, 8 spp"
    bool pass = false;
    std::string message;  ///< the verdict in one sentence
    /// PNG file names relative to the report folder ("" when not written).
    std::string student_png, reference_png, reference_same_spp_png, heatmap_png;
    /// Figures in display order: name and formatted value.
    std::vector<std::pair<std::string, std::string>> numbers;
};

struct TaskResult {
    int part = 0;
    std::string id, name, check;
    TaskType type = TaskType::function;
    TaskStatus status = TaskStatus::fail;
    double points = 0;              ///< earned
    double max_points = 0;          ///< from the manifest
    std::string metric;             ///< what `value` measures, e.g. "mismatches", "relMSE ratio"
    double value = 0;               ///< the measured figure (NaN when nothing could be measured)
    std::string comparison = "<=";  ///< how value must compare with threshold to pass: "<=" or ">="
    double threshold = 0;           ///< the limit from the manifest (or the check's default)
    std::string message;            ///< one line: why it passed or failed
    std::vector<std::string> details;     ///< further lines: per-category counts, first mismatches
    std::vector<ImageCaseResult> images;  ///< image tasks: one per rendered case
    double seconds = 0;                   ///< time spent grading the task
    /// Points earned when the task fails but some of its case families
    /// (the manifest's "families") pass; 0 otherwise (case_log.h).
    double family_points = 0;
};

}  // namespace pt
