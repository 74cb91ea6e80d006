// Which runner grades a task: the runner executables (grade_runner_KEY,
// src/apps/grade_runner_main.cpp) hold the student's code and the reference
// of everything except the functions they withhold. A task runs in the
// runner that withholds the functions it grades, together with every
// reference function that calls one of them directly (and may have inlined
// it), so that the student code cannot call the reference of what it is
// graded on. src/CMakeLists.txt lists the same keys with their symbols.
#pragma once

#include <string>
#include <vector>

#include "grade/task.h"

namespace pt {

/// The runner key of a task ("generate_ray", "bvh", ...); throws InputError
/// naming the manifest when no runner grades its functions.
std::string runner_key(const TaskSpec& spec);

/// The stage slots (student_calls.h names) that runner `key` withholds.
std::vector<std::string> withheld_slots(const std::string& key);

/// Every runner key.
std::vector<std::string> runner_keys();

}  // namespace pt
