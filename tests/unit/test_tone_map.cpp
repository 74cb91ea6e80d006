// Tone mapping (image/tone_map.h): each operator's curve against its
// formula, exposure in stops, the bilateral filter keeping an edge, and the
// local operator compressing the base layer while keeping local contrast.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "image/tone_map.h"

using namespace pt;

namespace {

Image constant(int w, int h, const Color& c) {
    Image image(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) image.set(x, y, c);
    return image;
}

Color one_pixel(const Color& c, ToneMap op, double ev = 0) {
    return tone_map(constant(1, 1, c), DisplaySettings{op, ev}).at(0, 0);
}

}  // namespace

TEST_CASE("tone map: clamp at 0 EV is the identity on [0, 1] and clamps outside") {
    CHECK(DisplaySettings{}.is_identity());
    CHECK_FALSE((DisplaySettings{ToneMap::clamp, 0.5}).is_identity());
    CHECK_FALSE((DisplaySettings{ToneMap::reinhard, 0}).is_identity());
    Image image(3, 1);
    image.set(0, 0, Color(0.25, 0.5, 0.75));
    image.set(1, 0, Color(2.0, -1.0, 1.0));
    image.set(2, 0, Color(std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 0.3));
    Image out = tone_map(image, DisplaySettings{});
    CHECK(out.at(0, 0) == image.at(0, 0));
    CHECK(out.at(1, 0) == Color(1.0, 0.0, 1.0));
    // Not finite (never from the renderer; a PFM may hold it): black.
    CHECK(out.at(2, 0).r == 0);
    CHECK(out.at(2, 0).g == 0);
    CHECK(out.at(2, 0).b == doctest::Approx(0.3));
}

TEST_CASE("tone map: exposure scales by 2^EV before the curve") {
    CHECK(one_pixel(Color(0.125), ToneMap::clamp, 1).r == doctest::Approx(0.25));
    CHECK(one_pixel(Color(0.125), ToneMap::clamp, 2).r == doctest::Approx(0.5));
    CHECK(one_pixel(Color(0.5), ToneMap::clamp, -1).r == doctest::Approx(0.25));
    // Reinhard of 2^EV x: a grey of 1 at +1 EV is Y = 2 -> 2 / 3.
    CHECK(one_pixel(Color(1), ToneMap::reinhard, 1).g == doctest::Approx(2.0 / 3.0));
}

TEST_CASE("tone map: Reinhard maps luminance Y to Y / (1 + Y) and keeps the hue") {
    for (double y : {0.01, 0.5, 1.0, 3.0, 100.0}) {
        Color c = one_pixel(Color(y), ToneMap::reinhard);
        CHECK(c.r == doctest::Approx(y / (1 + y)));
        CHECK(c.b == doctest::Approx(y / (1 + y)));
    }
    Color tinted(0.2, 0.4, 0.1);
    Color out = one_pixel(tinted, ToneMap::reinhard);
    double y = tinted.luminance();
    CHECK(out.luminance() == doctest::Approx(y / (1 + y)));
    CHECK(out.r / out.g == doctest::Approx(0.5));  // ratios kept
    CHECK(out.b / out.g == doctest::Approx(0.25));
}

TEST_CASE("tone map: filmic follows Narkowicz's ACES fit, monotone from 0 to 1") {
    auto aces = [](double x) { return x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14); };
    CHECK(one_pixel(Color(0), ToneMap::filmic).r == 0);
    CHECK(one_pixel(Color(0.18), ToneMap::filmic).r == doctest::Approx(aces(0.18)));
    CHECK(aces(0.18) == doctest::Approx(0.2669).epsilon(1e-3));
    double previous = -1;
    for (double x = 0; x < 50; x = x * 1.3 + 0.01) {
        double v = one_pixel(Color(x), ToneMap::filmic).g;
        CHECK(v >= previous);
        CHECK(v <= 1.0);
        previous = v;
    }
    CHECK(one_pixel(Color(1e4), ToneMap::filmic).r == 1.0);
}

TEST_CASE("bilateral filter: an edge far above sigma_range survives; noise below it is smoothed") {
    const int w = 40, h = 10;
    std::vector<float> step(size_t(w) * h), noisy(size_t(w) * h);
    double noise_in = 0, noise_out = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            step[size_t(y) * w + x] = x < w / 2 ? 0.0f : 3.0f;
            noisy[size_t(y) * w + x] = float(0.05 * std::sin(1.7 * x + 2.3 * y));  // far below sigma_r
        }
    std::vector<float> a = bilateral_filter(step, w, h, 3.0, 0.4);
    // Across the edge the range weight is exp(-9 / 0.32) ~ 7e-13: nothing leaks.
    for (size_t i = 0; i < a.size(); ++i) CHECK(std::fabs(a[i] - step[i]) < 1e-6);
    std::vector<float> b = bilateral_filter(noisy, w, h, 3.0, 0.4);
    for (size_t i = 0; i < b.size(); ++i) {
        noise_in += noisy[i] * noisy[i];
        noise_out += b[i] * b[i];
    }
    CHECK(noise_out < 0.1 * noise_in);
}

TEST_CASE("local operator: five decades become two, local contrast stays") {
    // Left half at 1e-2, right half at 1e3, both with a +-10% checker texture.
    const int w = 64, h = 32;
    Image image(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double base = x < w / 2 ? 1e-2 : 1e3;
            double texture = (x + y) % 2 ? 1.1 : 1.0 / 1.1;
            image.set(x, y, Color(base * texture));
        }
    Image out = tone_map(image, DisplaySettings{ToneMap::local, 0});
    // Inside the dark half (away from the edge), the texture's ratio 1.21 survives.
    auto at = [&](int x, int y) { return out.at(x, y).g; };
    CHECK(at(10, 10) / at(11, 10) == doctest::Approx(1.0 / 1.21).epsilon(0.02));
    // The base layers, 5 decades apart, end 2 decades apart with the bright
    // one at 1 (Durand and Dorsey's absolute scale): its texture's brighter
    // half clips at 1, its darker half shows at 1 / 1.1.
    double dark = std::sqrt(at(10, 10) * at(11, 10));
    CHECK(dark == doctest::Approx(0.01).epsilon(0.02));
    CHECK(std::min(at(50, 10), at(51, 10)) == doctest::Approx(1.0 / 1.1).epsilon(0.02));
    CHECK(std::max(at(50, 10), at(51, 10)) == 1.0);
    // A global curve cannot do this: Reinhard leaves the dark half at 1%.
    Image global = tone_map(image, DisplaySettings{ToneMap::reinhard, 0});
    CHECK(global.at(10, 10).g < 0.012);
    // Black stays black, and a black image gives a black image.
    Image black = tone_map(constant(4, 4, Color(0)), DisplaySettings{ToneMap::local, 0});
    CHECK(black.at(2, 2) == Color(0));
}
