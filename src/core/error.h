// The three kinds of failure the apps tell apart, one per exit code
// (DESIGN.md "Exit codes"): bad input (2), a student stage that is not
// implemented yet (3), and anything else (1).
#pragma once

#include <stdexcept>
#include <string>

namespace pt {

/// Bad input: a scene, mesh, image or flag that is wrong. The message names
/// the file (or flag), where in it, and what was expected. Exit code 2.
class InputError : public std::runtime_error {
public:
    explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

/// A student function that still throws from its handout stub. Exit code 3.
/// The message reads "Part N, task T: FUNCTION is not implemented yet".
class NotImplemented : public std::runtime_error {
public:
    NotImplemented(int part, const std::string& task, const std::string& function)
        : std::runtime_error("Part " + std::to_string(part) + ", task " + task + ": " + function +
                             " is not implemented yet"),
          part_(part) {}
    int part() const { return part_; }

private:
    int part_;
};

/// Exit codes of every executable (DESIGN.md contract).
enum ExitCode : int {
    kExitOk = 0,
    kExitFailure = 1,
    kExitBadInput = 2,
    kExitNotImplemented = 3,
};

}  // namespace pt
