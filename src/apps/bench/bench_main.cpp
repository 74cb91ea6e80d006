// bench: dispatches `bench SUBCOMMAND [ARGS...]` to the registered
// subcommands (bench_command.h) and turns errors into exit codes.
#include <algorithm>
#include <iostream>

#include "apps/bench/bench_command.h"
#include "core/error.h"

namespace pt::bench {

std::vector<BenchCommand>& bench_commands() {
    static std::vector<BenchCommand> commands;  // built before main, read after
    return commands;
}

BenchCommandRegistration::BenchCommandRegistration(BenchCommand command) {
    auto& commands = bench_commands();
    commands.push_back(std::move(command));
    std::sort(commands.begin(), commands.end(),
              [](const BenchCommand& a, const BenchCommand& b) { return a.name < b.name; });
}

namespace {

void print_usage(std::ostream& out) {
    out << "usage: bench SUBCOMMAND [options]\n\n";
    for (const BenchCommand& c : bench_commands())
        out << "  bench " << c.usage << "\n      " << c.summary << "\n";
    out << "\n`bench SUBCOMMAND --help` describes its options.\n"
        << "exit codes: 0 ok, 1 failure, 2 bad input\n";
}

}  // namespace
}  // namespace pt::bench

int main(int argc, char** argv) {
    using namespace pt;
    using namespace pt::bench;
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty()) {
        std::cerr << "bench: error: no subcommand given (see bench --help)\n";
        return kExitBadInput;
    }
    if (args[0] == "-h" || args[0] == "--help") {
        print_usage(std::cout);
        return kExitOk;
    }
    const BenchCommand* command = nullptr;
    for (const BenchCommand& c : bench_commands())
        if (c.name == args[0]) command = &c;
    try {
        if (!command) throw InputError("unknown subcommand '" + args[0] + "' (see bench --help)");
        return command->run(std::vector<std::string>(args.begin() + 1, args.end()));
    } catch (const InputError& e) {
        std::cerr << "bench: error: " << e.what() << "\n";
        return kExitBadInput;
    } catch (const NotImplemented& e) {
        std::cerr << "bench: " << e.what() << "\n";
        return kExitNotImplemented;
    } catch (const std::exception& e) {
        std::cerr << "bench: internal error: " << e.what() << "\n";
        return kExitFailure;
    }
}
