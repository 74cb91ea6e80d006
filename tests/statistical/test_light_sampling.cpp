// Chi-square tests of every light's sample_Li against its pdf_Li (chi2.h),
// the grouping of emissive triangles into lights, and finite results in
// the hard cases (a point on the plane of a light, on a light, at a point
// light, inside a sphere light).
#include <doctest/doctest.h>

#include <cstdlib>

#include "core/sampling.h"
#include "scene/light_set.h"
#include "scene/lights.h"
#include "scene/scene_loader.h"
#include "statistical/chi2_check.h"

using namespace pt;
using namespace pt::stats;

namespace {

constexpr int kSamples = 1000000;

/// Area sampling of a triangle light, seen from ref: the sampled points must
/// be uniform by area, and pdf_Li (a solid-angle density) converted back to
/// area by cos(theta') / r^2 must be that uniform density. A wrong r^2 or
/// cos factor in pdf_Li, or a wrong choice among the triangles, fails.
Chi2Result triangle_light_test(const std::vector<Triangle>& triangles,
                               const LightSampleContext& ref, uint64_t seed) {
    std::unique_ptr<Light> light = make_triangle_light(triangles, Color(1));
    TriangleGrid grid;
    grid.n = 20;
    for (const Triangle& t : triangles)
        grid.triangles.push_back({t.p0, t.p1, t.p2});
    auto normal_at = [&](const Vec3& p) {
        int c = grid.cell(p);
        const auto& t = grid.triangles[size_t(c / grid.cells_per_triangle())];
        return cross(t.p1 - t.p0, t.p2 - t.p0).unit();
    };
    int inconsistent = 0;
    auto sample = [&](Rng& rng) -> std::optional<Vec3> {
        LightSample s = light->sample_Li(ref, rng.next_2d());
        if (!s.valid() || !(s.L == Color(1))) return std::nullopt;
        // The pdf a sample reports is the one pdf_Li gives its direction.
        Vec3 p = s.p;
        if (grid.cell(p) < 0) return p;  // outside: counted as a failure by the test
        double pdf = light->pdf_Li(ref, s.wi, p, normal_at(p));
        if (std::fabs(pdf - s.pdf) > 1e-6 * s.pdf) ++inconsistent;
        if (dot((p - ref.p).unit(), s.wi) < 1 - 1e-9) ++inconsistent;
        return p;
    };
    auto area_pdf = [&](const Vec3& p) {
        Vec3 d = p - ref.p;
        Vec3 wi = d.unit();
        Vec3 n = normal_at(p);
        return light->pdf_Li(ref, wi, p, n) * std::fabs(dot(n, wi)) / d.norm2();
    };
    Chi2Result r = chi2_sampling_test(grid, sample, area_pdf, kSamples, seed);
    CHECK(inconsistent == 0);
    return r;
}

/// Two triangles of the quad corner + s e1 + t e2, both with normal e1 x e2.
std::vector<Triangle> quad(const Vec3& c, const Vec3& e1, const Vec3& e2) {
    Triangle a, b;
    a.p0 = c, a.p1 = c + e1, a.p2 = c + e1 + e2;
    b.p0 = c, b.p1 = c + e1 + e2, b.p2 = c + e2;
    return {a, b};
}

}  // namespace

TEST_CASE("chi2: quad light, area sampling") {
    // A unit quad facing down at height 1, a shading point 0.7 below and off
    // centre: directions span a wide solid angle, with strong r^2 / cos variation.
    std::vector<Triangle> q = quad(Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(0, 0, 1));
    check_passes(triangle_light_test(q, {Vec3(0.2, 0.3, 0.4), Vec3(0, 1, 0)}, 21));
}

TEST_CASE("chi2: triangle light of unequal, tilted triangles") {
    Triangle big, small, tilted;
    big.p0 = Vec3(-2, 2, -1), big.p1 = Vec3(1, 2, 2), big.p2 = Vec3(1, 2, -1);
    small.p0 = Vec3(2, 1.5, 0), small.p1 = Vec3(2.3, 1.5, 0.1), small.p2 = Vec3(2.1, 1.8, 0.4);
    tilted.p0 = Vec3(-1, 0.5, 2), tilted.p1 = Vec3(0, 1.5, 2.5), tilted.p2 = Vec3(-2, 1, 3);
    // Turn each to face the shading point at the origin (lights are one-sided).
    for (Triangle* t : {&big, &small, &tilted})
        if (dot(cross(t->p1 - t->p0, t->p2 - t->p0), t->p0) > 0) std::swap(t->p1, t->p2);
    check_passes(triangle_light_test({big, small, tilted}, {Vec3(0, 0, 0), Vec3(0, 1, 0)}, 22));
}

TEST_CASE("chi2: sphere light, cone sampling") {
    Sphere sphere{Vec3(0.5, 3, -0.2), 1.2};
    std::unique_ptr<Light> light = make_sphere_light(sphere, Color(2));
    LightSampleContext ref{Vec3(0, 0, 0), Vec3(0, 1, 0)};
    Vec3 axis = (sphere.center - ref.p).unit();
    double sin2 = sphere.radius * sphere.radius / (sphere.center - ref.p).norm2();
    DirectionGrid grid;
    grid.frame = Frame(axis);
    grid.z_min = std::sqrt(1 - sin2);
    grid.nz = 20;
    grid.nphi = 40;
    int off = 0;
    auto sample = [&](Rng& rng) -> std::optional<Vec3> {
        LightSample s = light->sample_Li(ref, rng.next_2d());
        if (!s.valid() || !(s.L == Color(2))) return std::nullopt;
        // The shadow-ray target is on the sphere, nudged towards ref.
        if (std::fabs((s.p - sphere.center).norm() - sphere.radius) > 1e-9) ++off;
        if (std::fabs(s.pdf - light->pdf_Li(ref, s.wi, s.p, (s.p - sphere.center).unit())) >
            1e-9 * s.pdf)
            ++off;
        return s.wi;
    };
    Chi2Result r = chi2_sampling_test(
        grid, sample, [&](const Vec3& w) { return light->pdf_Li(ref, w, {}, {}); }, kSamples, 23);
    CHECK(off == 0);
    check_passes(r);
}

TEST_CASE("chi2: constant environment light") {
    EnvironmentLight env;
    env.radiance = Color(0.5);
    std::unique_ptr<Light> light = make_environment_light(env, BBox(Vec3(-1), Vec3(1)));
    auto run = [&](const LightSampleContext& ref, uint64_t seed) {
        DirectionGrid grid;
        if (ref.n.norm2() > 0) grid.frame = Frame(ref.n);
        int wrong_target = 0;
        auto sample = [&](Rng& rng) -> std::optional<Vec3> {
            LightSample s = light->sample_Li(ref, rng.next_2d());
            if (!s.valid()) return std::nullopt;
            // The shadow-ray target lies along wi, beyond the scene's bounding sphere.
            if (((s.p - ref.p).unit() - s.wi).norm() > 1e-9) ++wrong_target;
            if ((s.p - ref.p).norm() < (ref.p - Vec3(0)).norm() + std::sqrt(3.0)) ++wrong_target;
            return s.wi;
        };
        check_passes(chi2_sampling_test(
            grid, sample, [&](const Vec3& w) { return light->pdf_Li(ref, w, {}, {}); }, kSamples,
            seed));
        CHECK(wrong_target == 0);
    };
    SUBCASE("cosine-weighted about a tilted normal") {
        run({Vec3(0.1, 0.2, 0.3), Vec3(1, 2, -2) / 3.0}, 24);
    }
    SUBCASE("uniform without a normal") {
        run({Vec3(0, 0, 0), Vec3(0, 0, 0)}, 25);
    }
}

TEST_CASE("emissive triangles form one light per quad, sphere or connected run") {
    Scene scene = parse_json_scene(R"({
        "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
        "materials": {"lamp": {"type": "diffuse", "albedo": [0, 0, 0], "emission": [4, 4, 4]},
                      "grey": {"type": "diffuse"}},
        "objects": [
            {"type": "quad", "corner": [0, 2, 0], "edge1": [0, 0, 1], "edge2": [1, 0, 0], "material": "lamp"},
            {"type": "quad", "corner": [3, 2, 0], "edge1": [0, 0, 1], "edge2": [1, 0, 0], "material": "lamp"},
            {"type": "quad", "corner": [-5, 0, -5], "edge1": [0, 0, 10], "edge2": [10, 0, 0], "material": "grey"},
            {"type": "sphere", "center": [0, 5, 0], "radius": 0.5, "material": "lamp"}
        ],
        "lights": [{"type": "point", "position": [0, 1, 0], "intensity": [1, 1, 1]},
                   {"type": "directional", "direction": [0, -1, 0], "irradiance": [1, 1, 1]},
                   {"type": "environment", "radiance": [0.1, 0.1, 0.1]}]
    })",
                                   "lights.json");
    LightSet lights(scene);
    // Two lamp quads (not sharing a vertex: two lights), one sphere, a point,
    // a directional and the environment.
    CHECK(lights.all().size() == 6);
    CHECK(lights.non_delta_count() == 4);
    CHECK(lights.light_of_primitive(0) != nullptr);
    CHECK(lights.light_of_primitive(0) == lights.light_of_primitive(1));
    CHECK(lights.light_of_primitive(2) == lights.light_of_primitive(3));
    CHECK(lights.light_of_primitive(0) != lights.light_of_primitive(2));
    CHECK(lights.light_of_primitive(4) == nullptr);  // the grey floor
    CHECK(lights.light_of_primitive(6) != nullptr);  // the sphere
    CHECK(lights.environment() != nullptr);
    CHECK(lights.environment_radiance(Vec3(0, 1, 0)) == Color(0.1));
    CHECK(lights.all()[3]->is_delta());
    CHECK(lights.all()[3]->sample_count(16) == 1);
    CHECK(lights.all()[0]->sample_count(16) == 16);
}

TEST_CASE("light samples are finite or invalid in the hard cases") {
    std::vector<Triangle> q = quad(Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(0, 0, 1));
    std::unique_ptr<Light> area = make_triangle_light(q, Color(1));
    std::unique_ptr<Light> sphere = make_sphere_light(Sphere{Vec3(0, 3, 0), 1}, Color(1));
    std::unique_ptr<Light> point = make_point_light({Vec3(0, 1, 0), Color(1)});
    std::unique_ptr<Light> degenerate =
        make_triangle_light(quad(Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)), Color(1));
    const LightSampleContext refs[] = {
        {Vec3(0.5, 1, 0.5), Vec3(0, -1, 0)},      // on the quad light
        {Vec3(3, 1, 0.5), Vec3(0, 1, 0)},         // on the quad's plane, beside it: every cos is 0
        {Vec3(0, 1, 0), Vec3(0, 1, 0)},           // at a corner of the quad; at the point light
        {Vec3(0, 2, 0), Vec3(0, 1, 0)},           // on the sphere light
        {Vec3(0, 3.2, 0), Vec3(0, 1, 0)},         // inside it
        {Vec3(0, 1 + 1e-300, 0), Vec3(0, 1, 0)},  // a hair from the light
        {Vec3(0.5, 0.5, 0.5), Vec3(0, 0, 0)},     // no normal
    };
    const double us[] = {0.0, 0.5, 1.0 - 0x1p-24};
    for (const LightSampleContext& ref : refs) {
        for (const Light* light : {area.get(), sphere.get(), point.get(), degenerate.get()}) {
            for (double a : us) {
                for (double b : us) {
                    LightSample s = light->sample_Li(ref, Vec2(a, b));
                    if (!s.valid()) continue;
                    CHECK(std::isfinite(s.pdf));
                    CHECK(s.L.is_finite());
                    CHECK(s.wi.is_finite());
                    CHECK(s.p.is_finite());
                    double pdf = light->pdf_Li(ref, s.wi, s.p, Vec3(0, -1, 0));
                    CHECK(std::isfinite(pdf));
                }
            }
        }
        // On the plane of the light, or on it, nothing can be received.
    }
    CHECK_FALSE(area->sample_Li(refs[1], Vec2(0.3, 0.3)).valid());
    CHECK_FALSE(point->sample_Li(refs[2], Vec2(0.3, 0.3)).valid());
    CHECK_FALSE(sphere->sample_Li(refs[3], Vec2(0.3, 0.3)).valid());
    CHECK_FALSE(sphere->sample_Li(refs[4], Vec2(0.3, 0.3)).valid());
    CHECK_FALSE(degenerate->sample_Li(refs[6], Vec2(0.3, 0.3)).valid());
}
