// `bench cycles`: bad inputs get one line and exit code 2 before anything
// renders (Blender is optional: a missing one is such an input), and, only
// when Debian's blender is installed, a tiny run side by side.
#include <doctest/doctest.h>

#include <algorithm>

#include <nlohmann/json.hpp>

#include "test_util.h"

using namespace pt;

namespace {

const std::string kCbox = test::source_path("assets/scenes/cbox.json");

std::string bench_cycles() {
    return test::bin_path("bench") + " cycles ";
}

}  // namespace

TEST_CASE("bench cycles: bad arguments, scenes it cannot export and a missing Blender: one line, exit 2") {
    const std::string dir = test::scratch_dir("bench_cycles_errors");
    const std::string spheres = test::source_path("assets/scenes/cbox_spheres.json");
    for (std::string args :
         {std::string(""), "'" + kCbox + "' --cycles-spp 4,x", "'" + kCbox + "' --cycles-pattern halton",
          "'" + kCbox + "' --sampler nope", "'" + kCbox + "' --clock sundial", "'" + spheres + "'",
          "'" + kCbox + "' --blender /no/such/blender --out '" + dir + "'"}) {
        CAPTURE(args);
        test::CommandResult r = test::run(bench_cycles() + args, dir);
        CHECK(r.exit_code == 2);
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
        CHECK(r.err.rfind("bench: error: cycles: ", 0) == 0);
    }
}

TEST_CASE("bench cycles: a tiny run when blender is installed") {
    const std::string dir = test::scratch_dir("bench_cycles_run");
    if (test::run("blender --version", dir).exit_code != 0) {
        MESSAGE("blender is not installed: skipped (apt-get install blender)");
        return;
    }
    test::CommandResult r = test::run(bench_cycles() + "'" + kCbox + "' -r 8 8 -t 1 -m 2 --cycles-spp 2 " +
                                          "--max-spp 4 --reference-spp 8 --no-cache --out '" + dir + "'",
                                      dir);
    REQUIRE(r.exit_code == 0);
    nlohmann::json j = nlohmann::json::parse(test::read_file(dir + "/cbox_cycles.json"));
    REQUIRE(j["renders"].size() == 3);  // pathtracer at 2 and 4 spp, Cycles at 2
    for (const auto& render : j["renders"]) {
        CHECK(render["rmse"].get<double>() > 0);
        CHECK(render["rmse"].get<double>() < 1);  // the same picture, not a black or missing one
    }
    CHECK(j["renders"][2]["renderer"] == "Cycles");
}
