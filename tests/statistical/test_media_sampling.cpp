// Chi-square tests of the media stage's sampling (stages/media.h; chi2.h for
// the method and the Sidak-corrected level, family-wise 0.01): HG sampling
// for g in {-0.9, -0.3, 0, 0.5, 0.95} against hg_phase integrated
// numerically over cells about the direction of travel, and free-flight
// distance sampling against the exponential's closed form (with "passed
// the surface" as one more cell). 10^6 samples each, fixed seeds.
#include <doctest/doctest.h>

#include <cmath>

#include "core/frame.h"
#include "core/math.h"
#include "core/rng.h"
#include "stages/media.h"
#include "statistical/chi2_check.h"

using namespace pt;
using namespace pt::stats;

namespace {

constexpr int kSamples = 1000000;

/// HG samples binned in (z, phi) about the direction of travel -wo: z =
/// cos theta in 200 equal steps (fine enough for g = 0.95's peak, which is
/// 0.0013 wide in z), phi in 8. A cell's expected count integrates hg_phase
/// over z with 16 x 5-point Gauss-Legendre pieces; phi is uniform.
Chi2Result hg_chi2(double g, uint64_t seed) {
    const Vec3 wo = Vec3(0.3, -0.5, 0.8).unit();
    const Frame frame(-wo);
    const int nz = 200, nphi = 8;
    std::vector<double> observed(size_t(nz * nphi), 0.0), expected(size_t(nz * nphi), 0.0);
    Rng rng(seed);
    for (int i = 0; i < kSamples; ++i) {
        Vec3 wi = reference::sample_hg(wo, g, rng.next_2d());
        Vec3 l = frame.to_local(wi);
        if (!wi.is_finite() || std::fabs(wi.norm() - 1) > 1e-9) {
            Chi2Result bad;
            bad.message = "a sample is not a unit vector";
            return bad;
        }
        int iz = std::clamp(int((l.z + 1.0) / 2.0 * nz), 0, nz - 1);
        double phi = std::atan2(l.y, l.x);
        if (phi < 0) phi += kTwoPi;
        int ip = std::clamp(int(phi / kTwoPi * nphi), 0, nphi - 1);
        observed[size_t(iz * nphi + ip)] += 1;
    }
    static const double node[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                   0.9061798459386640};
    static const double weight[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                     0.4786286704993665, 0.2369268850561891};
    double total = 0;
    for (int iz = 0; iz < nz; ++iz) {
        double z0 = -1.0 + 2.0 * iz / nz, dz = 2.0 / nz / 16;
        double integral = 0;  // of p over the ring: 2 pi integral p(z) dz
        for (int piece = 0; piece < 16; ++piece) {
            double c = z0 + (piece + 0.5) * dz, h = 0.5 * dz;
            for (int k = 0; k < 5; ++k) integral += weight[k] * h * reference::hg_phase(c + h * node[k], g);
        }
        integral *= kTwoPi;
        total += integral;
        for (int ip = 0; ip < nphi; ++ip) expected[size_t(iz * nphi + ip)] = kSamples * integral / nphi;
    }
    if (std::fabs(total - 1.0) > 1e-6) {
        Chi2Result bad;
        bad.message = "hg_phase integrates to " + std::to_string(total) + ", not 1";
        return bad;
    }
    return chi2_test(observed, expected, per_test_significance());
}

}  // namespace

TEST_CASE("chi2: Henyey-Greenstein sampling, g = -0.9") { check_passes(hg_chi2(-0.9, 91)); }
TEST_CASE("chi2: Henyey-Greenstein sampling, g = -0.3") { check_passes(hg_chi2(-0.3, 92)); }
TEST_CASE("chi2: Henyey-Greenstein sampling, g = 0") { check_passes(hg_chi2(0.0, 93)); }
TEST_CASE("chi2: Henyey-Greenstein sampling, g = 0.5") { check_passes(hg_chi2(0.5, 94)); }
TEST_CASE("chi2: Henyey-Greenstein sampling, g = 0.95") { check_passes(hg_chi2(0.95, 95)); }

TEST_CASE("chi2: free-flight distance sampling, with passing as one more cell") {
    const double sigma_t = 2.0, t_max = 1.3;
    const int bins = 60;
    std::vector<double> observed(bins + 1, 0.0), expected(bins + 1, 0.0);
    Rng rng(96);
    int wrong_pdf = 0;
    for (int i = 0; i < kSamples; ++i) {
        DistanceSample s = reference::sample_distance(sigma_t, t_max, rng.next_1d());
        if (s.scattered) {
            REQUIRE(s.t >= 0);
            REQUIRE(s.t < t_max);
            observed[size_t(std::min(bins - 1, int(s.t / t_max * bins)))] += 1;
            wrong_pdf += std::fabs(s.pdf - sigma_t * std::exp(-sigma_t * s.t)) > 1e-12 * s.pdf;
        } else {
            observed[bins] += 1;
            wrong_pdf += s.t != t_max || std::fabs(s.pdf - std::exp(-sigma_t * t_max)) > 1e-15;
        }
    }
    // P(t in [a, b)) = e^(-sigma a) - e^(-sigma b); P(pass) = e^(-sigma t_max).
    for (int b = 0; b < bins; ++b)
        expected[size_t(b)] = kSamples * (std::exp(-sigma_t * t_max * b / bins) - std::exp(-sigma_t * t_max * (b + 1) / bins));
    expected[bins] = kSamples * std::exp(-sigma_t * t_max);
    check_passes(chi2_test(observed, expected, per_test_significance()));
    CHECK(wrong_pdf == 0);
}
