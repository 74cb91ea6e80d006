// bench: the instructor's timing tools, one subcommand per file.
//
// Each subcommand registers itself from its own source file with a static
// BenchCommandRegistration, so adding `bench accuracy` is one new file in
// src/apps/bench/ (the build globs the folder) and no edit elsewhere.
#pragma once

#include <string>
#include <vector>

namespace pt::bench {

/// Runs a subcommand on its arguments (those after the subcommand's name)
/// and returns the exit code. Throws InputError for bad arguments.
using BenchCommandFn = int (*)(const std::vector<std::string>& args);

struct BenchCommand {
    std::string name;     ///< the word after `bench`
    std::string usage;    ///< one line: "bvh [SCENES...] [--json FILE] ..."
    std::string summary;  ///< one line: what it measures
    BenchCommandFn run;
};

/// All registered subcommands, sorted by name.
std::vector<BenchCommand>& bench_commands();

/// Registers a subcommand at static-initialisation time:
///     static const BenchCommandRegistration kBvh({"bvh", "...", "...", run_bvh});
struct BenchCommandRegistration {
    explicit BenchCommandRegistration(BenchCommand command);
};

}  // namespace pt::bench
