// Chi-square tests of the BSDFs' sample_f against their pdf (chi2.h): the
// diffuse lobe, the microfacet conductor, and glass's two discrete lobes.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>

#include "core/math.h"

#include "scene/bsdf.h"
#include "scene/material.h"
#include "stages/direct.h"
#include "statistical/chi2_check.h"

using namespace pt;
using namespace pt::stats;

TEST_CASE("chi2: diffuse BSDF sample_f") {
    Material m;
    m.albedo = Color(0.7, 0.5, 0.2);
    BSDF bsdf(m, Frame(), {reference::diffuse_f, reference::diffuse_sample_f});
    Vec3 wo = Vec3(0.3, -0.2, 0.8).unit();
    int inconsistent = 0;
    auto sample = [&](Rng& rng) -> std::optional<Vec3> {
        BSDFSample s = bsdf.sample_f(wo, rng.next_2d());
        if (!s.valid() || s.is_delta) return std::nullopt;
        // What a sample reports is what f and pdf say about its direction.
        if (!(s.f == bsdf.f(wo, s.wi)) || std::fabs(s.pdf - bsdf.pdf(wo, s.wi)) > 1e-12)
            ++inconsistent;
        return s.wi;
    };
    Chi2Result r = chi2_sampling_test(
        DirectionGrid{}, sample, [&](const Vec3& w) { return bsdf.pdf(wo, w); }, 1000000, 31);
    check_passes(r);
    CHECK(inconsistent == 0);
}

namespace {

Material microfacet(double roughness) {
    Material m;
    m.type = MaterialType::microfacet;
    m.roughness = roughness;
    m.eta = Color(0.2, 0.9, 1.1);
    m.k = Color(3.9, 2.4, 1.6);
    return m;
}

/// The upper hemisphere of the surface frame (z_min = 0, so the horizon,
/// where the pdf drops to 0, is a cell edge), each cell integrated as 4 x 4
/// sub-cells: the GGX lobe is peaked.
SubdividedDirectionGrid hemisphere_grid() { return {DirectionGrid{Frame(), 40, 80, 0.0}, 4}; }

}  // namespace

// Visible-normal sampling of GGX: the directions against pdf(wo, wi) on the
// upper hemisphere. A sample
// reflected below the surface is "no sample" (one more cell, expecting the
// probability the pdf leaves out). 3 roughnesses x 2 directions: 6 tests.
TEST_CASE("chi2: microfacet (GGX, visible normals) sample_f") {
    for (double roughness : {0.2, 0.5, 1.0}) {
        for (Vec3 wo : {Vec3(0.2, 0.1, 0.97).unit(), Vec3(0.8, -0.3, 0.25).unit()}) {
            CAPTURE(roughness);
            CAPTURE(wo.z);
            Material m = microfacet(roughness);
            BSDF bsdf(m, Frame(), {reference::diffuse_f, reference::diffuse_sample_f});
            int inconsistent = 0;
            auto sample = [&](Rng& rng) -> std::optional<Vec3> {
                BSDFSample s = bsdf.sample_f(wo, rng.next_2d());
                if (!s.valid()) return std::nullopt;
                if (s.is_delta || !(s.wi.z > 0)) ++inconsistent;
                // A sample reports what f and pdf say about its direction.
                Color f = bsdf.f(wo, s.wi);
                if (std::fabs(s.f.g - f.g) > 1e-9 * f.g ||
                    std::fabs(s.pdf - bsdf.pdf(wo, s.wi)) > 1e-9 * s.pdf)
                    ++inconsistent;
                return s.wi;
            };
            Chi2Result r = chi2_sampling_test(
                hemisphere_grid(), sample, [&](const Vec3& w) { return bsdf.pdf(wo, w); }, 1000000,
                uint64_t(100 * roughness + 10 * wo.z), /*may_fail=*/true);
            check_passes(r);
            CHECK(inconsistent == 0);
        }
    }
}

// Glass is a delta with two lobes: sample_f must return exactly the two
// directions (mirror, and Snell's refraction) with probabilities F and
// 1 - F. A discrete chi-square test of the counts, entering and leaving: 2 tests.
TEST_CASE("chi2: glass picks reflection with probability F and refraction with 1 - F") {
    Material glass;
    glass.type = MaterialType::glass;
    glass.ior = 1.5;
    BSDF bsdf(glass, Frame(), {reference::diffuse_f, reference::diffuse_sample_f});
    // Entering at 60 degrees (F = 0.0918); leaving at 35 degrees (below the
    // critical 41.8, F = 0.0632 by symmetry with the refracted 59.4).
    for (Vec3 wo : {Vec3(std::sin(radians(60)), 0, std::cos(radians(60))),
                    Vec3(std::sin(radians(35)), 0, -std::cos(radians(35)))}) {
        CAPTURE(wo.z);
        DeltaLobe lobes[2];
        REQUIRE(bsdf.delta_lobes(wo, lobes) == 2);
        std::vector<double> observed(2, 0.0),
            expected = {lobes[0].probability, lobes[1].probability};
        const int n = 200000;
        Rng rng(uint64_t(1000 * (wo.z + 2)));
        int other = 0;
        for (int i = 0; i < n; ++i) {
            BSDFSample s = bsdf.sample_f(wo, rng.next_2d());
            REQUIRE(s.valid());
            REQUIRE(s.is_delta);
            if (s.wi == lobes[0].wi && s.pdf == lobes[0].probability)
                observed[0] += 1;
            else if (s.wi == lobes[1].wi && s.pdf == lobes[1].probability)
                observed[1] += 1;
            else
                ++other;
        }
        CHECK(other == 0);
        for (double& e : expected)
            e *= n;
        check_passes(chi2_test(observed, expected, per_test_significance()));
    }
}
