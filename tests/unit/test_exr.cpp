// OpenEXR input and output (image/exr_io.h): a float round trip bit for
// bit, half-float files written by tinyexr itself, and bad files as bad input.
#include <doctest/doctest.h>

#include <tinyexr.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "image/exr_io.h"
#include "image/image_io.h"
#include "scene/environment_map.h"
#include "test_util.h"

using namespace pt;

namespace {

std::string error_of(const std::string& path) {
    try {
        read_exr(path);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

/// A 4-channel RGBA file written by tinyexr's simple API (half or float).
void save_rgba(const std::vector<float>& rgba, int w, int h, bool half, const std::string& path) {
    const char* err = nullptr;
    REQUIRE(SaveEXR(rgba.data(), w, h, 4, half ? 1 : 0, path.c_str(), &err) == TINYEXR_SUCCESS);
}

}  // namespace

TEST_CASE("EXR: a float image survives a round trip bit for bit") {
    std::string dir = test::scratch_dir("exr_round_trip");
    Image image(7, 5);  // odd sizes: no row padding can hide
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x)
            image.set(x, y, Color(1e-7 * (x + 1), 0.5 + y, 1e5 * (x + y) + 0.123456789));
    write_exr(image, dir + "/a.exr");
    Image back = read_exr(dir + "/a.exr");
    REQUIRE(back.width() == 7);
    REQUIRE(back.height() == 5);
    CHECK(back.data() == image.data());
    // Through the extension dispatch too, and against PFM.
    write_image(image, dir + "/b.exr");
    write_image(image, dir + "/b.pfm");
    CHECK(read_image(dir + "/b.exr").data() == read_image(dir + "/b.pfm").data());
}

TEST_CASE("EXR: half-float RGBA files read to within half precision; alpha dropped") {
    std::string dir = test::scratch_dir("exr_half");
    const int w = 3, h = 2;
    std::vector<float> rgba;
    for (int i = 0; i < w * h; ++i) {
        float v = 0.25f * float(i) + 0.1f;
        rgba.insert(rgba.end(), {v, 2 * v, 100 * v, 0.5f});
    }
    save_rgba(rgba, w, h, true, dir + "/half.exr");
    Image image = read_exr(dir + "/half.exr");
    REQUIRE(image.width() == w);
    for (int i = 0; i < w * h; ++i) {
        Color c = image.at(i % w, i / w);
        CHECK(c.r == doctest::Approx(rgba[4 * i]).epsilon(1e-3));  // half: 11 significant bits
        CHECK(c.g == doctest::Approx(rgba[4 * i + 1]).epsilon(1e-3));
        CHECK(c.b == doctest::Approx(rgba[4 * i + 2]).epsilon(1e-3));
    }
}

TEST_CASE("EXR: an environment map loads from .exr as from .pfm") {
    std::string dir = test::scratch_dir("exr_environment");
    Image sky(16, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) sky.set(x, y, Color(0.1 * x, 0.2 * y + 0.01, x == 3 && y == 2 ? 50.0 : 1.0));
    write_exr(sky, dir + "/sky.exr");
    write_pfm(sky, dir + "/sky.pfm");
    EnvironmentMap a = EnvironmentMap::load(dir + "/sky.exr", Color(1)), b = EnvironmentMap::load(dir + "/sky.pfm", Color(1));
    for (Vec3 w : {Vec3(0, 1, 0), Vec3(0.3, -0.2, 0.9).unit(), Vec3(-1, 0, 0)}) CHECK(a.Le(w) == b.Le(w));
}

TEST_CASE("EXR: bad files are bad input naming the file") {
    std::string dir = test::scratch_dir("exr_bad");
    CHECK(error_of(dir + "/missing.exr").find("cannot read " + dir + "/missing.exr") != std::string::npos);
    test::write_file(dir + "/text.exr", "this is not an image\n");
    CHECK(error_of(dir + "/text.exr").find(dir + "/text.exr: not an OpenEXR image") != std::string::npos);
    // A real file cut in half.
    Image image(64, 64);
    for (int i = 0; i < 64 * 64; ++i) image.set(i % 64, i / 64, Color(std::sin(i), 1, 2));
    write_exr(image, dir + "/whole.exr");
    std::string bytes = test::read_file(dir + "/whole.exr");
    test::write_file(dir + "/cut.exr", bytes.substr(0, bytes.size() / 2));
    CHECK(error_of(dir + "/cut.exr").find(dir + "/cut.exr: ") == 0);
    // A NaN or an infinity would reach the film through a map or a texture.
    std::vector<float> rgba(4 * 4, 1.0f);
    rgba[5] = std::numeric_limits<float>::quiet_NaN();
    save_rgba(rgba, 2, 2, false, dir + "/nan.exr");
    CHECK(error_of(dir + "/nan.exr").find("pixel (1, 0) is not finite") != std::string::npos);
    rgba[5] = std::numeric_limits<float>::infinity();
    save_rgba(rgba, 2, 2, false, dir + "/inf.exr");
    CHECK(error_of(dir + "/inf.exr").find("is not finite") != std::string::npos);
    // Writing where no file can be: the reason, and no file left behind.
    try {
        write_exr(image, dir + "/no/such/dir/x.exr");
        FAIL("expected an InputError");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find("cannot write " + dir + "/no/such/dir/x.exr") == 0);
    }
}
