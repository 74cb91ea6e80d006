// "Simulate only what the scene calls for" (DESIGN.md "Effects"): for each
// code path the effects analysis can skip, a scene without that effect
// renders byte-identical with the path forced on (RenderSettings::force)
// and off, and the ray counts show the forced path really ran. The savings
// are measured by tools/effects_bench, not here. Also: the analysis itself
// (which scenes can cast shadows, which effects a scene has) and the
// integrator that `--integrator auto` picks.
#include <doctest/doctest.h>

#include <string>

#include "global/global_render.h"
#include "render_fixture.h"
#include "stages/effects.h"
#include "test_util.h"

using namespace pt;
using namespace pt::global_test;

namespace {

const char* kSphereUnderSky = R"({
    "camera": {"position": [0, 0.5, 4], "look_at": [0, 0, 0], "vfov": 40},
    "film": {"width": 16, "height": 16},
    "materials": {"grey": {"type": "diffuse", "albedo": [0.6, 0.5, 0.4]}},
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "grey"}],
    "lights": [{"type": "environment", "radiance": [1, 0.8, 0.6]},
               {"type": "point", "position": [2, 3, 2], "intensity": [4, 4, 4]}]
})";

// Point lights, a diffuse floor and wall, a mirror: nothing emits.
std::string point_lit(
    const std::string& lights =
        R"({"type": "point", "position": [1, 3, 2], "intensity": [10, 10, 10]})") {
    return R"({
    "camera": {"position": [0, 1.5, 5], "look_at": [0, 0.5, 0], "vfov": 40},
    "film": {"width": 16, "height": 12},
    "materials": {"floor": {"type": "diffuse", "albedo": [0.7, 0.7, 0.6]},
                  "chrome": {"type": "mirror", "reflectance": [0.9, 0.9, 0.9]}},
    "objects": [
      {"type": "quad", "corner": [-5, 0, 5], "edge1": [10, 0, 0], "edge2": [0, 0, -10], "material": "floor"},
      {"type": "quad", "corner": [-5, 0, -2], "edge1": [10, 0, 0], "edge2": [0, 5, 0], "material": "floor"},
      {"type": "sphere", "center": [0, 0.6, 0], "radius": 0.6, "material": "chrome"}
    ],
    "lights": [)" +
           lights + R"(]
})";
}
const std::string kPointLit = point_lit();

Scene cbox() {
    Scene scene = load_scene(test::source_path("assets/scenes/cbox.json"));
    scene.film_width = scene.film_height = 16;
    return scene;
}

/// Renders `scene` with and without `force` set on the given code path.
void check_identical_when_forced(const Scene& scene, RenderSettings settings, bool CodePaths::*path,
                                 IntegratorKind kind, uint64_t RayCounters::*witness = nullptr) {
    RenderResult off = render(scene, settings, kind);
    settings.force.*path = true;
    RenderResult on = render(scene, settings, kind);
    CHECK(same_pixels(off.image, on.image));
    if (witness) {
        CHECK(off.counters.*witness == 0);
        CHECK(on.counters.*witness > 0);
    }
}

}  // namespace

TEST_CASE("effects: shadow rays are skipped only where nothing can cast a shadow") {
    // One sphere seen from outside, a plane, the inside of a convex box with
    // its own walls as lights: nothing can block a light sample.
    CHECK_FALSE(scene_can_occlude(scene_from(kSphereUnderSky)));
    CHECK_FALSE(scene_can_occlude(test::make_quad_scene(4, 4)));
    const double rho[3] = {0.5, 0.5, 0.5}, Le[3] = {1, 1, 1};
    CHECK_FALSE(scene_can_occlude(scene_from(closed_box(glowing_wall(rho, Le), 4))));
    CHECK_FALSE(scene_can_occlude(scene_from(
        closed_box(glowing_wall(rho, Le), 4,
                   R"({"type": "point", "position": [0.5, 0.2, 0], "intensity": [1, 1, 1]})"))));
    // A light outside the box, the sky around it, or a camera inside the
    // sphere with the sky outside: blocked light samples are possible.
    CHECK(scene_can_occlude(scene_from(
        closed_box(glowing_wall(rho, Le), 4,
                   R"({"type": "point", "position": [3, 0, 0], "intensity": [1, 1, 1]})"))));
    CHECK(scene_can_occlude(scene_from(closed_box(
        glowing_wall(rho, Le), 4, R"({"type": "environment", "radiance": [1, 1, 1]})"))));
    std::string inside = kSphereUnderSky;
    inside.replace(inside.find("[0, 0.5, 4]"), 11, "[0, 0.5, 0]");
    CHECK(scene_can_occlude(scene_from(inside)));
    CHECK(scene_can_occlude(cbox()));
    CHECK(scene_can_occlude(scene_from(kPointLit)));
}

TEST_CASE("effects: each skipped code path changes no pixel when forced on") {
    SUBCASE("shadow rays: a sphere under the sky and a point light") {
        for (DirectStrategy strategy : {DirectStrategy::light, DirectStrategy::mis}) {
            RenderSettings s = path_settings(3, 4);
            s.direct = strategy;
            check_identical_when_forced(scene_from(kSphereUnderSky), s, &CodePaths::shadow_rays,
                                        IntegratorKind::path, &RayCounters::shadow_rays);
        }
        // And the interior furnace box, whose lights are its walls.
        const double rho[3] = {0.5, 0.4, 0.3}, Le[3] = {1, 1, 1};
        check_identical_when_forced(scene_from(closed_box(glowing_wall(rho, Le), 12)),
                                    path_settings(4, 2), &CodePaths::shadow_rays,
                                    IntegratorKind::path, &RayCounters::shadow_rays);
    }
    SUBCASE("lens sampling: a pinhole camera") {
        check_identical_when_forced(cbox(), path_settings(3, 2), &CodePaths::lens_sampling,
                                    IntegratorKind::path);
        check_identical_when_forced(scene_from(kSphereUnderSky), path_settings(1, 4),
                                    &CodePaths::lens_sampling, IntegratorKind::direct);
    }
    SUBCASE("emission look-ups: only point lights") {
        for (DirectStrategy strategy : {DirectStrategy::light, DirectStrategy::mis}) {
            RenderSettings s = path_settings(2, 4);
            s.direct = strategy;
            // At the last bounce, the forced path traces a ray after the
            // mirror to look for emission that cannot be there.
            RenderResult off = render(scene_from(kPointLit), s);
            s.force.emission = true;
            RenderResult on = render(scene_from(kPointLit), s);
            CHECK(same_pixels(off.image, on.image));
            CHECK(on.counters.closest_hit_rays > off.counters.closest_hit_rays);
        }
    }
    SUBCASE("refraction book-keeping: no glass") {
        RenderSettings s = path_settings(8, 2);
        s.rr_depth = 0;  // roulette at every bounce, where eta^2 would enter
        check_identical_when_forced(scene_from(kPointLit), s, &CodePaths::refraction,
                                    IntegratorKind::path);
        check_identical_when_forced(cbox(), s, &CodePaths::refraction, IntegratorKind::path);
    }
    SUBCASE("light sampling: no light") {
        std::string dark = point_lit("");
        REQUIRE_FALSE(scene_from(dark).has_lights());
        check_identical_when_forced(scene_from(dark), path_settings(3, 2),
                                    &CodePaths::light_sampling, IntegratorKind::path);
    }
}

TEST_CASE("effects: the direct integrator that auto picks at -m 1 is the path tracer's image") {
    // Without mirrors or glass, a path tracer capped at one bounce computes
    // exactly what the direct integrator does, with the same random numbers.
    RenderSettings s = path_settings(1, 4);
    RenderResult direct = render(cbox(), s, IntegratorKind::direct);
    RenderResult path = render(cbox(), s, IntegratorKind::path);
    CHECK(same_pixels(direct.image, path.image));
    CHECK(direct.counters.rays() == path.counters.rays());
}

TEST_CASE("effects: Whitted at -m 1 is the path tracer without diffuse interreflection") {
    // Point light, diffuse floor and wall, a mirror: Whitted's E S* D L. The
    // path tracer at -m 3 adds diffuse interreflection (floor to wall): it
    // is at least as bright, and equal where a pixel sees no interreflection.
    Scene scene = scene_from(kPointLit);
    RenderSettings s = path_settings(1, 1);
    RenderResult whitted = render(scene, s, IntegratorKind::whitted);
    CHECK(whitted.counters.nonfinite_samples == 0);
    // Deterministic: another seed gives the same bytes.
    s.seed = 99;
    CHECK(same_pixels(whitted.image, render(scene, s, IntegratorKind::whitted).image));
    // The mirror sphere shows the lit floor in Whitted; at -m 1 the path
    // tracer sees it black (a reflection of the floor is a second bounce).
    RenderResult direct = render(scene, s, IntegratorKind::path);
    double whitted_sum = 0, path_sum = 0;
    for (float v : whitted.image.data())
        whitted_sum += v;
    for (float v : direct.image.data())
        path_sum += v;
    CHECK(whitted_sum > path_sum);
}

TEST_CASE("effects: what the analysis reports and what auto picks") {
    RenderSettings s;
    s.max_depth = 1;
    Effects e = analyze_effects(cbox(), s);
    CHECK(e.to_string() == "emission_visible, area_lights, soft_shadows");
    std::string why;
    CHECK(choose_integrator(cbox(), e, s, &why) == IntegratorKind::direct);
    s.max_depth = 5;
    e = analyze_effects(cbox(), s);
    CHECK(e.diffuse_interreflection);
    CHECK(choose_integrator(cbox(), e, s, &why) == IntegratorKind::path);

    Scene spheres = load_scene(test::source_path("assets/scenes/cbox_spheres.json"));
    s.max_depth = 1;
    e = analyze_effects(spheres, s);
    CHECK(e.mirror);
    CHECK(e.refraction);
    CHECK_FALSE(e.caustics);
    // The lamp seen in the mirror sphere is a one-bounce path.
    CHECK(choose_integrator(spheres, e, s, &why) == IntegratorKind::path);
    s.max_depth = 0;
    CHECK(choose_integrator(spheres, analyze_effects(spheres, s), s, &why) ==
          IntegratorKind::direct);

    Scene whitted = load_scene(test::source_path("assets/scenes/whitted.json"));
    s.max_depth = 1;
    e = analyze_effects(whitted, s);
    CHECK(e.to_string() == "point_lights, hard_shadows, mirror, refraction");
    CHECK(choose_integrator(whitted, e, s, &why) == IntegratorKind::whitted);
    s.max_depth = 5;
    // Point lights and glass over a floor: caustics only photon mapping carries.
    CHECK(analyze_effects(whitted, s).point_light_caustics);
    CHECK(analyze_effects(whitted, s).specular_diffuse_specular);
    CHECK(choose_integrator(whitted, analyze_effects(whitted, s), s, &why) == IntegratorKind::sppm);
    CHECK(why.find("photon mapping") != std::string::npos);
    // A student's global stage always runs in the path tracer.
    s.max_depth = 1;
    CHECK(choose_integrator(cbox(), analyze_effects(cbox(), s), s, &why,
                            StageSet::parse("global")) == IntegratorKind::path);
    // A thin lens is depth of field; -o 0 -m 1 hides the emission seen directly.
    Scene lens = cbox();
    lens.camera.lens_radius = 10;
    CHECK(analyze_effects(lens, s).depth_of_field);
    s.accumulate_bounces = false;
    CHECK_FALSE(analyze_effects(cbox(), s).emission_visible);
}
