// The image flags: -f and --hdr in PNG, PFM and EXR, -e with an EXR map,
// imgdiff on EXR, --tonemap and --exposure (the default PNG unchanged byte
// for byte: it is the clamped, sRGB-encoded radiance of the --hdr image).
#include <doctest/doctest.h>

#include <algorithm>
#include <string>

#include "image/image_io.h"
#include "image/tone_map.h"
#include "test_util.h"

using namespace pt;
using namespace pt::test;

namespace {

const std::string kScene = source_path("assets/scenes/materials.json");

std::string pathtracer(const std::string& args) {
    return "'" + bin_path("pathtracer") + "' -q -t 2 -r 48 24 -s 4 -m 3 " + args;
}

}  // namespace

TEST_CASE("-f and --hdr write EXR, PFM and PNG of the same render") {
    std::string dir = scratch_dir("cli_exr");
    REQUIRE(run(pathtracer("-f " + dir + "/a.png --hdr " + dir + "/a.pfm " + kScene), dir).exit_code == 0);
    REQUIRE(run(pathtracer("-f " + dir + "/b.exr --hdr " + dir + "/b.exr2.exr " + kScene), dir).exit_code == 0);
    Image pfm = read_image(dir + "/a.pfm");
    CHECK(read_image(dir + "/b.exr").data() == pfm.data());
    CHECK(read_image(dir + "/b.exr2.exr").data() == pfm.data());
    // The default PNG is the clamped radiance, sRGB-encoded, byte for byte.
    write_png(pfm, dir + "/from_pfm.png");
    CHECK(read_file(dir + "/a.png") == read_file(dir + "/from_pfm.png"));
    // --tonemap clamp --exposure 0 is the default.
    REQUIRE(run(pathtracer("--tonemap clamp --exposure 0 -f " + dir + "/c.png " + kScene), dir).exit_code == 0);
    CHECK(read_file(dir + "/a.png") == read_file(dir + "/c.png"));
    // imgdiff reads EXR.
    CommandResult r = run("'" + bin_path("imgdiff") + "' " + dir + "/b.exr " + dir + "/a.pfm --max-relmse 0", dir);
    CHECK(r.exit_code == 0);
    CHECK(r.out.find("RMSE               0") != std::string::npos);
}

TEST_CASE("--tonemap and --exposure change the PNG only, as the operators say") {
    std::string dir = scratch_dir("cli_tonemap");
    REQUIRE(run(pathtracer("-f " + dir + "/base.png --hdr " + dir + "/base.pfm " + kScene), dir).exit_code == 0);
    Image radiance = read_image(dir + "/base.pfm");
    for (ToneMap op : {ToneMap::clamp, ToneMap::reinhard, ToneMap::filmic, ToneMap::local}) {
        std::string name = to_string(op);
        CAPTURE(name);
        CommandResult r = run(pathtracer("--tonemap " + name + " --exposure 1.5 -f " + dir + "/" + name + ".png --hdr " +
                                         dir + "/" + name + ".pfm " + kScene),
                              dir);
        REQUIRE(r.exit_code == 0);
        CHECK(read_image(dir + "/" + name + ".pfm").data() == radiance.data());  // the HDR output is untouched
        write_png(tone_map(radiance, DisplaySettings{op, 1.5}), dir + "/expected.png");
        CHECK(read_file(dir + "/" + name + ".png") == read_file(dir + "/expected.png"));
        CHECK(read_file(dir + "/" + name + ".png") != read_file(dir + "/base.png"));
    }
}

TEST_CASE("-e reads an EXR map as it reads the same map in PFM") {
    std::string dir = scratch_dir("cli_exr_env");
    Image sky = read_image(source_path("assets/env/sky.hdr"));
    write_image(sky, dir + "/sky.exr");
    write_image(sky, dir + "/sky.pfm");
    std::string scene = source_path("assets/scenes/whitted.json");
    REQUIRE(run(pathtracer("-m 2 -e " + dir + "/sky.exr -f " + dir + "/e.png " + scene), dir).exit_code == 0);
    REQUIRE(run(pathtracer("-m 2 -e " + dir + "/sky.pfm -f " + dir + "/p.png " + scene), dir).exit_code == 0);
    CHECK(read_file(dir + "/e.png") == read_file(dir + "/p.png"));
}

TEST_CASE("bad image flags and files exit 2 with one line") {
    std::string dir = scratch_dir("cli_image_flags");
    test::write_file(dir + "/fake.exr", "not an exr");
    struct Case {
        std::string args, expected;
    };
    const Case cases[] = {
        {"--tonemap aces " + kScene, "--tonemap: expected one of clamp, reinhard, filmic, local, got 'aces'"},
        {"--exposure bright " + kScene, "--exposure: expected a number"},
        {"--exposure 100 " + kScene, "--exposure: expected a number"},
        {"--hdr x.png " + kScene, "--hdr: expected a file name ending in .pfm or .exr"},
        {"-f x.jpg " + kScene, "-f: expected a file name ending in .png or .exr"},
        {"-e " + dir + "/fake.exr " + kScene, dir + "/fake.exr: not an OpenEXR image"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.args);
        CommandResult r = run(pathtracer(c.args), dir);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find(c.expected) != std::string::npos);
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    }
}
