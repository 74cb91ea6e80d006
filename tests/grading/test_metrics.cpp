// Image metrics and the heat map's colour scale, against hand-computed values.
#include <doctest/doctest.h>

#include <cmath>

#include "core/error.h"
#include "image/colormap.h"
#include "image/metrics.h"

using namespace pt;

TEST_CASE("metrics of a 2x1 image against hand-computed values") {
    Image a(2, 1), b(2, 1);
    a.set(0, 0, Color(0.5, 0.5, 0.5));
    b.set(0, 0, Color(0.5, 0.5, 0.5));
    a.set(1, 0, Color(0.3, 0.0, 0.0));
    b.set(1, 0, Color(0.1, 0.0, 0.0));
    // One value of six differs, by 0.2 (float rounding aside).
    CHECK(mse(a, b) == doctest::Approx(0.04 / 6).epsilon(1e-6));
    CHECK(rmse(a, b) == doctest::Approx(std::sqrt(0.04 / 6)).epsilon(1e-6));
    CHECK(relmse(a, b) == doctest::Approx(0.04 / (0.01 + 0.01) / 6).epsilon(1e-6));
    CHECK(mean_abs_diff(a, b) == doctest::Approx(0.2 / 6).epsilon(1e-6));
    CHECK(psnr(a, b) == doctest::Approx(10 * std::log10(6 / 0.04)).epsilon(1e-6));
    CHECK(share_over(a, b, 0.1) == 0.5);
    CHECK(share_over(a, b, 0.3) == 0.0);
    CHECK(std::isinf(psnr(a, a)));
    CHECK(relmse(a, a) == 0);
}

TEST_CASE("relMSE is relative to the reference, the second argument") {
    Image a(1, 1), b(1, 1);
    a.set(0, 0, Color(2, 2, 2));
    b.set(0, 0, Color(1, 1, 1));
    CHECK(relmse(a, b) == doctest::Approx(1 / 1.01));
    CHECK(relmse(b, a) == doctest::Approx(1 / 4.01));
}

TEST_CASE("different sizes are bad input") {
    CHECK_THROWS_AS(rmse(Image(2, 2), Image(2, 3)), InputError);
    CHECK_THROWS_AS(compare_images(Image(4, 4), Image(3, 4)), InputError);
}

TEST_CASE("viridis ends dark purple and yellow, and the heat map marks NaN magenta") {
    Color lo = viridis_srgb(0), hi = viridis_srgb(1);
    CHECK(lo.r == doctest::Approx(68 / 255.0));
    CHECK(lo.b == doctest::Approx(84 / 255.0));
    CHECK(hi.r == doctest::Approx(253 / 255.0));
    CHECK(hi.g == doctest::Approx(231 / 255.0));
    CHECK(viridis_srgb(-1) == lo);
    CHECK(viridis_srgb(NAN) == lo);
    CHECK(viridis_hex_stops().front() == "#440154");
    CHECK(heatmap_position(1e-4, {}) == 0);
    CHECK(heatmap_position(1e-2, {}) == doctest::Approx(0.5));
    CHECK(heatmap_position(10, {}) == 1);

    Image a(2, 1), b(2, 1);
    a.set(1, 0, Color(NAN, 0, 0));
    Image map = error_heatmap(a, b);
    CHECK(map.width() == 2);
    CHECK(map.at(1, 0) == Color(1, 0, 1));
    CHECK(map.at(0, 0).r ==
          doctest::Approx(0.0578).epsilon(0.02));  // sRGB 68/255 decoded to linear
}
