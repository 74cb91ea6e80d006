// Piecewise-constant distributions and the lat-long environment map:
// densities integrate to one and agree with what sampling returns.
#include <doctest/doctest.h>

#include <cmath>

#include "core/distribution.h"
#include "core/math.h"
#include "core/rng.h"
#include "scene/environment_map.h"

using namespace pt;

TEST_CASE("Distribution1D samples steps in proportion to their heights and never a zero step") {
    Distribution1D d({1, 3, 0, 4});
    CHECK(d.integral() == doctest::Approx(2.0));  // (1 + 3 + 0 + 4) / 4
    CHECK(d.pdf(1) == doctest::Approx(1.5));
    int counts[4] = {};
    Rng rng(1);
    for (int i = 0; i < 80000; ++i) {
        double pdf = 0;
        int index = -1;
        double x = d.sample_continuous(rng.next_1d(), &pdf, &index);
        REQUIRE(x >= 0.0);
        REQUIRE(x < 1.0);
        REQUIRE(index == int(x * 4));
        REQUIRE(pdf == d.pdf(index));
        counts[index]++;
    }
    CHECK(counts[2] == 0);
    // Expected 10000, 30000, 40000; 5 standard deviations of a binomial.
    CHECK(std::abs(counts[0] - 10000) < 5 * std::sqrt(10000 * 0.875));
    CHECK(std::abs(counts[3] - 40000) < 5 * std::sqrt(40000 * 0.5));
    // Boundary inputs stay inside [0, 1) and in a non-zero step.
    for (double u : {0.0, 0.5, 1.0 - 0x1p-24, 0.125, 0.5 + 1e-17}) {
        int index = -1;
        double x = d.sample_continuous(u, nullptr, &index);
        CHECK(x < 1.0);
        CHECK(index != 2);
    }
    Distribution1D zero({0, 0});
    CHECK(zero.pdf(0) == 1.0);  // all zero: uniform
}

TEST_CASE("the environment map's direction mapping round-trips and its density integrates to one") {
    for (Vec2 uv : {Vec2(0.5, 0.5), Vec2(0.1, 0.3), Vec2(0.9, 0.8), Vec2(0.25, 0.01)}) {
        Vec2 back = EnvironmentMap::direction_to_uv(EnvironmentMap::uv_to_direction(uv));
        CHECK(back.x == doctest::Approx(uv.x));
        CHECK(back.y == doctest::Approx(uv.y));
    }
    CHECK(EnvironmentMap::uv_to_direction({0.5, 0.5}).z == doctest::Approx(-1));  // centre: -z horizon
    CHECK(EnvironmentMap::uv_to_direction({0.5, 0.0}).y == doctest::Approx(1));   // top row: zenith

    EnvironmentMap env(make_sky_image(64, 32, 35, -40), Color(1));
    // Integrate the solid-angle density over the sphere with a fine grid (midpoint rule in (u, v)).
    const int n = 512;
    double integral = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            Vec2 uv((i + 0.5) / n, (j + 0.5) / n);
            double sin_theta = std::sin(uv.y * kPi);
            integral += env.pdf(EnvironmentMap::uv_to_direction(uv)) * sin_theta * (kTwoPi / n) * (kPi / n);
        }
    CHECK(integral == doctest::Approx(1.0).epsilon(1e-3));

    // Samples report the density pdf() gives them and the radiance Le() gives them.
    Rng rng(4);
    for (int i = 0; i < 2000; ++i) {
        EnvironmentMap::Sample s = env.sample(rng.next_2d());
        REQUIRE(s.wi.norm() == doctest::Approx(1));
        if (s.pdf == 0) continue;
        CHECK(s.pdf == doctest::Approx(env.pdf(s.wi)).epsilon(1e-6));
        CHECK(s.L == env.Le(s.wi));
    }
}
