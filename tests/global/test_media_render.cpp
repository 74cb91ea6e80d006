// The volume path tracer (render/volpath_integrator.cpp) against closed
// forms and quadrature, with fixed seeds; means are checked within 4
// standard errors of the mean over pixels (each pixel an independent
// estimate of the same value):
//   - transmittance through an absorbing slab and sphere: exact
//     (e^(-sigma_t d) per channel, no sampling when nothing scatters);
//     through a scattering slab at -m 0, by free flights, within 4 SE;
//   - delta and ratio tracking agree with the closed form on a constant
//     grid and with each other on the cloud;
//   - single scattering (-m 1) from a point light in a slab against
//     numerical quadrature of the single-scattering integral;
//   - the medium furnace: a sphere of non-absorbing medium (chromatic
//     sigma_s, g = 0.6) with the camera inside, under a sky of radiance 1,
//     renders 1, by light sampling and by MIS, homogeneous and on the cloud;
//   - the medium in a white furnace (glowing diffuse walls around fog of
//     albedo 1) keeps Le / (1 - rho); with albedo a < 1, the k-th
//     scattering's image is a^k times the albedo-1 one;
//   - without media, volpath and path estimate the same Cornell box;
//   - the hard cases render no NaN or Inf, and one image at 1 and 2 threads.
#include <doctest/doctest.h>

#include <cmath>

#include "core/math.h"
#include "global/global_render.h"
#include "global/same_mean.h"
#include "render_fixture.h"
#include "stages/media.h"
#include "stages/medium_tracking.h"

using namespace pt;
using namespace pt::global_test;

namespace {

const std::string kCube = test::source_path("assets/meshes/cube.obj");

/// An orthographic camera 1e-3 wide at z = 3 looking down -z: every pixel
/// sees (almost) the same ray, so pixels are independent samples of one value.
std::string ortho_scene(const std::string& materials, const std::string& objects, const std::string& lights,
                        int size = 8) {
    return R"({"camera": {"type": "orthographic", "position": [0, 0, 3], "look_at": [0, 0, 0], "height": 0.001},
        "film": {"width": )" + std::to_string(size) + R"(, "height": )" + std::to_string(size) + R"(},
        "materials": {)" + materials + R"(}, "objects": [)" + objects + R"(], "lights": [)" + lights + "]}";
}

/// The slab |z| <= 0.5, 10 units wide, of material "slab".
std::string slab() {
    return R"({"type": "mesh", "file": ")" + kCube + R"(", "material": "slab", "transform": {"scale": [5, 5, 0.5]}})";
}
const std::string kBackdrop =
    R"({"type": "quad", "corner": [-5, -5, -2], "edge1": [10, 0, 0], "edge2": [0, 10, 0], "material": "lamp"})";
const std::string kLamp = R"("lamp": {"type": "diffuse", "albedo": [0, 0, 0], "emission": [1, 1, 1]})";

RenderSettings volpath_settings(int max_depth, int spp, uint64_t seed = 1) {
    RenderSettings s = path_settings(max_depth, spp, seed);
    s.integrator = IntegratorKind::volpath;
    return s;
}

}  // namespace

TEST_CASE("transmittance: an absorbing slab and sphere dim an emitter by e^(-sigma_a d), exactly") {
    Scene s = scene_from(ortho_scene(kLamp + R"(, "slab": {"type": "null", "interior": {"sigma_a": [0.2, 0.5, 0]}})",
                                     kBackdrop + ", " + slab(), ""));
    RenderResult r = render(s, volpath_settings(0, 1), IntegratorKind::volpath);
    CHECK(r.image.at(3, 3)[0] == doctest::Approx(std::exp(-0.2)).epsilon(1e-6));  // the film is float
    CHECK(r.image.at(3, 3)[1] == doctest::Approx(std::exp(-0.5)).epsilon(1e-6));
    CHECK(r.image.at(3, 3)[2] == 1.0);
    // A sphere of radius 1 on the axis: a path length of 2 (glass boundary, so
    // the ray refracts; at normal incidence it goes straight through, dimmed
    // also by Fresnel; a null boundary keeps this exact).
    s = scene_from(ortho_scene(kLamp + R"(, "ball": {"type": "null", "interior": {"sigma_a": [1, 0.25, 2]}})",
                               kBackdrop + R"(, {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "ball"})", ""));
    r = render(s, volpath_settings(0, 1), IntegratorKind::volpath);
    CHECK(r.image.at(4, 4)[0] == doctest::Approx(std::exp(-2.0)).epsilon(1e-6));
    CHECK(r.image.at(4, 4)[1] == doctest::Approx(std::exp(-0.5)).epsilon(1e-6));
    CHECK(r.image.at(4, 4)[2] == doctest::Approx(std::exp(-4.0)).epsilon(1e-6));
    // A scattering slab at -m 0: free flights that collide are dropped, those
    // that pass carry T / P; the mean is T = e^(-sigma_t), chromatic.
    s = scene_from(ortho_scene(kLamp + R"(, "slab": {"type": "null", "interior": {"sigma_a": [0.1, 0.1, 0.1], "sigma_s": [0.4, 1.0, 0]}})",
                               kBackdrop + ", " + slab(), "", 16));
    r = render(s, volpath_settings(0, 16), IntegratorKind::volpath);
    const double expected[3] = {std::exp(-0.5), std::exp(-1.1), std::exp(-0.1)};
    for (int c = 0; c < 3; ++c) {
        CAPTURE(c);
        PixelStats p = channel_stats(r.image, c);
        CHECK(std::fabs(p.z(expected[c])) <= 4.0);
    }
}

TEST_CASE("tracking: delta and ratio tracking agree with the closed form on a constant grid, and on the cloud") {
    std::string dir = test::scratch_dir("media_tracking");
    std::vector<float> ones(8, 1.0f);
    test::write_file(dir + "/one.grid", density_grid_text(2, 2, 2, BBox(Vec3(-1), Vec3(1)), ones, ""));
    Scene s = scene_from(ortho_scene(
        kLamp + R"(, "a": {"type": "null", "interior": {"sigma_a": [0.3, 0.6, 0.0], "sigma_s": [0.3, 0.6, 0.9], "density": ")" +
            dir + R"(/one.grid"}}, "b": {"type": "null", "interior": {"sigma_a": [0.5, 0.5, 0.5], "sigma_s": [2, 3, 4], "density": ")" +
            test::source_path("assets/media/cloud.grid") + R"("}})",
        kBackdrop, ""));
    Stages stages = make_stages(StageSet::none());
    std::unique_ptr<Accelerator> accelerator = build_accelerator(s, stages, AcceleratorSettings{});
    std::unique_ptr<Integrator> integrator = make_integrator(IntegratorKind::volpath);
    RenderSettings settings;
    RenderContext context{s, *accelerator, stages, settings, *integrator};
    const int n = 20000;
    auto mean_of = [&](const Medium& m, const Ray& ray, double t1, TrackingEstimator e, uint64_t seed, Color* se) {
        Rng rng(seed);
        Color sum, sum2;
        for (int i = 0; i < n; ++i) {
            Color T = segment_transmittance(context, m, ray, 0.0, t1, rng, e);
            sum += T;
            sum2 += T * T;
        }
        Color mean = sum / double(n);
        *se = Color(std::sqrt(std::max(0.0, sum2.r / n - mean.r * mean.r) / n),
                    std::sqrt(std::max(0.0, sum2.g / n - mean.g * mean.g) / n),
                    std::sqrt(std::max(0.0, sum2.b / n - mean.b * mean.b) / n));
        return mean;
    };
    // Through the constant grid: 1.6 units of sigma_t = (0.6, 1.2, 0.9).
    Ray ray(Vec3(-0.8, 0.1, 0.2), Vec3(1, 0, 0));
    for (TrackingEstimator e : {TrackingEstimator::ratio, TrackingEstimator::delta}) {
        Color se;
        Color T = mean_of(s.media[0], ray, 1.6, e, 7, &se);
        const double expected[3] = {std::exp(-0.96), std::exp(-1.92), std::exp(-1.44)};
        for (int c = 0; c < 3; ++c) CHECK(std::fabs(T[c] - expected[c]) <= 4.0 * se[c] + 1e-12);
    }
    // Through the cloud, where no closed form exists: the two agree.
    Ray through(Vec3(-1.6, 0.6, 0.1), Vec3(1, 0.05, 0).unit());
    Color se_ratio, se_delta;
    Color ratio = mean_of(s.media[1], through, 3.2, TrackingEstimator::ratio, 8, &se_ratio);
    Color delta = mean_of(s.media[1], through, 3.2, TrackingEstimator::delta, 9, &se_delta);
    for (int c = 0; c < 3; ++c) {
        CAPTURE(c);
        CHECK(ratio[c] < 0.9);  // the cloud is there
        CHECK(std::fabs(ratio[c] - delta[c]) <= 4.0 * std::hypot(se_ratio[c], se_delta[c]));
    }
    CHECK(se_ratio[0] < se_delta[0]);  // ratio tracking's point: less variance (red: T about 0.3)
    // --transmittance delta sends shadow rays to delta tracking: through the
    // cloud some return exactly 0, which ratio tracking never does there.
    auto zeros = [&](bool delta) {
        settings.delta_tracking_shadows = delta;
        Rng rng(10);
        int count = 0;
        for (int i = 0; i < 2000; ++i)
            count += shadow_transmittance(context, Ray(through.o, through.d, 0.0, 3.2), 1, rng).is_black();
        return count;
    };
    CHECK(zeros(false) == 0);
    CHECK(zeros(true) > 100);
}

TEST_CASE("single scattering from a point light in a slab matches quadrature of its integral") {
    // Camera ray down -z through the slab |z| <= 0.5 (null boundary, vacuum
    // outside); a point light at q = (0.8, 0, 1.2), above the slab. For the
    // collision at x = (0, 0, z) the light is at r = |q - x|, its shadow ray
    // leaves the slab after l = (0.5 - z) r / (1.2 - z), and
    //   L = integral_-0.5^0.5 T(0.5 - z) sigma_s p(cos) I / r^2 T(l) dz,
    // cos theta between the ray's direction (0, 0, -1) and q - x.
    const double sigma_a[3] = {0.2, 0.4, 0.1}, sigma_s[3] = {0.5, 0.3, 0.9}, g = 0.4, I = 2.0;
    Scene s = scene_from(ortho_scene(
        R"("slab": {"type": "null", "interior": {"sigma_a": )" + color_json(sigma_a) + R"(, "sigma_s": )" +
            color_json(sigma_s) + R"(, "g": 0.4}})",
        slab(), R"({"type": "point", "position": [0.8, 0, 1.2], "intensity": [2, 2, 2]})", 16));
    RenderResult r = render(s, volpath_settings(1, 64), IntegratorKind::volpath);
    for (int c = 0; c < 3; ++c) {
        const double st = sigma_a[c] + sigma_s[c];
        double integral = 0;
        const int pieces = 20000;
        for (int i = 0; i < pieces; ++i) {
            double z = -0.5 + (i + 0.5) / pieces;
            Vec3 to_light = Vec3(0.8, 0, 1.2) - Vec3(0, 0, z);
            double r2 = to_light.norm2(), dist = std::sqrt(r2);
            double cos_theta = dot(Vec3(0, 0, -1), to_light / dist);
            double l = (0.5 - z) * dist / (1.2 - z);
            integral += std::exp(-st * (0.5 - z)) * sigma_s[c] * reference::hg_phase(cos_theta, g) * I / r2 *
                        std::exp(-st * l) / pieces;
        }
        CAPTURE(c);
        PixelStats p = channel_stats(r.image, c);
        CAPTURE(p.mean);
        CAPTURE(integral);
        CHECK(std::fabs(p.z(integral)) <= 4.0);
        CHECK(p.standard_error < 0.02 * integral);  // the power to see a 8% error
    }
}

TEST_CASE("medium furnace: a non-absorbing medium under a sky of radiance 1 renders 1 from inside") {
    // The camera at the centre of a null sphere of radius 1 filled with a
    // scattering medium (albedo 1): every path ends in the sky, radiance 1.
    auto furnace = [](const std::string& medium) {
        return R"({"camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "vfov": 60}, "film": {"width": 16, "height": 16},
            "materials": {"ball": {"type": "null", "interior": )" + medium + R"(}},
            "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "ball"}],
            "lights": [{"type": "environment", "radiance": [1, 1, 1]}]})";
    };
    struct Case {
        const char* name;
        std::string medium;
        DirectStrategy direct;
        MisHeuristic heuristic = MisHeuristic::power;
    } cases[] = {
        {"homogeneous, light sampling", R"({"sigma_s": [0.5, 1, 2], "g": 0.6})", DirectStrategy::light},
        {"homogeneous, MIS", R"({"sigma_s": [0.5, 1, 2], "g": -0.3})", DirectStrategy::mis},
        // Light samples and phase samples must use the same heuristic, or their weights do not sum to 1.
        {"homogeneous, MIS by the balance heuristic", R"({"sigma_s": [0.5, 1, 2], "g": -0.3})", DirectStrategy::mis,
         MisHeuristic::balance},
        {"the cloud's density (scaled into the ball)", R"({"sigma_s": [3, 3, 3], "density": ")" +
                                                           test::source_path("assets/media/cloud.grid") + R"("})",
         DirectStrategy::light},
    };
    for (const Case& c : cases) {
        CAPTURE(c.name);
        RenderSettings settings = volpath_settings(100000, 64);
        settings.direct = c.direct;
        settings.mis_heuristic = c.heuristic;
        RenderResult r = render(scene_from(furnace(c.medium)), settings, IntegratorKind::volpath);
        for (int ch = 0; ch < 3; ++ch) {
            PixelStats p = channel_stats(r.image, ch);
            CAPTURE(ch);
            CAPTURE(p.mean);
            CHECK(std::fabs(p.z(1.0)) <= 4.0);
            CHECK(p.standard_error < 0.02);
            CHECK(p.max < 50);  // energy is not gained anywhere
        }
        CHECK(r.counters.nonfinite_samples == 0);
    }
}

TEST_CASE("medium in a white furnace: an albedo-1 fog inside glowing walls renders Le / (1 - rho)") {
    // The interior furnace (test_interior_furnace.cpp: walls that emit Le and
    // reflect diffusely with albedo rho) filled with fog that does not absorb.
    // L = Le / (1 - rho) everywhere and in every direction still solves the
    // volume rendering equation: along a ray, dL/ds = -sigma_t L + sigma_s
    // (p * L) = -sigma_a L = 0, because a phase function integrates to 1
    // whatever g. So any sigma_s and g leave the radiance where it was: energy
    // is neither gained nor lost. Uncapped (-m 100000, Russian roulette).
    // Not by light sampling alone: from a fog point at distance h from the
    // wall, the wall's points are weighted cos / r^2 with no cosine at the
    // medium point to bound it, so the estimate's variance grows as 1 / h^2
    // and its integral over the fog diverges (as light sampling in a box,
    // test_interior_furnace.cpp). MIS bounds that weight by the phase function's.
    const double rho[3] = {0.5, 0.3, 0.7}, Le[3] = {0.5, 0.7, 0.3};  // Le / (1 - rho) = 1, 1, 1
    std::string dir = test::scratch_dir("medium_white_furnace");
    write_glowing_sphere(dir, 1.0, 12, rho, Le);
    for (const char* medium : {R"({"sigma_s": [0.5, 1, 2], "g": 0.6})", R"({"sigma_s": [3, 3, 3], "g": -0.3})"}) {
        for (DirectStrategy direct : {DirectStrategy::mis, DirectStrategy::hemisphere}) {
            CAPTURE(medium);
            CAPTURE(std::string(to_string(direct)));
            test::write_file(dir + "/fog.json", R"({"camera": {"position": [0.1, 0.2, 0], "look_at": [0.4, 0.3, -1], "vfov": 70},
                "film": {"width": 16, "height": 16}, "medium": )" + std::string(medium) + R"(,
                "objects": [{"type": "mesh", "file": "glow.obj"}]})");
            RenderSettings settings = volpath_settings(100000, 16, 7);
            settings.direct = direct;
            RenderResult r = render(load_scene(dir + "/fog.json"), settings, IntegratorKind::volpath);
            CHECK(r.counters.nonfinite_samples == 0);
            for (int c = 0; c < 3; ++c) {
                PixelStats p = channel_stats(r.image, c);
                CAPTURE(c);
                CAPTURE(p.mean);
                CHECK(std::fabs(p.z(1.0)) <= 4.0);  // a correct estimator fails with probability 6.3e-5
                CHECK(p.standard_error < 0.03);
            }
        }
    }
}

TEST_CASE("medium furnace with albedo a < 1: the k-th scattering scales by a^k") {
    // The sky furnace above with sigma_t fixed and sigma_s = a sigma_t: a path
    // that escapes after exactly k collisions has the same density for every
    // a (free flights depend on sigma_t only) and carries a^k (each collision
    // scatters with weight sigma_s / sigma_t). So the image of the k-th
    // scattering alone (-m k -o 0) is a^k times the albedo-1 image, and the
    // full image is sum_k a^k p_k, where p_k, the probability of escaping
    // after k collisions, sums to 1 (the test above). Checked for k = 1, 2 on
    // two independent renders (4 standard errors of their difference).
    const double a = 0.6;
    auto furnace = [](double albedo) {
        const double sigma_t = 1.5;
        std::string s = std::to_string(albedo * sigma_t), t = std::to_string((1 - albedo) * sigma_t);
        return scene_from(R"({"camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "vfov": 60}, "film": {"width": 16, "height": 16},
            "materials": {"ball": {"type": "null", "interior": {"sigma_s": [)" + s + "," + s + "," + s +
                          R"(], "sigma_a": [)" + t + "," + t + "," + t + R"(], "g": 0.4}}},
            "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "ball"}],
            "lights": [{"type": "environment", "radiance": [1, 1, 1]}]})");
    };
    for (int k = 1; k <= 2; ++k) {
        CAPTURE(k);
        RenderSettings settings = volpath_settings(k, 256, 40 + k);
        settings.accumulate_bounces = false;
        settings.direct = DirectStrategy::mis;
        Image scaled = render(furnace(a), settings, IntegratorKind::volpath).image;
        settings.seed += 100;
        Image white = render(furnace(1.0), settings, IntegratorKind::volpath).image;
        for (float& v : white.data()) v *= static_cast<float>(std::pow(a, k));
        check_same_mean(scaled, white, 0.1);
    }
}

TEST_CASE("without media, volpath estimates the path tracer's image; auto picks volpath for media") {
    Scene s = load_scene(test::source_path("assets/scenes/cbox.json"));
    RenderSettings settings = path_settings(5, 64, 3);
    settings.integrator = IntegratorKind::path;
    Scene small = s;
    small.film_width = small.film_height = 32;
    small.camera.aspect = 1;
    RenderResult path = render(small, settings, IntegratorKind::path);
    settings.seed = 4;
    RenderResult vol = render(small, settings, IntegratorKind::volpath);
    check_same_mean(path.image, vol.image, 0.2);

    Scene fog = scene_from(ortho_scene(kLamp, kBackdrop, "") );
    CHECK(choose_integrator(fog, analyze_effects(fog, settings), RenderSettings{}, nullptr) != IntegratorKind::volpath);
    fog.media.push_back(Medium{"medium", Color(0.1), Color(0.2), 0.0, nullptr});
    fog.outside_medium = 0;
    CHECK(choose_integrator(fog, analyze_effects(fog, settings), RenderSettings{}, nullptr) == IntegratorKind::volpath);
    Effects e = analyze_effects(fog, settings);
    CHECK(e.medium_absorption);
    CHECK(e.single_scattering);
    CHECK(e.multiple_scattering);
    settings.max_depth = 1;
    CHECK_FALSE(analyze_effects(fog, settings).multiple_scattering);
}

TEST_CASE("hard cases render no NaN or Inf, the same at 1 and 2 threads") {
    // sigma_t 0 in one channel, g = +-0.999, the camera in fog, a ray grazing
    // a medium boundary (the camera at the slab's top face, looking along it).
    struct Case {
        const char* name;
        std::string json;
    } cases[] = {
        {"sigma_t 0 in one channel, g 0.999",
         ortho_scene(kLamp + R"(, "slab": {"type": "null", "interior": {"sigma_s": [0, 1, 2], "g": 0.999}})",
                     kBackdrop + ", " + slab(), R"({"type": "point", "position": [0.3, 0, 1], "intensity": [1, 1, 1]})")},
        {"g -0.999 in glass",
         ortho_scene(kLamp + R"(, "slab": {"type": "glass", "interior": {"sigma_s": [1, 1, 1], "g": -0.999}})",
                     kBackdrop + ", " + slab(), "")},
        {"camera in fog, grazing the slab", R"({"camera": {"position": [-4, 0.5, 0.5], "look_at": [4, 0.5, 0.5], "vfov": 20},
            "film": {"width": 8, "height": 8}, "medium": {"sigma_s": [0.1, 0.1, 0.1], "sigma_a": [0.05, 0, 0]},
            "materials": {)" + kLamp + R"(, "slab": {"type": "null", "interior": {"sigma_s": [2, 2, 2]}}},
            "objects": [)" + kBackdrop + ", " + slab() + R"(], "lights": [{"type": "environment", "radiance": [1, 1, 1]}]})"},
    };
    Stages stages = make_stages(StageSet::none());
    for (const Case& c : cases) {
        CAPTURE(c.name);
        Scene s = scene_from(c.json);
        RenderSettings settings = volpath_settings(8, 8);
        std::unique_ptr<Integrator> integrator = make_integrator(IntegratorKind::volpath);
        RenderResult one = test::render_with(s, *integrator, settings, stages, 1);
        RenderResult two = test::render_with(s, *integrator, settings, stages, 2);
        CHECK(one.counters.nonfinite_samples == 0);
        CHECK(one.image.data() == two.image.data());
        double sum = 0;
        for (float v : one.image.data()) sum += v;
        CHECK(std::isfinite(sum));
        CHECK(sum > 0);
    }
}
