// The one place that turns a tool's exceptions into DESIGN.md's exit codes:
// bad input -> one "PROGRAM: error: ..." line and exit 2, a stage left to the
// student -> exit 3, anything else -> "internal error" and exit 1. Every
// small tool's main() is `return pt::run_tool("name", argc, argv, run);`.
#pragma once

#include <iostream>
#include <string>
#include <vector>

#include "core/error.h"

namespace pt {

template <typename Run>
int run_tool(const std::string& program, int argc, char** argv, Run run) {
    try {
        return run(std::vector<std::string>(argv + 1, argv + argc));
    } catch (const InputError& e) {
        std::cerr << program << ": error: " << e.what() << "\n";
        return kExitBadInput;
    } catch (const NotImplemented& e) {
        std::cerr << program << ": " << e.what() << "\n";
        return kExitNotImplemented;
    } catch (const std::exception& e) {
        std::cerr << program << ": internal error: " << e.what() << "\n";
        return kExitFailure;
    }
}

}  // namespace pt
