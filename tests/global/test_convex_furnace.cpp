// The convex white furnace: a sphere that absorbs nothing (diffuse albedo 1,
// glass without tint, a perfect mirror) inside a constant environment of
// radiance 1 renders 1 everywhere: every path that leaves the camera ends
// in the sky, and no bounce loses energy. (Glass scales radiance by
// 1 / eta^2 going in and by eta^2 coming out: the factors cancel.)
//
// A convex sphere lets a diffuse or mirror path meet it once, so -m 1 is
// already exact; glass paths bounce inside and need a higher cap (-m 1000:
// the chance of 999 internal reflections, at most 0.1 each for incidences
// up to 67 degrees, is nil). Without roulette every sample is 1 up to
// rounding (pixel by pixel, 1e-6 relative: the film stores floats); with
// roulette from the first bounce (weights 0 or 1 / q) the mean is 1 within
// 4 standard errors.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "global/global_render.h"

using namespace pt;
using namespace pt::global_test;

namespace {

// The sphere fills the image: it subtends 11.5 degrees, the corners are 10.6 off axis.
std::string furnace(const std::string& material) {
    return R"({
    "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "vfov": 15},
    "film": {"width": 16, "height": 16},
    "materials": {"white": )" +
           material + R"(},
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"}],
    "lights": [{"type": "environment", "radiance": [1, 1, 1]}]
})";
}

const char* kMaterials[] = {
    R"({"type": "diffuse", "albedo": [1, 1, 1]})",
    R"({"type": "glass", "ior": 1.5})",
    R"({"type": "mirror", "reflectance": [1, 1, 1]})",
};

}  // namespace

TEST_CASE("convex white furnace: diffuse, glass and mirror spheres of albedo 1 render 1") {
    for (const char* material : kMaterials) {
        Scene scene = scene_from(furnace(material));
        for (DirectStrategy strategy :
             {DirectStrategy::light, DirectStrategy::mis, DirectStrategy::hemisphere}) {
            CAPTURE(material);
            CAPTURE(std::string(to_string(strategy)));
            RenderSettings settings = path_settings(1000, 4, 3);
            settings.direct = strategy;
            settings.russian_roulette = false;
            RenderResult r = render(scene, settings);
            CHECK(r.counters.nonfinite_samples == 0);
            for (int c = 0; c < 3; ++c) {
                PixelStats s = channel_stats(r.image, c);
                CHECK(s.min == doctest::Approx(1.0).epsilon(1e-6));
                CHECK(s.max == doctest::Approx(1.0).epsilon(1e-6));
            }
        }
    }
}

TEST_CASE("convex white furnace with Russian roulette from the first bounce: mean 1") {
    for (const char* material : kMaterials) {
        Scene scene = scene_from(furnace(material));
        CAPTURE(material);
        RenderSettings settings = path_settings(1000, 8, 5);
        settings.direct = DirectStrategy::hemisphere;  // the sky through the path's own rays
        settings.rr_depth = 0;
        RenderResult r = render(scene, settings);
        CHECK(r.counters.nonfinite_samples == 0);
        for (int c = 0; c < 3; ++c) {
            PixelStats s = channel_stats(r.image, c);
            CAPTURE(s.mean);
            CAPTURE(s.standard_error);
            CHECK(s.standard_error > 0);  // roulette did act: weights 0 or 1 / 0.95
            CHECK(std::fabs(s.z(1.0)) <= 4.0);
        }
    }
}
