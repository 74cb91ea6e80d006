// The command line contract: exit codes 0, 2 and 3, one-line messages, and
// no image written when a render fails.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>

#include "test_util.h"

using namespace pt::test;

namespace {

const std::string kScene = source_path("assets/scenes/cbox_spheres.json");

std::string pathtracer(const std::string& args) { return "'" + bin_path("pathtracer") + "' " + args; }

/// Number of lines in a message (a trailing newline does not count).
size_t lines(const std::string& s) {
    size_t n = size_t(std::count(s.begin(), s.end(), '\n'));
    return (!s.empty() && s.back() != '\n') ? n + 1 : n;
}

}  // namespace

TEST_CASE("a good render exits 0, writes the image and prints one summary line") {
    std::string dir = scratch_dir("cli_ok");
    CommandResult r = run(pathtracer("-q -t 2 -r 32 24 -f " + dir + "/n.png --hdr " + dir + "/n.pfm --stats " + dir +
                                     "/s.json " + kScene),
                          dir);
    CHECK(r.exit_code == 0);
    CHECK(file_exists(dir + "/n.png"));
    CHECK(file_exists(dir + "/n.pfm"));
    std::string stats = read_file(dir + "/s.json");
    CHECK(stats.find("\"nonfinite_samples\": 0") != std::string::npos);
    CHECK(stats.find("\"effects\"") != std::string::npos);
    CHECK(stats.find("\"render\"") != std::string::npos);
    CHECK(r.out.find("32x24, 1 spp") != std::string::npos);
    CHECK(r.out.find("Mrays/s") != std::string::npos);
    CHECK(r.out.find("tests/ray") != std::string::npos);
    CHECK(r.err.empty());
}

TEST_CASE("bad flags exit 2 with one line naming the flag") {
    std::string dir = scratch_dir("cli_flags");
    struct Case {
        std::string args, expected;
    };
    const Case cases[] = {
        {"-s 0 " + kScene, "-s: expected a whole number >= 1, got '0'"},
        {"-r -1 5 " + kScene, "-r (width): expected a whole number in [1, 32768], got '-1'"},
        {"-t abc " + kScene, "-t: expected a whole number in [1, 4096], got 'abc'"},
        {"-m x " + kScene, "-m: expected a whole number"},
        {"-o 2 " + kScene, "-o: expected a whole number in [0, 1]"},
        {"-a 32 " + kScene, "-a (max tolerance): expected a number > 0"},
        {"--accel kd " + kScene, "--accel: expected one of none, grid, kdtree, bvh, embree, got 'kd'"},
        {"--transmittance dual " + kScene, "--transmittance: expected one of ratio, delta, got 'dual'"},
        {"--packets yes " + kScene, "--packets: expected one of on, off, got 'yes'"},
        {"--student camra " + kScene, "--student: unknown stage 'camra'"},
        {"--frobnicate " + kScene, "--frobnicate: unknown option"},
        {"-s", "-s: expected 1 value after it"},
        {"", "no scene given"},
        {"-f out.jpg " + kScene, "-f: expected a file name ending in .png"},
        {"-f /nonexistent/dir/x.png " + kScene, "cannot write /nonexistent/dir/x.png"},
        {"-p 0 0 1000 10 " + kScene, "-p: the cell does not fit"},
        {kScene + " extra.json", "unexpected argument 'extra.json'"},
        {"missing.json", "cannot read missing.json"},
        {"--bvh-view LRX " + kScene, "--bvh-view: expected a path of L and R steps"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.args);
        CommandResult r = run(pathtracer("-q " + c.args), dir);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find(c.expected) != std::string::npos);
        CHECK(lines(r.err) == 1);
    }
}

TEST_CASE("a bad scene file exits 2 naming the file and the JSON path") {
    std::string dir = scratch_dir("cli_scene");
    write_file(dir + "/bad.json", R"({"camera": {"position": [0,0,5], "look_at": [0,0,0]},
        "materials": {"m": {"type": "diffuse"}},
        "objects": [{"type": "sphere", "center": [0,0,0], "radius": -2, "material": "m"}]})");
    CommandResult r = run(pathtracer("-q -f " + dir + "/x.png " + dir + "/bad.json"), dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("bad.json: objects[0].radius: expected a number > 0, got -2") != std::string::npos);
    CHECK(lines(r.err) == 1);
    CHECK_FALSE(file_exists(dir + "/x.png"));
}

TEST_CASE("part1 on the handout stubs exits 3, says what is missing, and writes no image") {
    std::string dir = scratch_dir("cli_stub");
    CommandResult r = run("'" + bin_path("part1") + "' -q -r 8 8 -f " + dir + "/p.png " + kScene, dir);
    CHECK(r.exit_code == 3);
    CHECK(r.err.find("Part 1, task") != std::string::npos);
    CHECK(r.err.find("is not implemented yet") != std::string::npos);
    CHECK(lines(r.err) == 1);
    CHECK_FALSE(file_exists(dir + "/p.png"));
    // With the reference switched back in, part1 renders.
    r = run("'" + bin_path("part1") + "' -q --student none -r 8 8 -f " + dir + "/p.png " + kScene, dir);
    CHECK(r.exit_code == 0);
    CHECK(file_exists(dir + "/p.png"));
}

TEST_CASE("--help exits 0 and lists the contract flags") {
    std::string dir = scratch_dir("cli_help");
    CommandResult r = run(pathtracer("--help"), dir);
    CHECK(r.exit_code == 0);
    for (const char* flag : {"-s N", "-a N TOL", "-l N", "-t N", "-m N", "-o 0|1", "-e FILE", "-f FILE.png", "-r W H",
                             "-p X Y DX DY", "-H", "-b R", "--seed", "--hdr", "--accel", "--integrator", "--student",
                             "--stats", "-q", "--direct", "--triangle", "--bvh-split", "--max-leaf", "--bvh-view",
                             "--packets"})
        CHECK(r.out.find(flag) != std::string::npos);
}
