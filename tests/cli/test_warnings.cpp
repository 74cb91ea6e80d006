// Outputs that never lie (issue 22): a render that is black everywhere
// although the scene has lights says so, a bare cbox.obj is no longer black,
// and imgdiff warns when it compares a linear PFM with an sRGB PNG.
#include <doctest/doctest.h>

#include <string>

#include "image/image_io.h"
#include "test_util.h"

using namespace pt::test;

namespace {

std::string app(const std::string& name, const std::string& args) { return "'" + bin_path(name) + "' " + args; }
bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }
const char* kBlack = "warning: every pixel is black although the scene has lights";

double mean(const pt::Image& image) {
    double sum = 0;
    for (float v : image.data()) sum += v;
    return sum / double(image.data().size());
}

}  // namespace

TEST_CASE("a bare cbox.obj renders the inside of the box, without a warning") {
    std::string dir = scratch_dir("warn_cbox_obj");
    CommandResult r = run(app("pathtracer", "-q -t 2 -r 32 24 -s 4 -f " + dir + "/c.png --hdr " + dir + "/c.pfm " +
                                                source_path("assets/meshes/cbox.obj")),
                          dir);
    REQUIRE(r.exit_code == 0);
    CHECK_FALSE(contains(r.out, kBlack));
    CHECK(mean(pt::read_pfm(dir + "/c.pfm")) > 0.01);  // 0 when it was framed from behind
}

TEST_CASE("an all-black render of a scene with lights says so") {
    std::string dir = scratch_dir("warn_black");
    // A wall seen from the front with its lamp behind it: every camera ray
    // meets the side of the wall that no light reaches.
    write_file(dir + "/behind.json",
               R"({"camera": {"position": [278, 273, 1400], "look_at": [278, 273, 0], "vfov": 20},
                   "materials": {"white": {"type": "diffuse", "albedo": [0.7, 0.7, 0.7]},
                                 "lamp": {"type": "diffuse", "albedo": [0, 0, 0], "emission": [10, 10, 10]}},
                   "objects": [{"type": "quad", "corner": [0, 0, 559], "edge1": [556, 0, 0], "edge2": [0, 548, 0], "material": "white"},
                               {"type": "quad", "corner": [200, 200, 300], "edge1": [0, 0, 100], "edge2": [100, 0, 0], "material": "lamp"}]})");
    CommandResult r = run(app("pathtracer", "-q -t 2 -r 16 12 -f " + dir + "/b.png " + dir + "/behind.json"), dir);
    CHECK(r.exit_code == 0);
    CHECK(contains(r.out, kBlack));
    // The same scene seen from the front has light and no warning.
    write_file(dir + "/front.json", R"({"camera": {"position": [278, 273, -800], "look_at": [278, 273, 0], "vfov": 40},
                   "materials": {"white": {"type": "diffuse", "albedo": [0.7, 0.7, 0.7]},
                                 "lamp": {"type": "diffuse", "albedo": [0, 0, 0], "emission": [10, 10, 10]}},
                   "objects": [{"type": "quad", "corner": [0, 0, 559], "edge1": [0, 548, 0], "edge2": [556, 0, 0], "material": "white"},
                               {"type": "quad", "corner": [200, 200, 300], "edge1": [0, 0, 100], "edge2": [100, 0, 0], "material": "lamp"}]})");
    r = run(app("pathtracer", "-q -t 2 -r 16 12 -f " + dir + "/f.png " + dir + "/front.json"), dir);
    CHECK(r.exit_code == 0);
    CHECK_FALSE(contains(r.out, kBlack));
}

TEST_CASE("imgdiff warns when a linear PFM is compared with an sRGB PNG, and not otherwise") {
    std::string dir = scratch_dir("warn_imgdiff_kinds");
    REQUIRE(run(app("pathtracer", "-q -t 2 -r 16 12 -f " + dir + "/a.png --hdr " + dir + "/a.pfm " +
                                      source_path("assets/scenes/cbox.json")),
                dir)
                .exit_code == 0);
    CommandResult r = run(app("imgdiff", dir + "/a.pfm " + dir + "/a.png"), dir);
    CHECK(r.exit_code == 0);
    CHECK(contains(r.err, "imgdiff: warning: " + dir + "/a.pfm is a linear PFM (unclamped) but " + dir +
                              "/a.png is an sRGB PNG (clamped to [0, 1])"));
    r = run(app("imgdiff", dir + "/a.png " + dir + "/a.png"), dir);
    CHECK(r.exit_code == 0);
    CHECK(r.err.empty());
}
