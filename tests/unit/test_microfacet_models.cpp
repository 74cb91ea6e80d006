// The microfacet distributions (scene/microfacet_distribution.h) and the
// glossy BSDFs built on them (scene/microfacet_bsdf.h): each D normalised
// over projected area, each Smith G1 against the visible-area identity,
// white-furnace energy (at most 1, and close to 1 when smooth), reciprocity,
// and the rough dielectric approaching smooth glass as roughness vanishes.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "core/math.h"
#include "core/rng.h"
#include "scene/bsdf.h"
#include "scene/fresnel.h"
#include "scene/material.h"
#include "scene/microfacet_bsdf.h"
#include "scene/microfacet_distribution.h"
#include "stages/direct.h"

using namespace pt;

namespace {

/// integral over the upper hemisphere of g(m) dm, midpoint rule in (z, phi).
template <class F>
double hemisphere_integral(F g, int nz = 2000, int nphi = 256) {
    double sum = 0;
    for (int i = 0; i < nz; ++i) {
        // z^2 spacing concentrates the nodes near the normal, where peaked lobes live.
        double t0 = double(i) / nz, t1 = double(i + 1) / nz;
        double z0 = 1 - t0 * t0, z1 = 1 - t1 * t1, z = 0.5 * (z0 + z1), dz = z0 - z1;
        double r = safe_sqrt(1 - z * z);
        for (int j = 0; j < nphi; ++j) {
            double phi = kTwoPi * (j + 0.5) / nphi;
            sum += g(Vec3(r * std::cos(phi), r * std::sin(phi), z)) * dz * (kTwoPi / nphi);
        }
    }
    return sum;
}

struct Model {
    MicrofacetDistribution d;
    const char* name;
};

std::vector<Model> models() {
    return {{MicrofacetDistribution(MicrofacetModel::ggx, 0.3, 0.3), "ggx 0.3"},
            {MicrofacetDistribution(MicrofacetModel::ggx, 0.1, 0.6), "ggx 0.1 x 0.6"},
            {MicrofacetDistribution(MicrofacetModel::beckmann, 0.3, 0.3), "beckmann 0.3"},
            {MicrofacetDistribution(MicrofacetModel::beckmann, 0.6, 0.2), "beckmann 0.6 x 0.2"},
            {MicrofacetDistribution::blinn_phong(0), "blinn-phong 0"},
            {MicrofacetDistribution::blinn_phong(1), "blinn-phong 1"},
            {MicrofacetDistribution::blinn_phong(30), "blinn-phong 30"},
            {MicrofacetDistribution::blinn_phong(300), "blinn-phong 300"}};
}

Material rough(MaterialType type, MicrofacetModel model, double ax, double ay, double exponent = 0) {
    Material m;
    m.type = type;
    m.distribution = model;
    m.roughness = ax;
    m.roughness_y = ay;
    m.exponent = exponent;
    m.ior = 1.5;
    m.eta = Color(1);
    m.k = Color(1e4);  // F = 1: the white furnace of the BSDF alone
    return m;
}

}  // namespace

TEST_CASE("microfacet models: D integrates to 1 over the projected hemisphere") {
    for (const Model& model : models()) {
        CAPTURE(std::string(model.name));
        CHECK(hemisphere_integral([&](const Vec3& m) { return model.d.D(m) * m.z; }) ==
              doctest::Approx(1.0).epsilon(2e-3));
    }
}

TEST_CASE("microfacet models: Smith G1 satisfies the visible-area identity") {
    // integral G1(wo) max(0, wo . m) D(m) dm = cos(theta_o) (Heitz 2014, eq. 2):
    // the facets seen from wo project to the surface's own area, for each
    // model's exact Smith Lambda.
    for (const Model& model : models()) {
        for (Vec3 wo : {Vec3(0, 0, 1), Vec3(0.6, 0, 0.8), Vec3(-0.5, 0.7, 0.3).unit(), Vec3(0.2, -0.95, 0.1).unit()}) {
            CAPTURE(std::string(model.name));
            CAPTURE(wo.z);
            double visible = hemisphere_integral([&](const Vec3& m) { return std::max(0.0, dot(wo, m)) * model.d.D(m); });
            double tolerance = 2e-3;
            CHECK(model.d.G1(wo) * visible == doctest::Approx(wo.z).epsilon(tolerance));
            // The visible-normal density integrates to 1 (the pdf of sample_normal for GGX).
            if (model.d.model() == MicrofacetModel::ggx)
                CHECK(hemisphere_integral([&](const Vec3& m) { return model.d.normal_pdf(wo, m); }) ==
                      doctest::Approx(1.0).epsilon(2e-3));
        }
    }
}

TEST_CASE("white furnace: glossy BSDFs reflect at most what arrives, nearly all of it when smooth") {
    const int n = 40000;
    uint64_t seed = 1;
    for (MaterialType type : {MaterialType::microfacet, MaterialType::rough_dielectric}) {
        for (MicrofacetModel model : {MicrofacetModel::ggx, MicrofacetModel::beckmann, MicrofacetModel::blinn_phong}) {
            for (double alpha : {0.05, 0.3, 1.0}) {
                // Blinn-Phong's exponent of the same roughness: e = 2 / alpha^2 - 2.
                Material m = rough(type, model, alpha, alpha, 2 / (alpha * alpha) - 2);
                for (double cos_o : {0.95, 0.5, 0.1}) {
                    for (double side : {1.0, -1.0}) {
                        if (type == MaterialType::microfacet && side < 0) continue;  // two-sided by its frame
                        Vec3 wo(std::sqrt(1 - cos_o * cos_o), 0, side * cos_o);
                        AlbedoEstimate estimate = rough_albedo(m, wo, n, ++seed);
                        double a = estimate.mean, error = estimate.standard_error;
                        CAPTURE(std::string(to_string(type)));
                        CAPTURE(std::string(to_string(model)));
                        CAPTURE(alpha);
                        CAPTURE(wo.z);
                        CAPTURE(a);
                        CHECK(a <= 1.0 + 4 * error + 1e-9);
                        if (alpha <= 0.05 && cos_o > 0.4) CHECK(a >= 0.98);
                    }
                }
            }
        }
    }
}

TEST_CASE("glossy BSDFs: reciprocity, and the rough dielectric's generalised reciprocity") {
    Rng rng(5);
    for (MicrofacetModel model : {MicrofacetModel::ggx, MicrofacetModel::beckmann, MicrofacetModel::blinn_phong}) {
        Material metal = rough(MaterialType::microfacet, model, 0.3, 0.5, 20);
        metal.eta = Color(0.2, 0.9, 1.1);
        metal.k = Color(3.9, 2.4, 1.6);
        Material glass = rough(MaterialType::rough_dielectric, model, 0.3, 0.5, 20);
        for (int i = 0; i < 200; ++i) {
            auto direction = [&]() {
                double z = 2 * rng.next_1d() - 1, phi = kTwoPi * rng.next_1d(), r = safe_sqrt(1 - z * z);
                return Vec3(r * std::cos(phi), r * std::sin(phi), z);
            };
            Vec3 a = direction(), b = direction();
            CAPTURE(std::string(to_string(model)));
            Color ab = rough_conductor_f(metal, a, b), ba = rough_conductor_f(metal, b, a);
            CHECK(ab.g == doctest::Approx(ba.g).epsilon(1e-10));
            // Reflection is symmetric; refraction carries radiance's 1 / eta^2:
            // f(wi, wo) = f(wo, wi) eta^2 with eta = n(wi side) / n(wo side).
            double eta = a.z * b.z > 0 ? 1.0 : (a.z > 0 ? 1.5 : 1 / 1.5);
            Color gab = rough_dielectric_f(glass, a, b), gba = rough_dielectric_f(glass, b, a);
            CHECK(gba.g == doctest::Approx(gab.g * eta * eta).epsilon(1e-9));
            // pdf is defined for both orders, and zero exactly where f is.
            CHECK((rough_dielectric_pdf(glass, a, b) > 0) == (gab.g > 0));
            CHECK((rough_dielectric_pdf(glass, b, a) > 0) == (gba.g > 0));
        }
    }
}

TEST_CASE("rough dielectric: as roughness vanishes, it reflects F and refracts 1 - F like glass") {
    Material m = rough(MaterialType::rough_dielectric, MicrofacetModel::ggx, 0.002, 0.002);
    BSDF bsdf(m, Frame(), {reference::diffuse_f, reference::diffuse_sample_f});
    for (double cos_o : {0.9, 0.5, -0.9, -0.8}) {
        Vec3 wo(std::sqrt(1 - cos_o * cos_o), 0, cos_o);
        Rng rng(uint64_t(100 * (cos_o + 2)));
        const int n = 100000;
        double reflected = 0, transmitted = 0;
        for (int i = 0; i < n; ++i) {
            BSDFSample s = bsdf.sample_f(wo, rng.next_2d());
            if (!s.valid()) continue;
            double w = s.f.g * std::fabs(s.wi.z) / s.pdf;
            (s.wi.z * wo.z > 0 ? reflected : transmitted) += w;
        }
        double F = fresnel_dielectric(cos_o, 1.5);
        CAPTURE(cos_o);
        CHECK(reflected / n == doctest::Approx(F).epsilon(0.01));
        // Transmitted radiance carries 1 / eta^2 (as glass's does).
        double eta = cos_o > 0 ? 1.5 : 1 / 1.5;
        CHECK(transmitted / n == doctest::Approx((1 - F) / (eta * eta)).epsilon(0.01));
    }
}
