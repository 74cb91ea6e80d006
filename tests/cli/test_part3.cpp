// The executables of Part 3, run as a user runs them: `part3` on the
// handout's stubs names the first missing task in one line and exits 3;
// `pathtracer -m 1` renders the Cornell box with direct light and no
// non-finite sample.
#include <doctest/doctest.h>

#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

namespace {

struct RunResult {
    int exit_code = -1;
    std::string output;  ///< stdout and stderr
};

RunResult run(const std::string& arguments) {
    std::string command = std::string(PT_BIN_DIR) + "/" + arguments + " 2>&1";
    RunResult r;
    FILE* pipe = popen(command.c_str(), "r");
    REQUIRE(pipe);
    char buffer[4096];
    while (fgets(buffer, sizeof buffer, pipe))
        r.output += buffer;
    int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

const std::string kCbox = std::string(PT_SOURCE_DIR) + "/assets/scenes/cbox.json";
const std::string kOut = std::string(PT_TEST_OUTPUT_DIR) + "/";

}  // namespace

TEST_CASE("part3 on the stubs reports the first missing task and exits 3") {
    std::remove((kOut + "part3_stub.png").c_str());
    RunResult r = run("part3 -q -t 1 -r 16 16 " + kCbox + " -f " + kOut + "part3_stub.png");
    CAPTURE(r.output);
    CHECK(r.exit_code == 3);
    CHECK(r.output.find(
              "part3: Part 3, task 1: diffuse_f is not implemented yet (no image written)\n") !=
          std::string::npos);
    CHECK_FALSE(std::ifstream(kOut + "part3_stub.png").good());
    // -m 0 needs only zero_bounce_radiance (task 3), so that is what is missing.
    RunResult m0 = run("part3 -q -t 1 -m 0 -r 16 16 " + kCbox + " -f " + kOut + "part3_stub.png");
    CHECK(m0.exit_code == 3);
    CHECK(m0.output.find("Part 3, task 3: zero_bounce_radiance is not implemented yet") !=
          std::string::npos);
}

TEST_CASE("pathtracer -m 1 renders the Cornell box with direct light, no NaN") {
    for (const char* strategy : {"light", "hemisphere", "mis"}) {
        CAPTURE(strategy);
        std::string stats = kOut + "cbox_direct_" + strategy + ".json";
        RunResult r =
            run("pathtracer -q -t 1 -m 1 -s 2 -l 2 -r 32 32 --direct " + std::string(strategy) +
                " " + kCbox + " -f " + kOut + "cbox_direct.png --stats " + stats);
        CAPTURE(r.output);
        REQUIRE(r.exit_code == 0);
        CHECK(r.output.find("integrator: direct") != std::string::npos);
        nlohmann::json j = nlohmann::json::parse(std::ifstream(stats));
        CHECK(j["nonfinite_samples"] == 0);
        CHECK(j["integrator"] == "direct");
        if (std::string(strategy) != "hemisphere") CHECK(j["rays"]["shadow"].get<long>() > 0);
    }
}
