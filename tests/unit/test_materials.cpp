// Part 4's materials against hand-worked values: Fresnel (normal incidence,
// total internal reflection, grazing), the mirror direction, Snell's law
// for glass with the radiance factor, and the microfacet conductor: D
// normalised, every sample's weight at most the Fresnel term (so energy <=
// 1, the white furnace of the BSDF alone), reciprocity, and the scene and
// MTL mappings of the new material.
#include <doctest/doctest.h>

#include <cmath>

#include "core/error.h"
#include "core/frame.h"
#include "core/math.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "scene/bsdf.h"
#include "scene/fresnel.h"
#include "scene/material.h"
#include "scene/microfacet.h"
#include "scene/scene_loader.h"
#include "stages/direct.h"
#include "test_util.h"

using namespace pt;

namespace {

BSDF make_bsdf(const Material& m, const Frame& frame = Frame()) {
    return BSDF(m, frame, {reference::diffuse_f, reference::diffuse_sample_f});
}
BSDF make_bsdf(Material&& m, const Frame& frame = Frame()) = delete;  // the BSDF would dangle

Material conductor(double roughness, const Color& eta, const Color& k) {
    Material m;
    m.type = MaterialType::microfacet;
    m.roughness = roughness;
    m.eta = eta;
    m.k = k;
    return m;
}

}  // namespace

TEST_CASE("Fresnel: dielectric at normal, critical and grazing incidence; conductors") {
    CHECK(fresnel_dielectric(1.0, 1.5) == doctest::Approx(0.04));   // ((n - 1) / (n + 1))^2
    CHECK(fresnel_dielectric(-1.0, 1.5) == doctest::Approx(0.04));  // the same from inside
    CHECK(fresnel_dielectric(0.0, 1.5) == doctest::Approx(1.0));    // grazing
    // From inside, beyond the critical angle asin(1 / 1.5) = 41.8 degrees: all reflected.
    CHECK(fresnel_dielectric(-std::cos(radians(42.0)), 1.5) == 1.0);
    CHECK(fresnel_dielectric(-std::cos(radians(41.0)), 1.5) < 1.0);
    // Reciprocity: the same F seen from both sides of a refracted pair.
    double cos_out = std::cos(radians(50.0));
    double sin_in = std::sin(radians(50.0)) / 1.5;
    CHECK(fresnel_dielectric(cos_out, 1.5) ==
          doctest::Approx(fresnel_dielectric(-std::sqrt(1 - sin_in * sin_in), 1.5)));
    // A conductor without absorption is a dielectric; at normal incidence
    // ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2).
    CHECK(fresnel_conductor(std::cos(0.7), 1.5, 0.0) ==
          doctest::Approx(fresnel_dielectric(std::cos(0.7), 1.5)));
    CHECK(fresnel_conductor(1.0, 0.2, 3.9) ==
          doctest::Approx((0.64 + 3.9 * 3.9) / (1.44 + 3.9 * 3.9)));
    CHECK(fresnel_conductor(0.0, 0.2, 3.9) == doctest::Approx(1.0));
    // The colour mapping (Gulbrandsen 2014): r at normal incidence, back again.
    Color r(0.95, 0.64, 0.54);
    ConductorIndex index = conductor_from_reflectance(r);
    Color back = fresnel_conductor(1.0, index.eta, index.k);
    CHECK(back.r == doctest::Approx(r.r));
    CHECK(back.g == doctest::Approx(r.g));
    CHECK(back.b == doctest::Approx(r.b));
}

TEST_CASE("mirror: wi = 2 (n . wo) n - wo in world space, weight = reflectance") {
    Material mirror;
    mirror.type = MaterialType::mirror;
    mirror.reflectance = Color(0.9, 0.5, 0.1);
    Rng rng(3);
    for (int i = 0; i < 100; ++i) {
        Vec3 n = sample_uniform_sphere(rng.next_2d());
        Vec3 wo = sample_uniform_sphere(rng.next_2d());
        if (dot(wo, n) < 0) wo = -wo;
        BSDF bsdf = make_bsdf(mirror, Frame(n));
        BSDFSample s = bsdf.sample_f(bsdf.to_local(wo), rng.next_2d());
        REQUIRE(s.valid());
        Vec3 expected = 2 * dot(n, wo) * n - wo;
        Vec3 got = bsdf.to_world(s.wi);
        CHECK((got - expected).norm() < 1e-12);
        Color weight = s.f * (std::fabs(s.wi.z) / s.pdf);
        CHECK(weight.r == doctest::Approx(0.9));
        CHECK(weight.b == doctest::Approx(0.1));
    }
}

TEST_CASE("glass: Snell's law, Fresnel split, radiance scaled by (n_o / n_i)^2, TIR") {
    Material glass;
    glass.type = MaterialType::glass;
    glass.ior = 1.5;
    BSDF bsdf = make_bsdf(glass);
    for (double degrees : {0.0, 20.0, 60.0, 85.0}) {
        for (bool entering : {true, false}) {
            CAPTURE(degrees);
            CAPTURE(entering);
            double t = radians(degrees);
            Vec3 wo(std::sin(t) * 0.6, std::sin(t) * 0.8, std::cos(t) * (entering ? 1 : -1));
            DeltaLobe lobes[2];
            int n = bsdf.delta_lobes(wo, lobes);
            double eta = entering ? 1.5 : 1 / 1.5;  // n(wi side) / n(wo side)
            double sin_t = std::sin(t) / eta;
            if (sin_t >= 1) {  // leaving beyond the critical angle
                REQUIRE(n == 1);
                CHECK(lobes[0].probability == 1.0);
                CHECK(lobes[0].wi == Vec3(-wo.x, -wo.y, wo.z));
                continue;
            }
            REQUIRE(n == 2);
            double F = fresnel_dielectric(wo.z, 1.5);
            CHECK(lobes[0].probability == doctest::Approx(F));
            CHECK(lobes[0].probability + lobes[1].probability == doctest::Approx(1.0));
            CHECK(lobes[0].wi == Vec3(-wo.x, -wo.y, wo.z));
            const Vec3& wt = lobes[1].wi;
            CHECK(wt.norm() == doctest::Approx(1.0));
            CHECK(wt.z * wo.z < 0);  // the other side
            // n_o sin(theta_o) = n_i sin(theta_i), in the plane of incidence (opposite azimuth).
            CHECK(std::hypot(wt.x, wt.y) * eta == doctest::Approx(std::sin(t)));
            if (degrees > 0) CHECK(wt.x / wt.y == doctest::Approx(wo.x / wo.y));
            CHECK(wt.x * wo.x <= 0);
            CHECK(lobes[1].eta == doctest::Approx(eta));
            CHECK(lobes[1].weight.g == doctest::Approx((1 - F) / (eta * eta)));
            // Energy: the reflected and transmitted fractions of the flux sum to 1.
            CHECK(lobes[0].weight.g + lobes[1].weight.g * eta * eta == doctest::Approx(1.0));
        }
    }
    // f and pdf are zero for any given pair: only sampling finds the lobes.
    CHECK(bsdf.f(Vec3(0, 0, 1), Vec3(0, 0, -1)).is_black());
    CHECK(bsdf.pdf(Vec3(0, 0, 1), Vec3(0, 0, -1)) == 0);
}

TEST_CASE("GGX: D integrates to 1 over the projected hemisphere") {
    for (double alpha : {0.05, 0.3, 1.0}) {
        // integral D(m) cos(theta_m) dm in (z = cos theta, phi): 2 pi integral D z dz.
        const int n = 200000;
        double sum = 0;
        for (int i = 0; i < n; ++i) {
            double z = (i + 0.5) / n;
            double r = std::sqrt(1 - z * z);
            sum += ggx::D(Vec3(r, 0, z), alpha) * z;
        }
        CHECK(sum * kTwoPi / n == doctest::Approx(1.0).epsilon(1e-3));
    }
}

TEST_CASE("microfacet: weights f cos / pdf never exceed F (energy <= 1), reciprocity") {
    // k huge: F = 1, a perfect conductor; the white furnace of the BSDF alone.
    Material white = conductor(0.3, Color(1), Color(1e4));
    Rng rng(9);
    for (double alpha : {0.01, 0.1, 0.3, 0.7, 1.0}) {
        white.roughness = alpha;
        BSDF bsdf = make_bsdf(white);
        for (double cos_o : {1.0, 0.7, 0.3, 0.05}) {
            CAPTURE(alpha);
            CAPTURE(cos_o);
            Vec3 wo(std::sqrt(1 - cos_o * cos_o), 0, cos_o);
            double albedo = 0;
            int n = 20000, over = 0;
            for (int i = 0; i < n; ++i) {
                BSDFSample s = bsdf.sample_f(wo, rng.next_2d());
                if (!s.valid()) continue;
                double w = s.f.g * s.wi.z / s.pdf;
                over += w > 1 + 1e-9;
                albedo += w;
            }
            CHECK(over == 0);
            CHECK(albedo / n <= 1.0);
            // Smooth surfaces lose little (single scattering: light that
            // would scatter twice between facets is lost, about 1% at alpha 0.1).
            if (alpha <= 0.1 && cos_o > 0.5) CHECK(albedo / n > (alpha < 0.05 ? 0.999 : 0.97));
        }
        // Reciprocity: f(wo, wi) = f(wi, wo).
        for (int i = 0; i < 100; ++i) {
            Vec3 a = sample_cosine_hemisphere(rng.next_2d()),
                 b = sample_cosine_hemisphere(rng.next_2d());
            Color fab = bsdf.f(a, b), fba = bsdf.f(b, a);
            CHECK(fab.g == doctest::Approx(fba.g).epsilon(1e-10));
        }
    }
    // Below the surface: nothing, in either argument.
    const Material gold = conductor(0.5, Color(0.2), Color(3));
    BSDF bsdf = make_bsdf(gold);
    CHECK(bsdf.f(Vec3(0, 0, 1), Vec3(0.6, 0, -0.8)).is_black());
    CHECK(bsdf.pdf(Vec3(0, 0, 1), Vec3(0.6, 0, -0.8)) == 0);
    CHECK_FALSE(bsdf.sample_f(Vec3(0, 0.6, -0.8), Vec2(0.3, 0.3)).valid());
    CHECK_FALSE(bsdf.is_delta());
}

TEST_CASE("microfacet in scene files and MTL: strict, with the colour or the complex index") {
    auto scene_with = [](const std::string& material) {
        return R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
            "materials": {"metal": )" +
               material + R"(},
            "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "metal"}]})";
    };
    Scene s = parse_json_scene(
        scene_with(
            R"({"type": "microfacet", "roughness": 0.2, "eta": [0.2, 0.9, 1.1], "k": [3.9, 2.4, 1.6]})"),
        "m.json");
    CHECK(s.materials[0].type == MaterialType::microfacet);
    CHECK(s.materials[0].roughness == 0.2);
    CHECK(s.materials[0].k.g == 2.4);
    s = parse_json_scene(scene_with(R"({"type": "microfacet", "reflectance": [0.9, 0.6, 0.3]})"),
                         "m.json");
    CHECK(fresnel_conductor(1.0, s.materials[0].eta.b, s.materials[0].k.b) == doctest::Approx(0.3));
    auto error = [&](const std::string& material) {
        try {
            parse_json_scene(scene_with(material), "bad.json");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(error(R"({"type": "microfacet"})").find("needs \"eta\" and \"k\"") != std::string::npos);
    CHECK(error(R"({"type": "microfacet", "eta": [1, 1, 1]})").find("materials.metal.k") !=
          std::string::npos);
    CHECK(
        error(
            R"({"type": "microfacet", "reflectance": [0.5, 0.5, 0.5], "eta": [1, 1, 1], "k": [1, 1, 1]})")
            .find("not both") != std::string::npos);
    CHECK(error(R"({"type": "microfacet", "roughness": 0, "reflectance": [0.5, 0.5, 0.5]})")
              .find("materials.metal.roughness") != std::string::npos);
    CHECK(error(R"({"type": "microfacet", "roughness": 0.3, "reflectance": [1.5, 0.5, 0.5]})")
              .find("reflectance") != std::string::npos);
    CHECK(error(R"({"type": "velvet"})").find("diffuse, mirror, glass, microfacet, rough_dielectric or null") !=
          std::string::npos);

    // MTL: Pm > 0 makes a rough metal of colour Kd and alpha Pr.
    std::string dir = test::scratch_dir("materials_mtl");
    test::write_file(dir + "/metal.obj",
                     "mtllib metal.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl gold\nf 1 2 3\n");
    test::write_file(dir + "/metal.mtl", "newmtl gold\nKd 0.95 0.64 0.54\nPm 1\nPr 0.25\n");
    Scene mesh = load_scene(dir + "/metal.obj");
    const Material& gold = mesh.materials.back();
    CHECK(gold.type == MaterialType::microfacet);
    CHECK(gold.roughness == doctest::Approx(0.25));
    CHECK(fresnel_conductor(1.0, gold.eta.r, gold.k.r) == doctest::Approx(0.95).epsilon(1e-6));
}
