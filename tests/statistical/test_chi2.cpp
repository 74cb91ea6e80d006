// The chi-square machinery itself: the incomplete gamma function against
// tabulated chi-square quantiles, pooling, and the power to reject a wrong pdf.
#include <doctest/doctest.h>

#include "core/sampling.h"
#include "statistical/chi2.h"

using namespace pt;
using namespace pt::stats;

TEST_CASE("chi-square p-values match tabulated quantiles") {
    // Upper-tail quantiles of the chi-square distribution (Abramowitz and
    // Stegun table 26.8; any statistics table).
    CHECK(chi2_p_value(3.841458820694124, 1) == doctest::Approx(0.05).epsilon(1e-9));
    CHECK(chi2_p_value(6.634896601021214, 1) == doctest::Approx(0.01).epsilon(1e-9));
    CHECK(chi2_p_value(23.209251158954356, 10) == doctest::Approx(0.01).epsilon(1e-9));
    CHECK(chi2_p_value(135.8067048, 100) == doctest::Approx(0.01).epsilon(1e-6));
    CHECK(chi2_p_value(67.32756330547962, 100) == doctest::Approx(0.995).epsilon(1e-9));
    // Two degrees of freedom: Q = exp(-x / 2) exactly.
    for (double x : {0.01, 0.5, 2.0, 9.0, 40.0, 200.0})
        CHECK(chi2_p_value(x, 2) == doctest::Approx(std::exp(-0.5 * x)).epsilon(1e-12));
    // Many degrees of freedom (the warp tests have thousands of cells): the
    // median is close to dof (1 - 2 / (9 dof))^3 (Wilson and Hilferty 1931).
    int dof = 3000;
    double median = dof * std::pow(1.0 - 2.0 / (9.0 * dof), 3);
    CHECK(chi2_p_value(median, dof) == doctest::Approx(0.5).epsilon(1e-3));
    CHECK(gamma_p(2.5, 1.7) + gamma_q(2.5, 1.7) == doctest::Approx(1.0).epsilon(1e-14));
}

TEST_CASE("Sidak correction") {
    CHECK(sidak_significance(0.01, 1) == doctest::Approx(0.01));
    double a = sidak_significance(0.01, kChiSquareTestCount);
    CHECK(1.0 - std::pow(1.0 - a, kChiSquareTestCount) == doctest::Approx(0.01).epsilon(1e-12));
}

TEST_CASE("pooling and zero-probability cells") {
    // Two large cells and three tiny ones: the tiny ones are pooled, and the
    // pool (expecting 3 < 5) is merged into the smallest regular cell.
    Chi2Result r = chi2_test({100, 98, 1, 2, 0}, {100, 100, 1, 1, 1}, 0.01);
    CHECK(r.passed);
    CHECK(r.dof == 1);
    // Seven tiny cells make a pool of their own.
    Chi2Result q = chi2_test({100, 98, 1, 2, 0, 1, 1, 1, 2}, {100, 100, 1, 1, 1, 1, 1, 1, 1}, 0.01);
    CHECK(q.passed);
    CHECK(q.dof == 2);
    // A sample where the pdf is 0 fails whatever the rest looks like.
    Chi2Result z = chi2_test({100, 100, 1}, {100, 101, 0}, 0.01);
    CHECK_FALSE(z.passed);
    CHECK(z.message.find("pdf is 0") != std::string::npos);
}

TEST_CASE("the test rejects a wrong pdf") {
    // Cosine-weighted samples checked against the uniform hemisphere pdf, and
    // uniform samples against the cosine pdf: both must fail, or the tests
    // in this folder would prove nothing.
    DirectionGrid grid;
    auto cosine = [](Rng& rng) {
        return std::optional<Vec3>(sample_cosine_hemisphere(rng.next_2d()));
    };
    auto uniform = [](Rng& rng) {
        return std::optional<Vec3>(sample_uniform_hemisphere(rng.next_2d()));
    };
    auto uniform_pdf = [](const Vec3& w) { return w.z > 0 ? uniform_hemisphere_pdf() : 0.0; };
    auto cosine_pdf = [](const Vec3& w) { return cosine_hemisphere_pdf(w.z); };
    CHECK_FALSE(chi2_sampling_test(grid, cosine, uniform_pdf, 100000, 1).passed);
    CHECK_FALSE(chi2_sampling_test(grid, uniform, cosine_pdf, 100000, 2).passed);
    // A subtle error: a cone sampled with the wrong angle (5% too wide).
    double omc = 1.0 - std::cos(0.5);
    DirectionGrid cone_grid;
    cone_grid.z_min = -1;
    auto wide = [&](Rng& rng) {
        return std::optional<Vec3>(sample_uniform_cone(rng.next_2d(), omc * 1.05));
    };
    auto cone_pdf = [&](const Vec3& w) { return w.z >= 1.0 - omc ? uniform_cone_pdf(omc) : 0.0; };
    CHECK_FALSE(chi2_sampling_test(cone_grid, wide, cone_pdf, 1000000, 3).passed);
}
