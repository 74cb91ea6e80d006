// Sampling and shading at their limits: MIS weights with zero or infinite
// densities, grazing cosines of 1e-8, directions exactly in the tangent
// plane, and warps at the edges of [0, 1)^2 all give finite values.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "core/frame.h"
#include "core/sampling.h"
#include "scene/bsdf.h"
#include "scene/material.h"
#include "stages/direct.h"

using namespace pt;

namespace {
const double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();
bool finite(const Color& c) { return c.is_finite(); }
}  // namespace

TEST_CASE("power heuristic with zero, infinite and NaN densities") {
    CHECK(power_heuristic(1, kInf, 1, 0.5) == 1.0);   // a delta lobe against a finite one
    CHECK(power_heuristic(1, 0.5, 1, kInf) == 0.0);
    CHECK(power_heuristic(1, kInf, 1, kInf) == 0.5);  // two deltas share
    CHECK(power_heuristic(1, 0.0, 1, 3.0) == 0.0);    // a sample the strategy cannot make
    CHECK(power_heuristic(1, 0.0, 1, 0.0) == 0.0);
    CHECK(power_heuristic(1, kNaN, 1, 1.0) == 0.0);   // NaN never becomes a weight
    CHECK(power_heuristic(1, 1e300, 1, 1e300) == doctest::Approx(0.5));  // no overflow to Inf/Inf
    CHECK(power_heuristic(1, 1e-300, 1, 1e-300) == doctest::Approx(0.5));
    CHECK(power_heuristic(4, 1.0, 1, 1.0) == doctest::Approx(16.0 / 17.0));
}

TEST_CASE("balance heuristic with zero, infinite and NaN densities") {
    CHECK(balance_heuristic(1, kInf, 1, 0.5) == 1.0);
    CHECK(balance_heuristic(1, 0.5, 1, kInf) == 0.0);
    CHECK(balance_heuristic(1, kInf, 1, kInf) == 0.5);
    CHECK(balance_heuristic(1, 0.0, 1, 3.0) == 0.0);
    CHECK(balance_heuristic(1, 0.0, 1, 0.0) == 0.0);
    CHECK(balance_heuristic(1, kNaN, 1, 1.0) == 0.0);
    CHECK(balance_heuristic(1, 1e300, 1, 1e300) == doctest::Approx(0.5));
    CHECK(balance_heuristic(1, 1e-300, 1, 1e-300) == doctest::Approx(0.5));
    CHECK(balance_heuristic(4, 1.0, 1, 1.0) == doctest::Approx(4.0 / 5.0));
    // The two strategies' weights of one sample sum to 1 (unbiasedness, Veach eq. 9.12).
    CHECK(balance_heuristic(3, 0.2, 2, 1.7) + balance_heuristic(2, 1.7, 3, 0.2) ==
          doctest::Approx(1.0));
}

TEST_CASE("the diffuse BSDF at grazing angles and in the tangent plane stays finite") {
    const Color albedo(0.5, 0.6, 0.7);
    for (auto f : {reference::diffuse_f}) {
        for (double c : {1e-8, 1e-300, 0.0, -1e-8}) {
            Vec3 grazing(std::sqrt(1 - c * c), 0, c);
            Color value = f(albedo, Vec3(0, 0, 1), grazing);
            CHECK(finite(value));
            if (c > 0) CHECK(value.g == doctest::Approx(0.6 / kPi));
            if (c < 0) CHECK(value.is_black());  // below the surface: no reflection
        }
    }
    // Sampling with u at the edges of [0, 1)^2 and wo at grazing angles.
    for (double u1 : {0.0, 0.5, 1.0 - 0x1p-24})
        for (double u2 : {0.0, 0.5, 1.0 - 0x1p-24})
            for (double c : {1.0, 1e-8}) {
                Vec3 wo(std::sqrt(1 - c * c), 0, c);
                BSDFSample s = reference::diffuse_sample_f(albedo, wo, Vec2(u1, u2));
                CHECK(finite(s.f));
                CHECK(std::isfinite(s.pdf));
                CHECK(s.wi.is_finite());
                // A sample in the tangent plane (pdf 0) is flagged invalid, never divided by.
                if (s.valid()) CHECK(s.wi.z > 0);
            }
}

TEST_CASE("shading frames and warps for normals near (0, 0, -1) and inputs at the edges") {
    for (double e : {0.0, 1e-300, 1e-17, 1e-9}) {
        Frame f(Vec3(e, -e, -1).unit());
        CHECK(f.s.is_finite());
        CHECK(f.t.is_finite());
        CHECK(std::fabs(dot(f.s, f.t)) < 1e-12);
        Vec3 w = f.to_world(sample_cosine_hemisphere(Vec2(0.3, 0.7)));
        CHECK(w.is_finite());
        CHECK(dot(w, f.n) > 0);
    }
    for (double u : {0.0, 0.5, 1.0 - 0x1p-24, 1.0 - 0x1p-53}) {
        CHECK(sample_concentric_disk(Vec2(u, u)).x <= 1.0);
        CHECK(sample_uniform_sphere(Vec2(u, 1 - u)).is_finite());
        CHECK(sample_cosine_hemisphere(Vec2(u, 0.25)).z >= 0.0);
    }
}

TEST_CASE("mirror and glass samples at grazing angles never carry Inf") {
    // f = weight / |cos theta_i|: a cosine of 1e-310 would make f Inf, and
    // the estimator's f * |cos| / pdf then Inf or NaN. Such lobes give no
    // sample; ordinary angles keep f * |cos| / pdf = the lobe's weight / probability.
    for (MaterialType type : {MaterialType::mirror, MaterialType::glass}) {
        Material m;
        m.type = type;
        BSDF bsdf(m, Frame(), {reference::diffuse_f, reference::diffuse_sample_f});
        for (double c : {0.5, 1e-8, 1e-13, 1e-300, 1e-310, 0.0, -1e-310, -0.5}) {
            Vec3 wo(std::sqrt(1 - c * c), 0, c);
            for (double u : {0.01, 0.99}) {
                INFO("material " << to_string(type) << ", cos theta_o " << c << ", u " << u);
                BSDFSample s = bsdf.sample_f(wo, Vec2(u, 0.5));
                CHECK(s.is_delta);
                CHECK(finite(s.f));
                CHECK(std::isfinite(s.pdf));
                if (!s.valid()) continue;
                Color weight = s.f * std::fabs(s.wi.z) / s.pdf;
                CHECK(finite(weight));
                CHECK(std::fabs(s.wi.z) > 1e-12);
                if (type == MaterialType::mirror) CHECK(weight.g == doctest::Approx(1.0));
            }
        }
    }
}
