// The noise-aware pass rule on synthetic images whose noise is known:
// correct "students" pass (and the false-failure rate is measured), a
// bias confined to one tile is caught by the z-test, excess noise by the
// error ratio, and without noise the rule is a tight tolerance.
#include <doctest/doctest.h>

#include <cmath>

#include "core/rng.h"
#include "grade/noise_rule.h"

using namespace pt;

namespace {

constexpr int kSize = 64;

/// A smooth "converged" image: a colour gradient.
Image converged() {
    Image r(kSize, kSize);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            r.set(x, y, Color(0.1 + 0.8 * x / kSize, 0.2 + 0.5 * y / kSize, 0.4));
    return r;
}

/// A render at `spp` samples per pixel whose samples are Bernoulli draws
/// (0 or 2 times the pixel's value): the two-valued noise of edge pixels,
/// the least Gaussian there is. One pixel in four is noisy, like edges.
Image noisy(const Image& r, int spp, uint64_t seed, double noise_scale = 1.0) {
    Image out = r;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            if ((x * 7 + y * 3) % 4 != 0) continue;
            Rng rng(seed, uint64_t(y * kSize + x), 0);
            Color mean = r.at(x, y), sum;
            for (int i = 0; i < spp; ++i) {
                for (int c = 0; c < 3; ++c) {
                    double v = rng.next_1d() < 0.5 ? 0.0 : 2 * mean[c];
                    double noisy_v = mean[c] + noise_scale * (v - mean[c]);
                    sum = Color(c == 0 ? sum.r + noisy_v : sum.r, c == 1 ? sum.g + noisy_v : sum.g,
                                c == 2 ? sum.b + noisy_v : sum.b);
                }
            }
            out.set(x, y, sum / double(spp));
        }
    }
    return out;
}

std::vector<Image> runs(const Image& r, int spp) {
    std::vector<Image> q;
    for (uint64_t k = 0; k < 8; ++k)
        q.push_back(noisy(r, spp, 1000 + k));
    return q;
}

/// The per-sample variance of noisy(): m^2 on the noisy pixels.
Image sample_variance(const Image& r) {
    Image v(kSize, kSize);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            if ((x * 7 + y * 3) % 4 == 0) v.set(x, y, r.at(x, y) * r.at(x, y));
    return v;
}

/// The rule on a student render at 8 spp (ratio) and 64 spp (bias), with
/// an exact converged image.
NoiseVerdict grade(const Image& r, const Image& s8, const Image& s64, const std::vector<Image>& q) {
    Image var = sample_variance(r);
    return apply_noise_rule(NoiseInputs{s8, s64, 64, r, 1 << 30, var, q}, NoiseRule{});
}

}  // namespace

TEST_CASE("correct noisy renders pass; false failures over 500 seeds stay near alpha") {
    Image r = converged();
    std::vector<Image> q = runs(r, 8);
    int failures = 0, ratio_failures = 0, z_failures = 0;
    for (uint64_t seed = 1; seed <= 500; ++seed) {
        NoiseVerdict v = grade(r, noisy(r, 8, seed), noisy(r, 64, seed), q);
        failures += !v.pass;
        ratio_failures += !v.ratio_ok;
        z_failures += !v.z_ok;
    }
    MESSAGE("synthetic two-valued noise, 500 correct renders: " << failures << " failures ("
                                                                << ratio_failures << " ratio, "
                                                                << z_failures << " z-test)");
    CHECK(ratio_failures == 0);
    CHECK(failures <= 2);  // alpha = 1e-4 predicts 0.05 of 500
}

TEST_CASE("a bias confined to one tile fails the z-test though the global ratio passes") {
    Image r = converged();
    std::vector<Image> q = runs(r, 8);
    Image s = noisy(r, 8, 7), s64 = noisy(r, 64, 7);
    for (int y = 16; y < 24; ++y) {
        for (int x = 40; x < 48; ++x) {
            s.set(x, y, s.at(x, y) + Color(0.05, 0, 0));
            s64.set(x, y, s64.at(x, y) + Color(0.05, 0, 0));
        }
    }
    NoiseVerdict v = grade(r, s, s64, q);
    CHECK(v.ratio_ok);
    CHECK_FALSE(v.z_ok);
    CHECK_FALSE(v.pass);
    CHECK(v.worst_tile_x == 40);
    CHECK(v.worst_tile_y == 16);
    CHECK(v.worst_channel == 0);
}

TEST_CASE("twice the noise (unbiased) fails the ratio test") {
    Image r = converged();
    std::vector<Image> q = runs(r, 8);
    NoiseVerdict v = grade(r, noisy(r, 8, 7, 2.0), noisy(r, 64, 7, 2.0), q);
    CHECK(v.student_relmse > 3 * v.reference_relmse);
    CHECK_FALSE(v.ratio_ok);
    CHECK_FALSE(v.pass);
}

TEST_CASE("less noise than the reference (better sampling) passes") {
    Image r = converged();
    NoiseVerdict v = grade(r, noisy(r, 32, 7), noisy(r, 256, 7), runs(r, 8));
    CHECK(v.pass);
    CHECK(v.student_relmse < v.reference_relmse);
}

TEST_CASE("without noise the rule is a tight tolerance") {
    Image r = converged(), zero(kSize, kSize);
    std::vector<Image> q(4, r);
    Image s = r;
    s.set(3, 3, s.at(3, 3) + Color(1e-6, 0, 0));  // rounding: passes
    CHECK(apply_noise_rule(NoiseInputs{s, s, 1, r, 1, zero, q}, NoiseRule{}).pass);
    s.set(5, 5, s.at(5, 5) + Color(0, 0.02, 0));  // one pixel visibly off: fails
    NoiseVerdict v = apply_noise_rule(NoiseInputs{s, s, 1, r, 1, zero, q}, NoiseRule{});
    CHECK_FALSE(v.pass);
    CHECK(v.tiles_failed == 1);
}

TEST_CASE("the Sidak level keeps the family-wise rate at alpha") {
    Image r = converged(), zero(kSize, kSize);
    std::vector<Image> q = {r, r};
    NoiseVerdict v = apply_noise_rule(NoiseInputs{r, r, 1, r, 1, zero, q}, NoiseRule{});
    CHECK(v.tests == 8 * 8 * 3);
    CHECK(1 - std::pow(1 - v.sidak_alpha, v.tests) == doctest::Approx(1e-4).epsilon(1e-9));
}
