// BDPT's flags and Part 7's executable, run as a user runs them: `part7` on
// the handout's stubs runs bdpt and names the first missing task (exit 3);
// --integrator bdpt and --bdpt-strategies write their images; `auto` picks
// bdpt for small lights behind a gap and for caustics, and says why;
// --bdpt-strategies without bdpt and bdpt with a camera without importance
// exit 2 with one line.
#include <doctest/doctest.h>

#include <string>

#include "test_util.h"

using namespace pt::test;

namespace {

std::string app(const std::string& program, const std::string& args) {
    return "'" + bin_path(program) + "' -q -t 2 " + args;
}

}  // namespace

TEST_CASE("part7 on the stubs runs bdpt and reports the first missing task") {
    std::string dir = scratch_dir("cli_part7");
    CommandResult r = run(app("part7", "-r 8 8 -m 3 -f " + dir + "/p.png " + source_path("assets/scenes/cbox.json")), dir);
    CHECK(r.exit_code == 3);
    CHECK(r.out.find("student stages: bdpt") != std::string::npos);
    CHECK(r.out.find("integrator: bdpt (bdpt is a student stage") != std::string::npos);
    CHECK(r.err == "part7: Part 7, task 1: random_walk is not implemented yet (no image written)\n");
    CHECK_FALSE(file_exists(dir + "/p.png"));
}

TEST_CASE("bdpt renders, writes its strategy images, and auto picks it where it pays") {
    std::string dir = scratch_dir("cli_bdpt");
    CommandResult r = run(app("pathtracer", "-r 12 9 -s 2 -m 3 --integrator bdpt --bdpt-strategies " + dir +
                                                "/strategies -f " + dir + "/b.png " +
                                                source_path("assets/scenes/bdpt_caustic.json")),
                          dir);
    CHECK(r.exit_code == 0);
    CHECK(r.err.empty());
    CHECK(file_exists(dir + "/b.png"));
    CHECK(file_exists(dir + "/strategies/strategies.png"));
    CHECK(file_exists(dir + "/strategies/s2_t1_unweighted.pfm"));
    CHECK(file_exists(dir + "/strategies/s0_t5_weighted.png"));

    r = run(app("pathtracer", "-r 8 6 -m 3 -f " + dir + "/c.png " + source_path("assets/scenes/bdpt_caustic.json")), dir);
    CHECK(r.exit_code == 0);
    CHECK(r.out.find("integrator: bdpt (small area lights focused by mirrors or glass") != std::string::npos);
    r = run(app("pathtracer", "-r 8 6 -m 5 -f " + dir + "/d.png " + source_path("assets/scenes/door_ajar.json")), dir);
    CHECK(r.exit_code == 0);
    CHECK(r.out.find("integrator: bdpt (small area lights, -m >= 3 and occluders") != std::string::npos);
    // The Cornell box's lamp is not small: the path tracer.
    r = run(app("pathtracer", "-r 8 8 -m 3 -f " + dir + "/e.png " + source_path("assets/scenes/cbox.json")), dir);
    CHECK(r.out.find("integrator: path") != std::string::npos);
}

TEST_CASE("bdpt's bad input exits 2 with one line") {
    std::string dir = scratch_dir("cli_bdpt_bad");
    CommandResult r = run(app("pathtracer", "-r 8 8 --integrator path --bdpt-strategies " + dir + "/s -f " + dir +
                                                "/a.png " + source_path("assets/scenes/cbox.json")),
                          dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--bdpt-strategies: needs --integrator bdpt") != std::string::npos);
    r = run(app("pathtracer", "-r 8 8 -m 2 --integrator bdpt -f " + dir + "/o.png " +
                                  source_path("assets/scenes/camera_orthographic.json")),
            dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--integrator bdpt: ") != std::string::npos);
}
