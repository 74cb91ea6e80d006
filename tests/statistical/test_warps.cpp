// Chi-square tests of every sample warp in core/sampling.h against its pdf
// (10^6 samples each, cells of equal measure, fixed seeds; chi2.h), and
// adversarial inputs: u exactly 0, 0.5 and 1 - 2^-24 give finite results.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>

#include "core/ray.h"
#include "core/sampling.h"
#include "statistical/chi2_check.h"

using namespace pt;
using namespace pt::stats;

namespace {

constexpr int kSamples = 1000000;

/// The grid for a cone of half-angle acos(cos_max) about `axis`: the cells cover only the cone.
DirectionGrid cone_grid(double cos_max, const Vec3& axis = Vec3(0, 0, 1)) {
    DirectionGrid g;
    g.frame = Frame(axis);
    g.z_min = cos_max;
    g.nz = 20;
    g.nphi = 40;
    return g;
}

const double kAdversarial[] = {0.0, 0.5, 1.0 - 0x1p-24};

}  // namespace

TEST_CASE("chi2: uniform hemisphere") {
    check_passes(chi2_sampling_test(
        DirectionGrid{},
        [](Rng& r) { return std::optional<Vec3>(sample_uniform_hemisphere(r.next_2d())); },
        [](const Vec3& w) { return w.z >= 0 ? uniform_hemisphere_pdf() : 0.0; }, kSamples, 11));
}

TEST_CASE("chi2: cosine hemisphere") {
    check_passes(chi2_sampling_test(
        DirectionGrid{},
        [](Rng& r) { return std::optional<Vec3>(sample_cosine_hemisphere(r.next_2d())); },
        [](const Vec3& w) { return cosine_hemisphere_pdf(w.z); }, kSamples, 12));
}

TEST_CASE("chi2: uniform sphere") {
    check_passes(chi2_sampling_test(
        DirectionGrid{},
        [](Rng& r) { return std::optional<Vec3>(sample_uniform_sphere(r.next_2d())); },
        [](const Vec3&) { return uniform_sphere_pdf(); }, kSamples, 13));
}

TEST_CASE("chi2: concentric disk") {
    check_passes(chi2_sampling_test(
        DiskGrid{}, [](Rng& r) { return std::optional<Vec2>(sample_concentric_disk(r.next_2d())); },
        [](const Vec2&) { return kInvPi; }, kSamples, 14));
}

TEST_CASE("chi2: uniform cone") {
    SUBCASE("half-angle 60 degrees") {
        double cos_max = 0.5;
        check_passes(chi2_sampling_test(
            cone_grid(cos_max),
            [&](Rng& r) {
                return std::optional<Vec3>(sample_uniform_cone(r.next_2d(), 1.0 - cos_max));
            },
            [&](const Vec3&) { return uniform_cone_pdf(1.0 - cos_max); }, kSamples, 15));
    }
    SUBCASE("half-angle 1 degree") {
        // 1 - cos from sin^2 / (1 + cos), as the sphere light computes it.
        double s = std::sin(radians(1.0)), c = std::cos(radians(1.0));
        double omc = s * s / (1.0 + c);
        check_passes(chi2_sampling_test(
            cone_grid(c),
            [&](Rng& r) { return std::optional<Vec3>(sample_uniform_cone(r.next_2d(), omc)); },
            [&](const Vec3&) { return uniform_cone_pdf(omc); }, kSamples, 16));
    }
}

TEST_CASE("chi2: uniform triangle") {
    // Barycentrics (b1, b2) placed on a skewed triangle: uniform in area, pdf 1 / area.
    TriangleGrid grid;
    grid.triangles = {{Vec3(0, 0, 0), Vec3(3, 0.5, 0), Vec3(1, 2, 1)}};
    const auto& t = grid.triangles[0];
    double area = 0.5 * cross(t.p1 - t.p0, t.p2 - t.p0).norm();
    check_passes(chi2_sampling_test(
        grid,
        [&](Rng& r) {
            Vec2 b = sample_uniform_triangle(r.next_2d());
            return std::optional<Vec3>(t.p0 + (t.p1 - t.p0) * b.x + (t.p2 - t.p0) * b.y);
        },
        [&](const Vec3&) { return uniform_triangle_pdf() / (2.0 * area); }, kSamples, 17));
}

TEST_CASE("chi2: sphere cap") {
    // Directions from `from` towards the sampled points must be uniform in
    // the cone the sphere subtends; the points must lie on the sphere and
    // face `from` (the visible cap).
    auto run = [](const Vec3& center, double radius, const Vec3& from, uint64_t seed) {
        Vec3 axis = (center - from).unit();
        double sin2 = radius * radius / (center - from).norm2();
        double cos_max = std::sqrt(1.0 - sin2);
        int off_sphere = 0, hidden = 0;
        auto sample = [&](Rng& r) -> std::optional<Vec3> {
            SphereCapSample s = sample_sphere_cap(r.next_2d(), center, radius, from);
            if (!(s.pdf > 0)) return std::nullopt;
            if (std::fabs((s.p - center).norm() - radius) > 1e-9 * radius) ++off_sphere;
            if (dot(s.n, from - s.p) < -1e-9 * radius) ++hidden;
            // The direction to the point and the sampled direction agree.
            if ((s.p - from).unit().norm() > 0 && dot((s.p - from).unit(), s.wi) < 1 - 1e-9)
                ++off_sphere;
            return s.wi;
        };
        Chi2Result r = chi2_sampling_test(
            cone_grid(cos_max, axis), sample,
            [&](const Vec3&) { return sphere_cap_pdf(center, radius, from); }, kSamples, seed);
        CHECK(off_sphere == 0);
        CHECK(hidden == 0);
        check_passes(r);
    };
    SUBCASE("distant") {
        run(Vec3(1, 2, 3), 0.5, Vec3(-2, 0.5, 1), 18);
    }
    SUBCASE("close: a wide cap") {
        run(Vec3(0, 0, 0), 1.0, Vec3(0.3, 1.0, 0.2), 19);
    }
}

TEST_CASE("warps are finite at u = 0, 0.5 and 1 - 2^-24") {
    for (double a : kAdversarial) {
        for (double b : kAdversarial) {
            Vec2 u(a, b);
            CAPTURE(a);
            CAPTURE(b);
            Vec2 d = sample_concentric_disk(u);
            CHECK((std::isfinite(d.x) && std::isfinite(d.y) && d.x * d.x + d.y * d.y <= 1 + 1e-12));
            for (Vec3 w : {sample_uniform_hemisphere(u), sample_cosine_hemisphere(u),
                           sample_uniform_sphere(u), sample_uniform_cone(u, 0.5),
                           sample_uniform_cone(u, 1e-30), sample_uniform_cone(u, 2.0)}) {
                CHECK(w.is_finite());
                CHECK(w.norm() == doctest::Approx(1.0).epsilon(1e-12));
            }
            CHECK(std::isfinite(cosine_hemisphere_pdf(sample_cosine_hemisphere(u).z)));
            Vec2 t = sample_uniform_triangle(u);
            CHECK((t.x >= 0 && t.y >= 0 && t.x + t.y <= 1));
            // Sphere caps from far away (a cone narrower than an ulp of cos),
            // from just outside, and from a generic point.
            for (double distance : {1e8, 1.0 + 1e-12, 3.0}) {
                SphereCapSample s =
                    sample_sphere_cap(u, Vec3(1, 1, 1), 1.0, Vec3(1, 1, 1) + Vec3(0, 0, distance));
                CHECK((s.p.is_finite() && s.n.is_finite() && s.wi.is_finite() &&
                       std::isfinite(s.pdf)));
                CHECK(s.pdf > 0);
                CHECK((s.p - Vec3(1, 1, 1)).norm() == doctest::Approx(1.0).epsilon(1e-9));
            }
        }
    }
    // Narrow cones keep their angle: the direction stays within theta_max.
    double omc = 1e-30;  // theta_max ~ 1.4e-15
    Vec3 w = sample_uniform_cone(Vec2(1.0 - 0x1p-24, 0.3), omc);
    CHECK(std::sqrt(w.x * w.x + w.y * w.y) <= std::sqrt(2 * omc) * (1 + 1e-9));
    CHECK(uniform_cone_pdf(omc) > 0);
    CHECK(std::isfinite(uniform_cone_pdf(omc)));
    // From on or inside the sphere: no sample, pdf 0.
    CHECK(sample_sphere_cap(Vec2(0.5, 0.5), Vec3(0, 0, 0), 1.0, Vec3(0, 0.5, 0)).pdf == 0);
    CHECK(sample_sphere_cap(Vec2(0.5, 0.5), Vec3(0, 0, 0), 1.0, Vec3(0, 1, 0)).pdf == 0);
    CHECK(sphere_cap_pdf(Vec3(0, 0, 0), 1.0, Vec3(0, 1, 0)) == 0);
}

TEST_CASE("power heuristic: weights sum to 1 and never NaN") {
    CHECK(power_heuristic(1, 2.0, 1, 2.0) == doctest::Approx(0.5));
    CHECK(power_heuristic(4, 1.0, 1, 2.0) + power_heuristic(1, 2.0, 4, 1.0) ==
          doctest::Approx(1.0));
    CHECK(power_heuristic(1, 0.0, 1, 1.0) == 0.0);
    CHECK(power_heuristic(1, 1.0, 0, 5.0) == 1.0);
    CHECK(power_heuristic(1, kInfinity, 1, 1.0) == 1.0);
    CHECK(power_heuristic(1, 1.0, 1, kInfinity) == 0.0);
    CHECK(power_heuristic(1, 1e300, 1, 1e300) == doctest::Approx(0.5));
    CHECK(power_heuristic(1, 1e-300, 1, 1e300) == 0.0);
    CHECK_FALSE(std::isnan(power_heuristic(1, kInfinity, 1, kInfinity)));
}
