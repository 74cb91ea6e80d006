// A TaskResult as JSON and back: the per-task objects of report.json, and
// the message an isolated task sends from its child process (isolation.h).
// JSON has no NaN or infinity; an unmeasured value is written as null and
// read back as NaN.
#pragma once

#include <nlohmann/json.hpp>

#include "grade/task.h"

namespace pt {

nlohmann::json task_to_json(const TaskResult& task);
/// Reads what task_to_json wrote; throws nlohmann::json::exception on other input.
TaskResult task_from_json(const nlohmann::json& j);

}  // namespace pt
