// scripts/handout.sh --level guided|standard (docs/handouts.md): the guided
// handout is the repository's assignments/ without the marker lines; the
// standard one differs from it only in comments and marked README
// paragraphs: every line of code, every TODO(part line and every contract
// pointer is kept, and no step list is left. And `partN --deliverables`
// refuses bad input with exit 2; with the handout's stubs it writes a page
// that says which images are missing and why, and removes stale images.
// (Rendering them with a working solution, tests/grading/solution, is done
// by hand: docs/handouts.md has the run; the renders are too slow for a test.)
#include <doctest/doctest.h>

#include <sstream>
#include <string>
#include <vector>

#include "test_util.h"

using namespace pt::test;

namespace {

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

std::string trimmed(const std::string& s) {
    size_t a = s.find_first_not_of(" \t");
    return a == std::string::npos ? "" : s.substr(a);
}

bool is_comment(const std::string& line) { return trimmed(line).rfind("//", 0) == 0; }

const char* kStubs[] = {"part1/camera.cpp", "part1/intersect.cpp", "part2/bvh.cpp",   "part2/grid.cpp", "part3/bsdf.cpp",
                        "part3/direct.cpp", "part3/mis.cpp",      "part4/global.cpp", "part5/adaptive.cpp",
                        "part6/sampler.cpp", "part7/bdpt.cpp", "part8/photon.cpp", "part9/media.cpp"};

}  // namespace

TEST_CASE("guided handouts are the repository's; standard ones keep all code and contracts, no steps") {
    std::string dir = scratch_dir("handout");
    CommandResult g = run("'" + source_path("scripts/handout.sh") + "' --level guided '" + dir + "/guided'", dir);
    CommandResult s = run("'" + source_path("scripts/handout.sh") + "' --level standard '" + dir + "/standard'", dir);
    REQUIRE(g.exit_code == 0);
    REQUIRE(s.exit_code == 0);
    for (const char* stub : kStubs) {
        INFO(stub);
        std::string repo = read_file(source_path(std::string("assignments/") + stub));
        std::vector<std::string> guided = lines_of(read_file(dir + "/guided/" + stub));
        std::vector<std::string> standard = lines_of(read_file(dir + "/standard/" + stub));
        std::vector<std::string> expected;
        int blocks = 0;
        for (const std::string& line : lines_of(repo)) {
            if (trimmed(line) == "// [guided]") ++blocks;
            if (trimmed(line) != "// [guided]" && trimmed(line) != "// [/guided]") expected.push_back(line);
        }
        CHECK(guided == expected);
        CHECK(blocks > 0);  // every stub has its steps marked
        // Code lines and TODO lines are the same, in the same order, at both levels.
        std::vector<std::string> code_g, code_s;
        for (const std::string& l : guided)
            if (!is_comment(l) || l.find("TODO(part") != std::string::npos) code_g.push_back(l);
        for (const std::string& l : standard)
            if (!is_comment(l) || l.find("TODO(part") != std::string::npos) code_s.push_back(l);
        CHECK(code_g == code_s);
        std::string text = read_file(dir + "/standard/" + stub);
        CHECK(text.find("[guided]") == std::string::npos);
        CHECK(text.find("states its contract") != std::string::npos);
        CHECK(standard.size() < guided.size());
    }
    // The READMEs lose only their marked paragraphs (Part 4: "Follow the numbered steps").
    std::string readme4 = read_file(dir + "/standard/part4/README.md");
    CHECK(readme4.find("Follow the numbered steps") == std::string::npos);
    CHECK(readme4.find("Russian roulette, and why it is unbiased") != std::string::npos);
    CHECK(read_file(dir + "/guided/part4/README.md").find("<!-- guided -->") == std::string::npos);
    // Parts 8 and 9 too: the kd-tree query's descent and HG's frame are steps.
    CHECK(read_file(dir + "/standard/part8/README.md").find("visit the side that holds p first") == std::string::npos);
    CHECK(read_file(dir + "/guided/part8/README.md").find("visit the side that holds p first") != std::string::npos);
    CHECK(read_file(dir + "/standard/part9/README.md").find("Frame(-wo)") == std::string::npos);
    CHECK(file_exists(dir + "/standard/part3/grading.json"));
    CHECK(file_exists(dir + "/standard/part3/deliverables.json"));
}

TEST_CASE("handout.sh and --deliverables refuse bad input with exit 2 and one line") {
    std::string dir = scratch_dir("handout_errors");
    CommandResult r = run("'" + source_path("scripts/handout.sh") + "' --level easy '" + dir + "/x'", dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err == "handout: --level: expected guided or standard, got 'easy'\n");
    REQUIRE(run("mkdir -p '" + dir + "/full' && echo x > '" + dir + "/full/file'", dir).exit_code == 0);
    r = run("'" + source_path("scripts/handout.sh") + "' --level guided '" + dir + "/full'", dir);
    CHECK(r.exit_code == 2);
    r = run("'" + bin_path("part3") + "' --deliverables '" + dir + "/d' -s 4", dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err == "part3: error: --deliverables DIR takes only -t N beside it, got '-s'\n");
}

TEST_CASE("--deliverables with the handout's stubs: a page naming every image as not rendered, exit 3, no stale image") {
    std::string dir = scratch_dir("deliverables_stubs");
    // A stale image from an earlier run must go: it is not this code's.
    REQUIRE(run("mkdir -p '" + dir + "/d' && echo old > '" + dir + "/d/normals.png'", dir).exit_code == 0);
    CommandResult r = run("'" + bin_path("part1") + "' --deliverables '" + dir + "/d' -t 1", dir);
    CHECK(r.exit_code == 3);
    std::string page = read_file(dir + "/d/index.html");
    std::string list = read_file(source_path("assignments/part1/deliverables.json"));
    for (const char* name : {"normals", "cbox_spheres"}) {
        INFO(name);
        CHECK(list.find(std::string("\"") + name + "\"") != std::string::npos);
        CHECK(page.find(std::string("-f ") + name + ".png") != std::string::npos);
        CHECK_FALSE(file_exists(dir + "/d/" + name + ".png"));
    }
    CHECK(page.find("Not rendered") != std::string::npos);
    CHECK(page.find("<img") == std::string::npos);
}
