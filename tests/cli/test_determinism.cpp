// Same seed, same bytes, whatever the thread count (DESIGN.md "Determinism").
#include <doctest/doctest.h>

#include <string>

#include "test_util.h"

using namespace pt::test;

TEST_CASE("the same scene and seed give byte-identical PNG and PFM with -t 1 and -t 2") {
    std::string dir = scratch_dir("cli_determinism");
    std::string scene = source_path("assets/scenes/cbox_spheres.json");
    for (int threads : {1, 2}) {
        std::string out = dir + "/t" + std::to_string(threads);
        // -s 4 jitters the samples, so the random streams matter.
        CommandResult r = run("'" + bin_path("pathtracer") + "' -q -s 4 -r 48 40 --seed 5 -t " + std::to_string(threads) +
                                  " -f " + out + ".png --hdr " + out + ".pfm " + scene,
                              dir);
        REQUIRE(r.exit_code == 0);
    }
    CHECK(read_file(dir + "/t1.png") == read_file(dir + "/t2.png"));
    CHECK(read_file(dir + "/t1.pfm") == read_file(dir + "/t2.pfm"));
    // A different seed changes the jittered image.
    run("'" + bin_path("pathtracer") + "' -q -s 4 -r 48 40 --seed 6 -t 2 -f " + dir + "/s6.png " + scene, dir);
    CHECK(read_file(dir + "/s6.png") != read_file(dir + "/t2.png"));
}
