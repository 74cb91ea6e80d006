// Chi-square test of the BSDF's sample_f against its pdf (chi2.h). Part 4
// adds one test per new material here.
#include <doctest/doctest.h>

#include <cstdlib>

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
