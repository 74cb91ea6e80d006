// The main program shared by `pathtracer` and `part1` ... `part5`: they
// differ only in their name and in which stages default to student code.
#pragma once

#include <string>

#include "stages/stage_set.h"

namespace pt {

/// Parses the command line, loads the scene, renders it and writes the
/// outputs; returns the exit code (DESIGN.md "Exit codes").
int run_render_app(int argc, char** argv, const std::string& program, StageSet default_student);

}  // namespace pt
