// Furnace tests: a diffuse surface under constant environment light L sees
// no other surface over its whole upper hemisphere, so direct light is
//     Lo = integral_H (albedo / pi) L cos dw = albedo * L.
// Light sampling draws the environment cosine-weighted about the normal, so
// each sample is (albedo / pi) L cos / (cos / pi) = albedo * L exactly: zero
// variance, checked pixel by pixel to 1e-12. MIS weighs two such exact
// samples (light and BSDF, both cos / pi) and is exact too. Hemisphere
// sampling is unbiased but noisy: its mean within 4 standard errors.
#include <doctest/doctest.h>

#include "analytic/tiny_render.h"

using namespace pt;
using namespace pt::analytic;

namespace {

// A unit sphere filling the whole image (it subtends 11.5 degrees of half-
// angle; the image's corners are 10.6 degrees off axis).
const char* kSphereScene = R"({
    "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "vfov": 15},
    "film": {"width": 24, "height": 24},
    "materials": {"grey": {"type": "diffuse", "albedo": [0.5, 0.25, 0.8]}},
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "grey"}],
    "lights": [{"type": "environment", "radiance": [1, 2, 0.5]}]
})";

// A large plane seen from above or (two-sided shading) from below.
std::string plane_scene(double camera_y) {
    return R"({
    "camera": {"position": [0.3, )" +
           std::to_string(camera_y) + R"(, 0.2], "look_at": [0, 0, 0], "vfov": 20},
    "film": {"width": 24, "height": 24},
    "materials": {"grey": {"type": "diffuse", "albedo": [0.5, 0.25, 0.8]}},
    "objects": [{"type": "quad", "corner": [-100, 0, -100], "edge1": [200, 0, 0], "edge2": [0, 0, 200],
                 "material": "grey"}],
    "lights": [{"type": "environment", "radiance": [1, 2, 0.5]}]
})";
}

const double kExpected[3] = {0.5 * 1, 0.25 * 2, 0.8 * 0.5};

void check_exact(const RenderResult& r) {
    for (int c = 0; c < 3; ++c) {
        PixelStats s = channel_stats(r.image, c);
        CAPTURE(c);
        // Film pixels are stored as float: exact to float rounding.
        CHECK(s.min == doctest::Approx(kExpected[c]).epsilon(1e-6));
        CHECK(s.max == doctest::Approx(kExpected[c]).epsilon(1e-6));
    }
    CHECK(r.counters.nonfinite_samples == 0);
}

void check_unbiased(const RenderResult& r) {
    for (int c = 0; c < 3; ++c) {
        PixelStats s = channel_stats(r.image, c);
        CAPTURE(c);
        CAPTURE(s.mean);
        CAPTURE(s.standard_error);
        CHECK(s.standard_error > 0);
        CHECK(std::fabs(s.z(kExpected[c])) <= 4.0);
    }
    CHECK(r.counters.nonfinite_samples == 0);
}

}  // namespace

TEST_CASE("furnace: diffuse sphere under a constant environment") {
    SUBCASE("light sampling: exact") {
        check_exact(render_json(kSphereScene, settings_for(DirectStrategy::light, 2, 4)));
    }
    SUBCASE("MIS: exact") {
        check_exact(render_json(kSphereScene, settings_for(DirectStrategy::mis, 2, 4)));
    }
    SUBCASE("hemisphere sampling: unbiased") {
        check_unbiased(render_json(kSphereScene, settings_for(DirectStrategy::hemisphere, 4, 4)));
    }
}

TEST_CASE("furnace: diffuse plane, lit the same from both sides") {
    for (double camera_y : {3.0, -3.0}) {
        CAPTURE(camera_y);
        std::string scene = plane_scene(camera_y);
        check_exact(render_json(scene, settings_for(DirectStrategy::light, 2, 4)));
        check_exact(render_json(scene, settings_for(DirectStrategy::mis, 2, 4)));
        check_unbiased(render_json(scene, settings_for(DirectStrategy::hemisphere, 4, 4)));
    }
}

TEST_CASE("-m 0 shows emission only; -o 0 -m 1 only the first bounce") {
    RenderSettings s = settings_for(DirectStrategy::light, 1, 1);
    s.max_depth = 0;
    // The sphere emits nothing: black; nothing else is in view.
    RenderResult r = render_json(kSphereScene, s);
    CHECK(channel_stats(r.image, 0).max == 0.0);
    // The environment is emission seen directly: a camera that misses everything sees it.
    std::string sky = plane_scene(3.0);
    sky.replace(sky.find("\"look_at\": [0, 0, 0]"), 20, "\"look_at\": [0, 6, 0]");
    RenderResult env = render_json(sky, s);
    CHECK(channel_stats(env.image, 1).min == doctest::Approx(2.0));
    s.max_depth = 1;
    s.accumulate_bounces = false;
    CHECK(channel_stats(render_json(sky, s).image, 1).max == 0.0);
    CHECK(channel_stats(render_json(kSphereScene, s).image, 0).min ==
          doctest::Approx(0.5).epsilon(1e-6));
}
