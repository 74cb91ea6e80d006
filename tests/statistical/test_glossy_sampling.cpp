// Chi-square tests (chi2.h) of the glossy BSDFs' sample_f against their
// pdf: the rough conductor with the anisotropic GGX, Beckmann (isotropic and
// anisotropic) and Blinn-Phong distributions, and the rough dielectric
// (reflection and refraction over the whole sphere, entering and leaving).
// A sample that fails (a facet reflecting below the surface, or facing
// away) is one more cell, expecting the probability the pdf leaves out.
// Each sample's f and pdf must equal f() and pdf() for its direction.
// 14 tests.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "scene/bsdf.h"
#include "scene/material.h"
#include "stages/direct.h"
#include "statistical/chi2_check.h"

using namespace pt;
using namespace pt::stats;

namespace {

Material conductor(MicrofacetModel model, double ax, double ay, double exponent = 0) {
    Material m;
    m.type = MaterialType::microfacet;
    m.distribution = model;
    m.roughness = ax;
    m.roughness_y = ay;
    m.exponent = exponent;
    m.eta = Color(0.2, 0.9, 1.1);
    m.k = Color(3.9, 2.4, 1.6);
    return m;
}

Material dielectric(MicrofacetModel model, double ax, double ay, double exponent = 0) {
    Material m = conductor(model, ax, ay, exponent);
    m.type = MaterialType::rough_dielectric;
    m.ior = 1.5;
    return m;
}

/// Runs the chi-square test of one material's sample_f from wo, on the
/// upper hemisphere (z_min = 0) or the whole sphere (z_min = -1).
void check_sampling(const Material& m, const Vec3& wo, double z_min, uint64_t seed) {
    BSDF bsdf(m, Frame(), {reference::diffuse_f, reference::diffuse_sample_f});
    int inconsistent = 0;
    auto sample = [&](Rng& rng) -> std::optional<Vec3> {
        BSDFSample s = bsdf.sample_f(wo, rng.next_2d());
        if (!s.valid()) return std::nullopt;
        Color f = bsdf.f(wo, s.wi);
        if (s.is_delta || std::fabs(s.f.g - f.g) > 1e-9 * f.g || std::fabs(s.pdf - bsdf.pdf(wo, s.wi)) > 1e-9 * s.pdf)
            ++inconsistent;
        return s.wi;
    };
    // The whole sphere (dielectrics) has cells cut by the edge of the
    // refracted lobe's support: 8 x 8 sub-cells find the thin slivers.
    const int k = z_min < 0 ? 8 : 4;
    Chi2Result r = chi2_sampling_test(SubdividedDirectionGrid{DirectionGrid{Frame(), 40, 80, z_min}, k}, sample,
                                      [&](const Vec3& w) { return bsdf.pdf(wo, w); }, 1000000, seed,
                                      /*may_fail=*/true);
    check_passes(r);
    CHECK(inconsistent == 0);
}

const Vec3 kNearNormal = Vec3(0.2, 0.1, 0.97).unit();
const Vec3 kOblique = Vec3(0.8, -0.3, 0.25).unit();

}  // namespace

TEST_CASE("chi2: rough conductor, anisotropic GGX (visible normals)") {
    for (Vec3 wo : {kNearNormal, kOblique}) {
        CAPTURE(wo.z);
        check_sampling(conductor(MicrofacetModel::ggx, 0.1, 0.5), wo, 0.0, uint64_t(1000 * wo.z) + 1);
    }
}

TEST_CASE("chi2: rough conductor, Beckmann isotropic and anisotropic") {
    for (Vec3 wo : {kNearNormal, kOblique}) {
        CAPTURE(wo.z);
        check_sampling(conductor(MicrofacetModel::beckmann, 0.3, 0.3), wo, 0.0, uint64_t(1000 * wo.z) + 2);
    }
    check_sampling(conductor(MicrofacetModel::beckmann, 0.5, 0.15), kOblique, 0.0, 3);
}

TEST_CASE("chi2: rough conductor, normalised Blinn-Phong") {
    for (Vec3 wo : {kNearNormal, kOblique}) {
        CAPTURE(wo.z);
        check_sampling(conductor(MicrofacetModel::blinn_phong, 0, 0, 20), wo, 0.0, uint64_t(1000 * wo.z) + 4);
    }
}

TEST_CASE("chi2: rough dielectric, reflection and refraction over the sphere") {
    struct Case {
        Material material;
        Vec3 wo;
        const char* what;
    };
    const Vec3 inside_near = Vec3(0.1, 0.2, -0.97).unit(), inside_oblique = Vec3(-0.5, 0.3, -0.8).unit();
    const Case cases[] = {
        {dielectric(MicrofacetModel::ggx, 0.3, 0.3), kOblique, "GGX 0.3 entering"},
        {dielectric(MicrofacetModel::ggx, 0.3, 0.3), inside_oblique, "GGX 0.3 leaving"},
        {dielectric(MicrofacetModel::ggx, 0.8, 0.8), kNearNormal, "GGX 0.8 entering"},
        {dielectric(MicrofacetModel::beckmann, 0.3, 0.3), kNearNormal, "Beckmann 0.3 entering"},
        {dielectric(MicrofacetModel::beckmann, 0.3, 0.3), inside_near, "Beckmann 0.3 leaving"},
        {dielectric(MicrofacetModel::blinn_phong, 0, 0, 50), kOblique, "Blinn-Phong 50 entering"},
        {dielectric(MicrofacetModel::ggx, 0.15, 0.6), kNearNormal, "anisotropic GGX entering"},
    };
    uint64_t seed = 10;
    for (const Case& c : cases) {
        CAPTURE(std::string(c.what));
        check_sampling(c.material, c.wo, -1.0, ++seed);
    }
}
