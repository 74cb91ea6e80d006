// The photon mapping flags and Part 8's executable, run as a user runs
// them: `part8` on the handout's stubs runs pm and names the first missing
// task (exit 3); pm, its map views and sppm write images and report their
// integrator; `auto` picks sppm where point lights make caustics and says
// why; bad photon flags exit 2 with one line naming the flag.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>

#include "test_util.h"

using namespace pt::test;

namespace {

const std::string kSpheres = source_path("assets/scenes/cbox_spheres.json");
const std::string kWhitted = source_path("assets/scenes/whitted.json");

std::string app(const std::string& program, const std::string& args) {
    return "'" + bin_path(program) + "' -q -t 2 " + args;
}

}  // namespace

TEST_CASE("part8 on the stubs runs pm and reports the first missing task") {
    std::string dir = scratch_dir("cli_part8");
    CommandResult r = run(app("part8", "-r 8 8 -f " + dir + "/p.png " + kSpheres), dir);
    CHECK(r.exit_code == 3);
    CHECK(r.out.find("student stages: photon") != std::string::npos);
    CHECK(r.out.find("integrator: pm (photon is a student stage") != std::string::npos);
    CHECK(r.err == "part8: Part 8, task 1: emit_photon is not implemented yet (no image written)\n");
    CHECK_FALSE(file_exists(dir + "/p.png"));
}

TEST_CASE("pm, its photon views and sppm render; auto picks sppm for point-light caustics") {
    std::string dir = scratch_dir("cli_photon");
    const std::string small = "-r 12 12 --photons 2000 --caustic-photons 2000 ";
    for (const std::string& extra : {std::string("--integrator pm"), std::string("--photon-view caustic"),
                                     std::string("--photon-view global --knn 10 --radius 30"),
                                     std::string("--integrator sppm --passes 2 --photons-per-pass 2000 --alpha 0.5")}) {
        CAPTURE(extra);
        CommandResult r = run(app("pathtracer", small + extra + " -f " + dir + "/p.png " + kSpheres), dir);
        CHECK(r.exit_code == 0);
        CHECK(r.err.empty());
        CHECK(file_exists(dir + "/p.png"));
    }
    CommandResult r = run(app("pathtracer", "-r 12 8 -m 4 --passes 1 --photons-per-pass 1000 -f " + dir +
                                                "/w.png " + kWhitted), dir);
    CHECK(r.exit_code == 0);
    CHECK(r.out.find("point_light_caustics") != std::string::npos);
    CHECK(r.out.find("integrator: sppm (point or directional light") != std::string::npos);
    CHECK(r.out.find("-m 4 is not used") != std::string::npos);
}

TEST_CASE("bad photon flags exit 2 with one line naming the flag") {
    std::string dir = scratch_dir("cli_photon_flags");
    struct Case {
        std::string args, expected;
    };
    const Case cases[] = {
        {"--alpha 1", "--alpha: expected a number in (0, 1)"},
        {"--alpha 0", "--alpha:"},
        {"--knn 0", "--knn: expected a whole number in [1"},
        {"--radius -1", "--radius:"},
        {"--photons -5", "--photons:"},
        {"--passes 0", "--passes:"},
        {"--photon-kernel gauss", "--photon-kernel: expected one of box, cone, epanechnikov"},
        {"--photon-view all", "--photon-view: expected one of caustic, global"},
        {"--photon-view caustic --integrator path", "--photon-view: shows pm's photon maps"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.args);
        CommandResult r = run(app("pathtracer", c.args + " -f " + dir + "/p.png " + kSpheres), dir);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find("pathtracer: error: " + c.expected) == 0);
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    }
}
