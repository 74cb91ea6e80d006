// PNG (sRGB) and PFM (linear) round trips, and bad image files.
#include <doctest/doctest.h>

#include <cmath>

#include "core/error.h"
#include "image/image_io.h"
#include "image/tonemap.h"
#include "test_util.h"

using namespace pt;

TEST_CASE("sRGB transfer function: known points and exact 8-bit round trip") {
    CHECK(srgb_encode(0) == 0);
    CHECK(srgb_encode(1) == 1);
    CHECK(srgb_encode(0.0031308) == doctest::Approx(0.0031308 * 12.92));
    CHECK(to_srgb8(0.5) == 188);  // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 -> 187.5 -> 188
    CHECK(to_srgb8(2.0) == 255);
    CHECK(to_srgb8(-1.0) == 0);
    CHECK(to_srgb8(std::nan("")) == 0);
    for (int code = 0; code < 256; ++code) CHECK(to_srgb8(from_srgb8(uint8_t(code))) == code);
}

TEST_CASE("PFM round trip is exact, including values above 1 and row order") {
    std::string dir = pt::test::scratch_dir("image_io_pfm");
    Image a(5, 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x) a.set(x, y, Color(x * 10.5, y + 0.25, -1.0 / (x + y + 1)));
    write_pfm(a, dir + "/a.pfm");
    Image b = read_image(dir + "/a.pfm");
    REQUIRE(b.width() == 5);
    REQUIRE(b.height() == 3);
    CHECK(b.data() == a.data());
}

TEST_CASE("PNG round trip is within half a quantisation step") {
    std::string dir = pt::test::scratch_dir("image_io_png");
    Image a(4, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) a.set(x, y, Color(x / 3.0, y * 0.5, 0.2));
    write_png(a, dir + "/a.png");
    Image b = read_image(dir + "/a.png");
    REQUIRE(b.width() == 4);
    for (size_t i = 0; i < a.data().size(); ++i) {
        double encoded_a = srgb_encode(a.data()[i]), encoded_b = srgb_encode(b.data()[i]);
        CHECK(std::fabs(encoded_a - encoded_b) <= 0.5 / 255 + 1e-9);
    }
}

TEST_CASE("bad image files and paths are InputErrors naming the file") {
    std::string dir = pt::test::scratch_dir("image_io_bad");
    pt::test::write_file(dir + "/not.png", "hello");
    pt::test::write_file(dir + "/short.pfm", "PF\n4 4\n-1.0\n1234");
    auto message = [](auto&& f) {
        try {
            f();
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(message([&] { read_image(dir + "/not.png"); }).find("not.png") != std::string::npos);
    CHECK(message([&] { read_image(dir + "/short.pfm"); }).find("truncated") != std::string::npos);
    CHECK(message([&] { read_image(dir + "/absent.pfm"); }).find("cannot read") != std::string::npos);
    CHECK(message([&] { read_image(dir + "/x.tga"); }).find("unknown image type") != std::string::npos);
    CHECK(message([&] { write_png(Image(2, 2), dir + "/no/such/dir/x.png"); }).find("cannot write") != std::string::npos);
}
