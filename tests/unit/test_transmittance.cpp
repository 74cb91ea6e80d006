// Closed forms of the media stage (stages/media.h): Beer-Lambert
// transmittance, free-flight distances by inversion, and the
// Henyey-Greenstein phase function (normalised, mean cosine g, its cdf in
// cos theta), with the hard cases: sigma_t = 0 in one channel, infinite
// distances, g = +-0.999.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "core/math.h"
#include "stages/media.h"

using namespace pt;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

/// integral_a^b f(z) dz by 5-point Gauss-Legendre on pieces that shrink
/// geometrically (ratio 0.8, down to 1e-13 of the interval) towards both
/// ends, where HG peaks for |g| near 1 (its peak is (1 - |g|)^2 / 2|g| wide).
template <class F>
double integrate_z(F f, double a = -1.0, double b = 1.0) {
    static const double node[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                   0.9061798459386640};
    static const double weight[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                     0.4786286704993665, 0.2369268850561891};
    auto gauss = [&](double x0, double x1) {
        double c = 0.5 * (x0 + x1), h = 0.5 * (x1 - x0), sum = 0;
        for (int k = 0; k < 5; ++k) sum += weight[k] * h * f(c + h * node[k]);
        return sum;
    };
    const double m = 0.5 * (a + b), half = 0.5 * (b - a);
    double sum = 0, outer = half;
    while (outer > 1e-13 * half) {
        double inner = outer * 0.8;
        sum += gauss(a + inner, a + outer) + gauss(b - outer, b - inner);
        outer = inner;
    }
    (void)m;
    return sum + gauss(a, a + outer) + gauss(b - outer, b);
}
}  // namespace

TEST_CASE("transmittance: e^(-sigma_t d) per channel, 1 where sigma_t is 0, 0 at infinity") {
    Color T = reference::homogeneous_transmittance(Color(0.5, 0, 2), 3.0);
    CHECK(T.r == doctest::Approx(std::exp(-1.5)).epsilon(1e-15));
    CHECK(T.g == 1.0);
    CHECK(T.b == doctest::Approx(std::exp(-6.0)).epsilon(1e-15));
    Color far = reference::homogeneous_transmittance(Color(0.5, 0, 2), kInf);
    CHECK(far == Color(0, 1, 0));  // no NaN from 0 * infinity
    CHECK(reference::homogeneous_transmittance(Color(1, 1, 1), 0.0) == Color(1));
    // Two slabs one after the other transmit the product (Beer-Lambert is multiplicative).
    Color a = reference::homogeneous_transmittance(Color(0.7), 1.25), b = reference::homogeneous_transmittance(Color(0.7), 2.5);
    CHECK(b.r == doctest::Approx(a.r * a.r).epsilon(1e-14));
}

TEST_CASE("distance sampling: the inversion, its density, passing, and sigma_t = 0") {
    // u = 1 - e^-1 is one mean free path.
    DistanceSample s = reference::sample_distance(2.0, 10.0, 1.0 - std::exp(-1.0));
    CHECK(s.scattered);
    CHECK(s.t == doctest::Approx(0.5).epsilon(1e-14));
    CHECK(s.pdf == doctest::Approx(2.0 * std::exp(-1.0)).epsilon(1e-14));
    s = reference::sample_distance(2.0, 0.25, 1.0 - std::exp(-1.0));
    CHECK_FALSE(s.scattered);
    CHECK(s.t == 0.25);
    CHECK(s.pdf == doctest::Approx(std::exp(-0.5)).epsilon(1e-14));
    s = reference::sample_distance(0.0, 1e30, 0.999);
    CHECK_FALSE(s.scattered);
    CHECK(s.pdf == 1.0);
    s = reference::sample_distance(1e-3, kInf, 0.0);  // u = 0: a collision at t = 0, finite pdf
    CHECK(s.scattered);
    CHECK(s.t == 0.0);
    s = reference::sample_distance(3.0, kInf, 1.0 - 0x1p-53);  // the largest u: finite t
    CHECK(s.scattered);
    CHECK(std::isfinite(s.t));
    // The scattering probability and the passing probability add up to 1.
    const double sigma = 1.7, t_max = 0.9;
    double scatter = integrate_z([&](double t) { return sigma * std::exp(-sigma * t); }, 0.0, t_max);
    CHECK(scatter + reference::sample_distance(sigma, t_max, 0.99).pdf == doctest::Approx(1.0).epsilon(1e-12));
}

TEST_CASE("Henyey-Greenstein: normalised, mean cosine g, its cdf, isotropic at g = 0, finite at g = +-0.999") {
    for (double g : {-0.999, -0.9, -0.3, 0.0, 0.5, 0.95, 0.999}) {
        CAPTURE(g);
        double norm = kTwoPi * integrate_z([&](double z) { return reference::hg_phase(z, g); });
        double mean = kTwoPi * integrate_z([&](double z) { return z * reference::hg_phase(z, g); });
        CHECK(norm == doctest::Approx(1.0).epsilon(1e-6));
        CHECK(mean == doctest::Approx(g).epsilon(1e-6).scale(1));
        // The cdf in cos theta: P(cos <= x) = (1 - g^2) / (2 g) ((1 + g^2 - 2 g x)^-1/2 - 1 / (1 + g)).
        if (g != 0) {
            const double x = 0.3;
            double cdf = (1 - g * g) / (2 * g) * (1 / std::sqrt(1 + g * g - 2 * g * x) - 1 / (1 + g));
            CHECK(kTwoPi * integrate_z([&](double z) { return reference::hg_phase(z, g); }, -1.0, x) ==
                  doctest::Approx(cdf).epsilon(1e-6));
        }
        for (double z : {-1.0, 0.0, 1.0}) CHECK(std::isfinite(reference::hg_phase(z, g)));
        for (double u : {0.0, 0.5, 1.0 - 0x1p-53}) {
            Vec3 wi = reference::sample_hg(Vec3(0, 0, 1), g, Vec2(u, 0.3));
            CHECK(wi.is_finite());
            CHECK(wi.norm() == doctest::Approx(1.0).epsilon(1e-12));
        }
    }
    CHECK(reference::hg_phase(0.3, 0.0) == doctest::Approx(kInvFourPi));
    // g > 0 scatters forward: wi (where light comes from) lies behind wo.
    Vec3 wo(0, 0, 1);
    Vec3 wi = reference::sample_hg(wo, 0.95, Vec2(0.5, 0.5));
    CHECK(dot(wi, wo) < -0.9);
}
