// Every executable and tool the README names answers --help with its usage
// on stdout and exit code 0 (issue 22: make_sky took "--help" for a file
// name, ray_cost aborted on it).
#include <doctest/doctest.h>

#include <sstream>
#include <string>
#include <vector>

#include "test_util.h"

using namespace pt::test;

TEST_CASE("every executable, bench subcommand, tool and script answers --help with exit 0") {
    std::string dir = scratch_dir("cli_help_all");
    const std::string tools = std::string(PT_BIN_DIR) + "/../tests/";
    std::vector<std::string> commands = {
        bin_path("pathtracer"), bin_path("part1"), bin_path("part2"), bin_path("part3"), bin_path("part4"),
        bin_path("part5"), bin_path("part6"), bin_path("part7"), bin_path("part8"), bin_path("grade"), bin_path("imgdiff"), bin_path("part9"), bin_path("make_sky"), bin_path("make_cloud"), bin_path("bench"),
        tools + "ray_cost", tools + "direct_compare",
        source_path("scripts/demo.sh"), source_path("scripts/test.sh"), source_path("scripts/setup.sh"),
        source_path("scripts/build.sh"), source_path("scripts/sanitize.sh"), source_path("scripts/fuzz.sh"),
        source_path("scripts/readme_images.sh"), source_path("scripts/wait_for_apt_lock.sh"),
        source_path("scripts/handout.sh"), source_path("scripts/instances_scene.sh"),
    };
    // Every subcommand `bench --help` lists ("  bench NAME ..."), so a new one is covered without an edit here.
    const CommandResult listing = run(bin_path("bench") + " --help", dir);
    std::istringstream lines(listing.out);
    int subcommands = 0;
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("  bench ", 0) == 0) {
            std::istringstream words(line);
            std::string bench, name;
            words >> bench >> name;
            commands.push_back(bin_path("bench") + " " + name);
            ++subcommands;
        }
    CHECK(subcommands >= 8);
    for (const std::string& command : commands) {
        for (const char* flag : {"--help", "-h"}) {
            CAPTURE(command);
            CAPTURE(flag);
            CommandResult r = run(command + " " + flag, dir);
            CHECK(r.exit_code == 0);
            CHECK(r.out.rfind("usage: ", 0) == 0);
            CHECK(r.err.empty());
        }
    }
}
