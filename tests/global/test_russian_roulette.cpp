// Russian roulette is unbiased and ends every path:
//   - on and off agree: a small Cornell-like box at -m 6, rendered with and
//     without roulette at the same seed; the mean of the per-pixel
//     differences is 0 within 4 standard errors (pixels are independent).
//   - a closed box of albedo 1 whose walls emit Le: with -m 30 the exact
//     radiance is 31 Le (every bounce returns all of it), and roulette
//     (survival capped at 0.95) must still give it on average.
//   - the same box without a depth cap (-m 100000) ends in bounded time:
//     after rr_depth bounces each continuation survives with q = 0.95, so a
//     camera sample traces 1 + rr_depth + 0.95 / 0.05 = 23 closest-hit rays
//     on average (a geometric tail, standard deviation 19.5 per sample).
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "global/global_render.h"
#include "global/same_mean.h"

using namespace pt;
using namespace pt::global_test;

namespace {

const char* kBox = R"({
    "camera": {"position": [0, 0, 2.5], "look_at": [0, 0, 0], "vfov": 45},
    "film": {"width": 16, "height": 16},
    "materials": {
      "white": {"type": "diffuse", "albedo": [0.8, 0.8, 0.8]},
      "red": {"type": "diffuse", "albedo": [0.8, 0.1, 0.1]},
      "green": {"type": "diffuse", "albedo": [0.1, 0.8, 0.1]},
      "chrome": {"type": "mirror", "reflectance": [0.9, 0.9, 0.9]},
      "lamp": {"type": "diffuse", "albedo": [0, 0, 0], "emission": [8, 8, 8]}
    },
    "objects": [
      {"type": "quad", "corner": [-1, -1, -1], "edge1": [0, 0, 2], "edge2": [2, 0, 0], "material": "white"},
      {"type": "quad", "corner": [-1, 1, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2], "material": "white"},
      {"type": "quad", "corner": [-1, -1, -1], "edge1": [0, 2, 0], "edge2": [0, 0, 2], "material": "red"},
      {"type": "quad", "corner": [1, -1, -1], "edge1": [0, 0, 2], "edge2": [0, 2, 0], "material": "green"},
      {"type": "quad", "corner": [-1, -1, -1], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "white"},
      {"type": "quad", "corner": [-0.3, 0.99, -0.3], "edge1": [0.6, 0, 0], "edge2": [0, 0, 0.6], "material": "lamp"},
      {"type": "sphere", "center": [0.4, -0.6, 0], "radius": 0.35, "material": "chrome"}
    ]
})";

}  // namespace

TEST_CASE("Russian roulette on and off agree (mean pixel difference within 4 SE)") {
    Scene scene = scene_from(kBox);
    for (DirectStrategy strategy : {DirectStrategy::light, DirectStrategy::mis}) {
        CAPTURE(std::string(to_string(strategy)));
        RenderSettings off = path_settings(6, 48, 7);
        off.direct = strategy;
        off.russian_roulette = false;
        RenderSettings on = off;
        on.russian_roulette = true;
        on.rr_depth = 1;
        RenderResult a = render(scene, off), b = render(scene, on);
        CHECK(a.counters.nonfinite_samples == 0);
        CHECK(b.counters.nonfinite_samples == 0);
        // Roulette did end paths early: fewer rays.
        CHECK(b.counters.closest_hit_rays < a.counters.closest_hit_rays);
        check_same_mean(a.image, b.image, 0.03);  // the test has power: a 3% bias would fail
    }
}

TEST_CASE("a closed box of albedo 1: roulette keeps the mean (31 Le at -m 30) and ends paths") {
    const double rho[3] = {1, 1, 1}, Le[3] = {0.25, 0.5, 1};
    Scene scene = scene_from(closed_box(glowing_wall(rho, Le), 16));

    SUBCASE("-m 30: the exact radiance (m + 1) Le") {
        RenderSettings settings = path_settings(30, 4, 11);
        settings.direct = DirectStrategy::mis;
        RenderResult r = render(scene, settings);
        for (int c = 0; c < 3; ++c) {
            PixelStats s = channel_stats(r.image, c);
            CAPTURE(s.mean);
            CAPTURE(s.standard_error);
            CHECK(std::fabs(s.z(31 * Le[c])) <= 4.0);
        }
    }

    SUBCASE("no depth cap: 23 closest-hit rays per camera sample on average") {
        RenderSettings settings = path_settings(100000, 4, 13);
        settings.direct = DirectStrategy::light;
        settings.rr_depth = 3;
        RenderResult r = render(scene, settings);
        CHECK(r.counters.nonfinite_samples == 0);
        const double samples = double(r.counters.camera_rays);
        const double per_sample = double(r.counters.closest_hit_rays) / samples;
        const double expected = 1 + 3 + kMaxSurvivalProbability / (1 - kMaxSurvivalProbability);
        const double sd = std::sqrt(kMaxSurvivalProbability) / (1 - kMaxSurvivalProbability);
        CAPTURE(per_sample);
        CHECK(std::fabs(per_sample - expected) <= 4 * sd / std::sqrt(samples));
        // Every sample saw at least the first four terms (4 Le) in expectation.
        CHECK(channel_stats(r.image, 0).mean > 4 * Le[0]);
    }
}
