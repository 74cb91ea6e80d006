// `bench accuracy` on tiny inputs: one-line errors with exit code 2, the
// files a run writes and what the JSON holds, the reference cache, a given
// reference, and a technique that does not finish within the budget.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "test_util.h"

using namespace pt;

namespace {

const std::string kCbox = test::source_path("assets/scenes/cbox.json");

std::string bench() {
    return test::bin_path("bench");
}

/// A quick run at 16x16 in `dir`, with its own cache.
test::CommandResult quick_run(const std::string& dir, const std::string& extra) {
    return test::run(bench() + " accuracy '" + kCbox +
                         "' -r 16 16 -t 2 --reference-spp 32 --out '" + dir + "' --cache '" + dir +
                         "/cache' " + extra,
                     dir);
}

int lines(const std::string& text) {
    return int(std::count(text.begin(), text.end(), '\n'));
}

}  // namespace

TEST_CASE("bad arguments get one line and exit code 2") {
    const std::string dir = test::scratch_dir("bench_accuracy_errors");
    const std::string missing = dir + "/missing.json";
    const std::string bad_ref = dir + "/small.pfm";
    test::write_file(bad_ref, "PF\n2 2\n-1.0\n" + std::string(2 * 2 * 3 * 4, '\0'));
    for (std::string args :
         {std::string(""), "'" + kCbox + "' --budget 0", "'" + kCbox + "' --budget abc",
          "'" + kCbox + "' --equal-time -1", "'" + kCbox + "' --techniques light,nope",
          "'" + kCbox + "' --frobnicate", "'" + kCbox + "' -r 16", "'" + missing + "'",
          "'" + kCbox + "' '" + kCbox + "'",
          "'" + kCbox + "' -r 16 16 --reference '" + bad_ref + "'", "'" + kCbox + "' -a 32 zero",
          "'" + kCbox + "' --clock sundial",
          "'" + kCbox + "' --out /proc/no/such/dir"}) {
        CAPTURE(args);
        test::CommandResult r = test::run(bench() + " accuracy " + args, dir);
        CHECK(r.exit_code == 2);
        CHECK(lines(r.err) == 1);
        CHECK(r.err.rfind("bench: error: ", 0) == 0);
    }
    test::CommandResult help = test::run(bench() + " accuracy --help", dir);
    CHECK(help.exit_code == 0);
    CHECK(help.out.find("--equal-time") != std::string::npos);
}

TEST_CASE(
    "a run writes the table, the JSON, the plot and the equal-time images; the reference is "
    "cached") {
    const std::string dir = test::scratch_dir("bench_accuracy_run");
    test::CommandResult r =
        quick_run(dir, "--budget 0.3 --equal-time 0.05 --techniques light,mis,adaptive");
    REQUIRE(r.exit_code == 0);
    for (const char* file :
         {"cbox_accuracy.md", "cbox_accuracy.json", "cbox_accuracy.png", "cbox_reference.png",
          "cbox_equal_time.png", "cbox_equal_time_light.png", "cbox_equal_time_mis.png",
          "cbox_equal_time_mis_error.png", "cbox_equal_time_adaptive_rate.png"})
        CHECK(test::file_exists(dir + "/" + file));
    CHECK(test::read_file(dir + "/cbox_accuracy.md") == r.out);
    CHECK(r.out.find("| technique") != std::string::npos);
    CHECK(r.out.find("rendered now") != std::string::npos);
    // One progress line per render, naming technique and spp.
    CHECK(r.err.find("bench accuracy: light: 1 spp") != std::string::npos);
    CHECK(r.err.find("bench accuracy: mis: 2 spp") != std::string::npos);

    nlohmann::json j = nlohmann::json::parse(test::read_file(dir + "/cbox_accuracy.json"));
    CHECK(j["reference"]["spp"] == 32);
    CHECK(j["width"] == 16);
    REQUIRE(j["techniques"].size() == 3);
    for (const auto& t : j["techniques"]) {
        REQUIRE(!t["rows"].empty());
        int spp = 1;
        for (const auto& row : t["rows"]) {
            CHECK(row["spp"] == spp);  // 1, 2, 4, ...
            spp *= 2;
            const double e = row["efficiency"], relmse = row["relmse"], s = row["seconds"];
            CHECK(e == doctest::Approx(1.0 / (relmse * s)).epsilon(1e-9));
        }
    }
    REQUIRE(j["comparisons"].size() == 2);  // mis and adaptive against light
    CHECK(j["comparisons"][0]["baseline"] == "light");
    CHECK(j["equal_time"]["results"].size() == 3);

    // The second run finds the reference in the cache.
    test::CommandResult again = quick_run(dir, "--budget 0.05 --techniques light");
    REQUIRE(again.exit_code == 0);
    CHECK(again.out.find("from the cache") != std::string::npos);
    nlohmann::json k = nlohmann::json::parse(test::read_file(dir + "/cbox_accuracy.json"));
    CHECK(k["reference"]["spp"] == 32);
}

TEST_CASE("a given reference is used with its spp from the sidecar") {
    const std::string dir = test::scratch_dir("bench_accuracy_given");
    REQUIRE(quick_run(dir, "--budget 0.05 --techniques light").exit_code == 0);
    nlohmann::json j = nlohmann::json::parse(test::read_file(dir + "/cbox_accuracy.json"));
    const std::string cached = j["reference"]["path"];
    test::CommandResult r = test::run(bench() + " accuracy '" + kCbox +
                                          "' -r 16 16 -t 1 --budget 0.05 --techniques light "
                                          "--out '" +
                                          dir + "/given' --reference '" + cached + "'",
                                      dir);
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("32 spp") != std::string::npos);
    CHECK(r.out.find(", given") != std::string::npos);
}

TEST_CASE("a technique whose first render exceeds the budget is reported as not finished") {
    const std::string dir = test::scratch_dir("bench_accuracy_dnf");
    test::CommandResult r = quick_run(dir, "--budget 0.000001 --techniques linear-scan");
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("did not finish within the budget") != std::string::npos);
    nlohmann::json j = nlohmann::json::parse(test::read_file(dir + "/cbox_accuracy.json"));
    CHECK(j["techniques"][0]["finished"] == false);
    CHECK(j["techniques"][0]["rows"].empty());
}

TEST_CASE("depth caps are skipped, with a note, unless the baseline is the path tracer") {
    const std::string dir = test::scratch_dir("bench_accuracy_skip");
    test::CommandResult r = quick_run(dir, "--budget 0.05 -m 1 --techniques light,depth-2");
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.find("skipping depth-2") != std::string::npos);
    nlohmann::json j = nlohmann::json::parse(test::read_file(dir + "/cbox_accuracy.json"));
    CHECK(j["techniques"].size() == 1);
}

TEST_CASE("with the path tracer as baseline, rr-off traces more rays and a depth cap fewer") {
    // Same seed and spp: roulette only ends paths early, so the render
    // without it traces strictly more rays (16x16, -m 8, roulette after 3
    // bounces); a cap of 2 bounces traces strictly fewer. Deterministic.
    const std::string dir = test::scratch_dir("bench_accuracy_path");
    test::CommandResult r =
        quick_run(dir, "--budget 0.3 --max-spp 2 -m 8 --clock cpu --techniques light,rr-off,depth-2");
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.find("skipping") == std::string::npos);
    nlohmann::json j = nlohmann::json::parse(test::read_file(dir + "/cbox_accuracy.json"));
    REQUIRE(j["techniques"].size() == 3);
    for (const auto& t : j["techniques"])
        REQUIRE(!t["rows"].empty());
    const double light = j["techniques"][0]["rows"][0]["rays"];
    const double rr_off = j["techniques"][1]["rows"][0]["rays"];
    const double depth2 = j["techniques"][2]["rows"][0]["rays"];
    CHECK(j["techniques"][1]["name"] == "rr-off");
    CHECK(j["clock"] == "cpu");
    CHECK(r.out.find("CPU seconds per thread") != std::string::npos);
    CHECK(rr_off > light);
    CHECK(depth2 < light);
}
