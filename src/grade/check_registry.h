// The check registry: every grading routine the manifests can name, with
// its task type and the parameters it accepts.
//
// Adding a part's tasks is a matter of entries: a check routine written
// once per kind of student function (function and performance checks), or
// no code at all for image checks (the generic `image` check is configured
// entirely by the manifest), then a task in assignments/partN/grading.json
// naming the check. See docs/grading.md "Adding a part".
#pragma once

#include <string>
#include <vector>

#include "grade/grade_environment.h"
#include "grade/task.h"

namespace pt {

/// A check fills status (pass or fail), metric, value, comparison,
/// threshold, message, details and images; the grader fills the rest and
/// turns exceptions into "not implemented" (NotImplemented) or "fail".
using CheckFn = TaskResult (*)(const TaskSpec& spec, const GradeEnvironment& env);

struct CheckInfo {
    const char* name;  ///< what manifests write in "check"
    TaskType type;     ///< must match the manifest's "type"
    CheckFn run;
    std::vector<std::string> params;  ///< accepted keys of the manifest's "params"
    const char* summary;              ///< one line for `grade --list-checks` and the docs
};

/// The registered check named `name`, or nullptr.
const CheckInfo* find_check(const std::string& name);
/// Every registered check, in registration order.
const std::vector<CheckInfo>& all_checks();

}  // namespace pt
