// The executables of Part 4, run as a user runs them: `part4` on the
// handout's stubs names the first missing task and exits 3; `pathtracer`
// renders with an environment map, a thin lens, Russian roulette and a
// clamp, reports the integrator and the skipped code paths, and --stats
// carries them with nonfinite_samples 0; bad Part 4 flags exit 2.
#include <doctest/doctest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "test_util.h"

using namespace pt::test;

namespace {

const std::string kCbox = source_path("assets/scenes/cbox.json");
const std::string kSpheres = source_path("assets/scenes/cbox_spheres.json");
const std::string kWhitted = source_path("assets/scenes/whitted.json");
const std::string kSky = source_path("assets/env/sky.hdr");

std::string app(const std::string& program, const std::string& args) {
    return "'" + bin_path(program) + "' -q -t 1 " + args;
}

nlohmann::json stats_of(const std::string& path) {
    return nlohmann::json::parse(std::ifstream(path));
}

}  // namespace

TEST_CASE("part4 on the stubs reports the first missing task and exits 3") {
    std::string dir = scratch_dir("cli_part4");
    CommandResult r = run(app("part4", "-r 16 16 -m 3 -f " + dir + "/p.png " + kCbox), dir);
    CHECK(r.exit_code == 3);
    CHECK(r.out.find("integrator: path (global is a student stage") != std::string::npos);
    CHECK(r.err ==
          "part4: Part 4, task 1: at_least_one_bounce_radiance is not implemented yet "
          "(no image written)\n");
    CHECK_FALSE(file_exists(dir + "/p.png"));
    // Emission only needs task 2.
    r = run(app("part4", "-r 16 16 -m 0 -f " + dir + "/p.png " + kCbox), dir);
    CHECK(r.exit_code == 3);
    CHECK(r.err.find("Part 4, task 2: est_radiance_global_illumination") != std::string::npos);
    // part3 at -m 2 runs the path tracer through the student's direct stage.
    r = run(app("part3", "-r 16 16 -m 2 -f " + dir + "/p.png " + kCbox), dir);
    CHECK(r.exit_code == 3);
    CHECK(r.out.find("integrator: path") != std::string::npos);
    CHECK(r.err.find("Part 3, task 1: diffuse_f") != std::string::npos);
}

TEST_CASE("pathtracer picks the integrator from the effects and says what it skips") {
    std::string dir = scratch_dir("cli_part4_auto");
    CommandResult r = run(
        app("pathtracer", "-r 24 18 -f " + dir + "/w.png --stats " + dir + "/w.json " + kWhitted),
        dir);
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("integrator: whitted") != std::string::npos);
    CHECK(r.out.find("skipped: emission look-ups (nothing emits), lens sampling (pinhole)") !=
          std::string::npos);
    nlohmann::json j = stats_of(dir + "/w.json");
    CHECK(j["integrator"] == "whitted");
    CHECK(j["code_paths"]["shadow_rays"] == true);
    CHECK(j["code_paths"]["emission"] == false);
    CHECK(j["nonfinite_samples"] == 0);

    r = run(app("pathtracer",
                "-r 24 24 -s 2 -m 4 -f " + dir + "/c.png --stats " + dir + "/c.json " + kSpheres),
            dir);
    REQUIRE(r.exit_code == 0);
    j = stats_of(dir + "/c.json");
    CHECK(j["integrator"] == "path");
    CHECK(j["max_depth"] == 4);
    CHECK(j["russian_roulette"]["rr_depth"] == 3);
    CHECK(j["clamp"] == false);
    CHECK(j["clamped_samples"] == 0);
    CHECK(j["nonfinite_samples"] == 0);
    // A forced Whitted on area lights says it is not noise-free.
    r = run(app("pathtracer", "-r 8 8 --integrator whitted -f " + dir + "/x.png " + kCbox), dir);
    CHECK(r.out.find("note: Whitted lights surfaces with area and sky lights") !=
          std::string::npos);
}

TEST_CASE("environment map, thin lens, roulette off and a clamp, from the command line") {
    std::string dir = scratch_dir("cli_part4_flags");
    std::string scene = source_path("assets/scenes/materials.json");
    CommandResult r =
        run(app("pathtracer", "-r 32 24 -s 2 -m 4 --rr-depth off --clamp 4 -b 0.05 -d 4 " +
                                  std::string("-e ") + kSky + " -f " + dir + "/m.png --stats " +
                                  dir + "/m.json " + scene),
            dir);
    CAPTURE(r.out);
    CAPTURE(r.err);
    REQUIRE(r.exit_code == 0);
    nlohmann::json j = stats_of(dir + "/m.json");
    CHECK(j["russian_roulette"] == false);
    CHECK(j["clamp"] == 4.0);
    CHECK(j["code_paths"]["lens_sampling"] == true);
    CHECK(j["nonfinite_samples"] == 0);
    std::vector<std::string> effects = j["effects"];
    CHECK(std::find(effects.begin(), effects.end(), "depth_of_field") != effects.end());
    CHECK(std::find(effects.begin(), effects.end(), "environment") != effects.end());
    if (j["clamped_samples"].get<long>() > 0)
        CHECK(r.out.find("--clamp scaled down") != std::string::npos);
}

TEST_CASE("bad Part 4 flags and maps exit 2 with one line") {
    std::string dir = scratch_dir("cli_part4_bad");
    struct Case {
        std::string args, expected;
    };
    const Case cases[] = {
        {"--rr-depth -1 " + kCbox,
         "--rr-depth: expected a whole number >= 0 (bounces before Russian roulette starts) or "
         "'off', got '-1'"},
        {"--rr-depth sometimes " + kCbox, "--rr-depth: expected a whole number >= 0"},
        {"--clamp 0 " + kCbox, "--clamp: expected a number > 0, got '0'"},
        {"--clamp inf " + kCbox, "--clamp: expected a number > 0"},
        {"-e " + dir + "/missing.hdr " + kCbox, "-e"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.args);
        CommandResult r = run(app("pathtracer", "-r 8 8 -f " + dir + "/x.png " + c.args), dir);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find(c.expected) != std::string::npos);
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    }
    // A file that is not an image: bad input, named.
    write_file(dir + "/broken.hdr", "#?RADIANCE\nthis is not a picture\n");
    CommandResult r = run(
        app("pathtracer", "-r 8 8 -f " + dir + "/x.png -e " + dir + "/broken.hdr " + kCbox), dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("broken.hdr") != std::string::npos);
}
