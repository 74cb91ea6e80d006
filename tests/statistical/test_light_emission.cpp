// Emission sampling of every light kind (Light::sample_Le, pdf_Le, power;
// scene/light_set.h), what light subpaths (Part 7) and photons (Part 8)
// start from:
//   - chi-square of the origins and directions that sample_Le draws against
//     the densities pdf_Le reports (chi2.h; 10 tests of the family);
//   - every sample's densities are the ones pdf_Le gives its ray;
//   - power() equals its closed form, and the mean flux of sampled rays,
//     Le |cos| / (pdf_pos pdf_dir), equals power() (within 4.5 standard
//     errors, two-sided 7e-6 per check; exactly where every ray carries
//     the same flux);
//   - the environment map's integral of Le against Monte Carlo over the sphere;
//   - light selection by power picks each light in proportion to its power.
#include <doctest/doctest.h>

#include <cmath>

#include "core/bbox.h"
#include "core/math.h"
#include "core/sampling.h"
#include "image/image_io.h"
#include "scene/environment_map.h"
#include "scene/interaction.h"
#include "scene/light_set.h"
#include "scene/lights.h"
#include "scene/scene_loader.h"
#include "statistical/chi2_check.h"
#include "statistical/latlong_grid.h"
#include "test_util.h"

using namespace pt;
using namespace pt::stats;

namespace {

constexpr int kSamples = 400000;

/// The scene bounds every light at infinity here is built with, and the
/// bounding sphere the emission disks are placed by.
const BBox kBounds(Vec3(-1, -0.5, 0), Vec3(2, 1.5, 1));
Vec3 bounds_centre() { return kBounds.centroid(); }
double bounds_radius() { return 0.5 * kBounds.extent().norm(); }

/// Two triangles of the quad corner + s e1 + t e2, both with normal e1 x e2.
std::vector<Triangle> quad(const Vec3& c, const Vec3& e1, const Vec3& e2) {
    Triangle a, b;
    a.p0 = c, a.p1 = c + e1, a.p2 = c + e1 + e2;
    b.p0 = c, b.p1 = c + e1 + e2, b.p2 = c + e2;
    return {a, b};
}

/// Draws n rays from `light`, counts those whose densities, direction or
/// side disagree with pdf_Le in *inconsistent, and returns their mean flux
/// with its standard error per channel.
struct FluxEstimate {
    Color mean, standard_error;
};
FluxEstimate mean_flux(const Light& light, int n, uint64_t seed, int* inconsistent) {
    Rng rng(seed);
    Color sum, sum2;
    for (int i = 0; i < n; ++i) {
        Vec2 u_pos = rng.next_2d(), u_dir = rng.next_2d();
        LightEmission e = light.sample_Le(u_pos, u_dir);
        if (!e.valid()) continue;  // counts as zero flux
        LightEmissionPdf pdf = light.pdf_Le(e.p, e.n, e.w);
        // Deltas report 1 when sampled and 0 when asked (a ray cannot find them).
        bool delta_pos = light.kind() == LightKind::point, delta_dir = light.kind() == LightKind::directional;
        if (!delta_pos && std::fabs(pdf.pos - e.pdf_pos) > 1e-12 * e.pdf_pos) ++*inconsistent;
        if (!delta_dir && std::fabs(pdf.dir - e.pdf_dir) > 1e-9 * e.pdf_dir) ++*inconsistent;
        if (std::fabs(e.w.norm() - 1) > 1e-12) ++*inconsistent;
        // The ray leaves on the emitting side (an area light's), off its surface.
        if (e.n.norm2() > 0 && !(dot(e.n, e.w) > 0)) ++*inconsistent;
        Color f = e.flux();
        sum += f;
        sum2 += f * f;
    }
    FluxEstimate r;
    r.mean = sum / double(n);
    Color var = sum2 / double(n) - r.mean * r.mean;
    r.standard_error = Color(std::sqrt(std::max(var.r, 0.0) / n), std::sqrt(std::max(var.g, 0.0) / n),
                             std::sqrt(std::max(var.b, 0.0) / n));
    return r;
}

/// The mean flux of sampled rays equals power(), and power() its closed form.
void check_power(const Light& light, const Color& closed_form, uint64_t seed) {
    Color power = light.power();
    for (int c = 0; c < 3; ++c) CHECK(power[c] == doctest::Approx(closed_form[c]).epsilon(1e-12));
    int inconsistent = 0;
    FluxEstimate f = mean_flux(light, kSamples, seed, &inconsistent);
    CHECK(inconsistent == 0);
    for (int c = 0; c < 3; ++c) {
        CAPTURE(c);
        CAPTURE(f.mean[c]);
        CAPTURE(f.standard_error[c]);
        CHECK(std::fabs(f.mean[c] - power[c]) <= 4.5 * f.standard_error[c] + 1e-9 * power[c]);
    }
}

/// The points of the emission disk of a light at infinity, as unit-disk
/// coordinates in the frame of the travel direction (or a point off the disk).
std::optional<Vec2> disk_coordinates(const LightEmission& e) {
    const double R = bounds_radius();
    Vec3 q = (e.p - (bounds_centre() - e.w * R)) / R;
    if (std::fabs(dot(q, e.w)) > 1e-9) return Vec2(2, 2);  // off the disk's plane: outside
    Frame frame(e.w);
    return Vec2(dot(q, frame.s), dot(q, frame.t));
}

/// Chi-square of the disk points of a light at infinity: uniform, 1 / (pi R^2).
void check_disk(const Light& light, uint64_t seed) {
    const double R2 = bounds_radius() * bounds_radius();
    Chi2Result r = chi2_sampling_test(
        DiskGrid{},
        [&](Rng& rng) -> std::optional<Vec2> {
            LightEmission e = light.sample_Le(rng.next_2d(), rng.next_2d());
            if (!e.valid()) return std::nullopt;
            return disk_coordinates(e);
        },
        // pdf_Le.pos per unit world area, times R^2: per unit area of the unit disk.
        [&](const Vec2&) { return light.pdf_Le({}, {}, Vec3(0, 0, 1)).pos * R2; }, kSamples, seed);
    check_passes(r);
}

std::unique_ptr<Light> sky_map_light(const std::string& name, Color tint) {
    std::string path = test::scratch_dir(name) + "/sky.pfm";
    write_pfm(make_sky_image(64, 32, 30, 70), path);
    EnvironmentLight env;
    env.file = path;
    env.radiance = tint;
    return make_environment_light(env, kBounds);
}

}  // namespace

TEST_CASE("emission: area lights on triangles and quads") {
    std::vector<Triangle> q = quad(Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(0, 0, 2));  // area 2, normal -y
    std::unique_ptr<Light> light = make_triangle_light(q, Color(1, 2, 3));
    check_power(*light, Color(1, 2, 3) * (kPi * 2), 31);

    SUBCASE("chi2: origins uniform over unequal, tilted triangles") {
        Triangle big, small, tilted;
        big.p0 = Vec3(-2, 2, -1), big.p1 = Vec3(1, 2, 2), big.p2 = Vec3(1, 2, -1);
        small.p0 = Vec3(3, 2, 0), small.p1 = Vec3(3.5, 2, 0.3), small.p2 = Vec3(3.2, 2, -0.4);
        tilted.p0 = Vec3(0, 0, 4), tilted.p1 = Vec3(1, 1, 4), tilted.p2 = Vec3(0, 2, 5);
        std::unique_ptr<Light> tris = make_triangle_light({big, small, tilted}, Color(1));
        TriangleGrid grid;
        grid.n = 16;
        for (const Triangle& t : {big, small, tilted}) grid.triangles.push_back({t.p0, t.p1, t.p2});
        Chi2Result r = chi2_sampling_test(
            grid,
            [&](Rng& rng) -> std::optional<Vec3> {
                LightEmission e = tris->sample_Le(rng.next_2d(), rng.next_2d());
                if (!e.valid()) return std::nullopt;
                return e.p;
            },
            [&](const Vec3& p) { return tris->pdf_Le(p, Vec3(0, 1, 0), Vec3(0, 1, 0)).pos; }, kSamples, 32);
        check_passes(r);
        Color expected = Color(kPi * (0.5 * cross(big.p1 - big.p0, big.p2 - big.p0).norm() +
                                      0.5 * cross(small.p1 - small.p0, small.p2 - small.p0).norm() +
                                      0.5 * cross(tilted.p1 - tilted.p0, tilted.p2 - tilted.p0).norm()));
        check_power(*tris, expected, 33);
    }
    SUBCASE("chi2: directions cosine-weighted about the emitting side") {
        Vec3 n(0, -1, 0);
        DirectionGrid grid;
        grid.frame = Frame(n);
        grid.z_min = 0;
        grid.nz = 20;
        grid.nphi = 40;
        Chi2Result r = chi2_sampling_test(
            grid,
            [&](Rng& rng) -> std::optional<Vec3> {
                LightEmission e = light->sample_Le(rng.next_2d(), rng.next_2d());
                if (!e.valid() || !(e.n == n)) return std::nullopt;
                return e.w;
            },
            [&](const Vec3& w) { return light->pdf_Le(Vec3(0.5, 1, 1), n, w).dir; }, kSamples, 34);
        check_passes(r);
    }
    SUBCASE("the ray starts off the light, on its emitting side") {
        Rng rng(35);
        for (int i = 0; i < 1000; ++i) {
            LightEmission e = light->sample_Le(rng.next_2d(), rng.next_2d());
            Ray ray = e.ray();
            CHECK(ray.o.y <= 1.0);  // the light is the plane y = 1, emitting towards -y
            CHECK(ray.d == e.w);
        }
    }
}

TEST_CASE("emission: sphere lights") {
    Sphere sphere{Vec3(0.5, 3, -0.2), 0.7};
    std::unique_ptr<Light> light = make_sphere_light(sphere, Color(2, 1, 0.5));
    check_power(*light, Color(2, 1, 0.5) * (kPi * 4 * kPi * 0.49), 41);
    SUBCASE("chi2: origins uniform over the sphere") {
        DirectionGrid grid;  // the outward normal n = (p - c) / r, binned on the sphere
        grid.nz = 20;
        grid.nphi = 40;
        Chi2Result r = chi2_sampling_test(
            grid,
            [&](Rng& rng) -> std::optional<Vec3> {
                LightEmission e = light->sample_Le(rng.next_2d(), rng.next_2d());
                if (!e.valid()) return std::nullopt;
                if ((e.n - (e.p - sphere.center) / sphere.radius).norm() > 1e-12) return Vec3(0);
                return e.n;
            },
            // per unit area, times r^2: per unit solid angle of the normal
            [&](const Vec3& n) {
                return light->pdf_Le(sphere.center + n * sphere.radius, n, n).pos * sphere.radius * sphere.radius;
            },
            kSamples, 42);
        check_passes(r);
    }
    SUBCASE("chi2: directions cosine-weighted about the outward normal") {
        DirectionGrid grid;  // in each sample's own normal frame
        grid.z_min = 0;
        grid.nz = 20;
        grid.nphi = 40;
        Chi2Result r = chi2_sampling_test(
            grid,
            [&](Rng& rng) -> std::optional<Vec3> {
                LightEmission e = light->sample_Le(rng.next_2d(), rng.next_2d());
                if (!e.valid()) return std::nullopt;
                return Frame(e.n).to_local(e.w);
            },
            [&](const Vec3& local) {
                return light->pdf_Le(sphere.center + Vec3(0, 0, sphere.radius), Vec3(0, 0, 1), local).dir;
            },
            kSamples, 43);
        check_passes(r);
    }
}

TEST_CASE("emission: point lights") {
    std::unique_ptr<Light> light = make_point_light({Vec3(0.2, 0.3, 0.4), Color(3, 2, 1)});
    check_power(*light, Color(3, 2, 1) * (4 * kPi), 51);
    Chi2Result r = chi2_sampling_test(
        DirectionGrid{},
        [&](Rng& rng) -> std::optional<Vec3> {
            LightEmission e = light->sample_Le(rng.next_2d(), rng.next_2d());
            if (!e.valid() || !(e.p == Vec3(0.2, 0.3, 0.4))) return std::nullopt;
            return e.w;
        },
        [&](const Vec3& w) { return light->pdf_Le({}, {}, w).dir; }, kSamples, 52);
    check_passes(r);
}

TEST_CASE("emission: directional lights cross the whole scene from a disk") {
    Vec3 direction = Vec3(1, -2, 0.5).unit();
    std::unique_ptr<Light> light = make_directional_light({direction, Color(0.5, 1, 2)}, kBounds);
    const double R = bounds_radius();
    check_power(*light, Color(0.5, 1, 2) * (kPi * R * R), 61);
    check_disk(*light, 62);
    Rng rng(63);
    for (int i = 0; i < 1000; ++i) {
        LightEmission e = light->sample_Le(rng.next_2d(), rng.next_2d());
        CHECK(e.w == direction);
        CHECK(dot(bounds_centre() - e.p, e.w) == doctest::Approx(R));  // the disk touches the sphere
    }
}

TEST_CASE("emission: the constant environment") {
    EnvironmentLight env;
    env.radiance = Color(0.25, 0.5, 1);
    std::unique_ptr<Light> light = make_environment_light(env, kBounds);
    const double R = bounds_radius();
    check_power(*light, Color(0.25, 0.5, 1) * (4 * kPi * kPi * R * R), 71);
    check_disk(*light, 72);
    Chi2Result r = chi2_sampling_test(
        DirectionGrid{},
        [&](Rng& rng) -> std::optional<Vec3> {
            LightEmission e = light->sample_Le(rng.next_2d(), rng.next_2d());
            if (!e.valid()) return std::nullopt;
            return e.w;
        },
        [&](const Vec3& w) { return light->pdf_Le({}, {}, w).dir; }, kSamples, 73);
    check_passes(r);
}

TEST_CASE("emission: the environment map, importance-sampled") {
    std::unique_ptr<Light> light = sky_map_light("light_emission_map", Color(1, 0.5, 2));
    const double R = bounds_radius();
    // The integral of Le over the sphere, by Monte Carlo with uniform directions.
    Rng rng(81);
    Color sum, sum2;
    const int n = 400000;
    for (int i = 0; i < n; ++i) {
        Color L = light->Le(sample_uniform_sphere(rng.next_2d())) / uniform_sphere_pdf();
        sum += L;
        sum2 += L * L;
    }
    Color integral = light->power() / (kPi * R * R);  // power = pi R^2 integral Le dw
    for (int c = 0; c < 3; ++c) {
        double mean = sum[c] / n, se = std::sqrt((sum2[c] / n - mean * mean) / n);
        CAPTURE(c);
        CHECK(std::fabs(mean - integral[c]) < 4.5 * se);
    }
    check_power(*light, light->power(), 82);
    check_disk(*light, 83);
    // Directions travel away from the sky direction that the map picks.
    Chi2Result r = chi2_sampling_test(
        LatLongGrid{},
        [&](Rng& g) -> std::optional<Vec3> {
            LightEmission e = light->sample_Le(g.next_2d(), g.next_2d());
            if (!e.valid()) return std::nullopt;
            if (!(e.Le == light->Le(-e.w))) return Vec3(0);
            return -e.w;
        },
        [&](const Vec3& sky) { return light->pdf_Le({}, {}, -sky).dir; }, 1000000, 84);
    check_passes(r);
}

TEST_CASE("light selection by power") {
    Scene scene = parse_json_scene(R"({
        "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
        "materials": {"lamp": {"type": "diffuse", "albedo": [0, 0, 0], "emission": [4, 4, 4]}},
        "objects": [{"type": "quad", "corner": [0, 2, 0], "edge1": [0, 0, 1], "edge2": [1, 0, 0], "material": "lamp"}],
        "lights": [{"type": "point", "position": [0, 1, 0], "intensity": [1, 1, 1]},
                   {"type": "point", "position": [0, 1, 0], "intensity": [0, 0, 0]}]
    })",
                                   "power.json");
    LightSet lights(scene);
    REQUIRE(lights.all().size() == 3);
    // Powers pi * 4 * 1 (the quad) and 4 pi * 1 (the point light): one half each; the dark light never.
    CHECK(lights.power_probability(lights.all()[0].get()) == doctest::Approx(0.5));
    CHECK(lights.power_probability(lights.all()[1].get()) == doctest::Approx(0.5));
    CHECK(lights.power_probability(lights.all()[2].get()) == 0);
    CHECK(lights.power_probability(nullptr) == 0);
    Rng rng(91);
    int counts[3] = {0, 0, 0};
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
        double p = 0;
        const Light* light = lights.sample_by_power(rng.next_1d(), &p);
        for (int k = 0; k < 3; ++k)
            if (light == lights.all()[size_t(k)].get()) ++counts[k];
        CHECK(p == doctest::Approx(lights.power_probability(light)));
    }
    CHECK(counts[2] == 0);
    CHECK(std::fabs(counts[0] - 0.5 * n) < 4.5 * std::sqrt(0.25 * n));
    CHECK(lights.sample_by_power(0.0, nullptr) == lights.all()[0].get());
    CHECK(lights.sample_by_power(1.0 - 0x1p-32, nullptr) == lights.all()[1].get());
}
