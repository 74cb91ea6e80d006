// Delta lights have no noise: one shadow ray each, whatever -l says.
//   point light:       Lo = albedo / pi * I cos(theta) / r^2  (inverse square)
//   directional light: Lo = albedo / pi * E cos(theta)
// Checked to 1e-6 relative (the film stores floats); a blocked light adds 0.
#include <doctest/doctest.h>

#include "analytic/tiny_render.h"
#include "core/math.h"

using namespace pt;
using namespace pt::analytic;

namespace {

std::string scene(const std::string& lights, const std::string& extra_objects = "") {
    return R"({
    "camera": {"position": [2, 1, 3], "look_at": [0.2, 0, -0.1], "vfov": 0.0002},
    "film": {"width": 8, "height": 8},
    "materials": {"floor": {"type": "diffuse", "albedo": [0.6, 0.3, 0.9]}},
    "objects": [)" +
           extra_objects +
           R"({"type": "quad", "corner": [-10, 0, -10], "edge1": [0, 0, 20], "edge2": [20, 0, 0], "material": "floor"}],
    "lights": [)" +
           lights + R"(]
})";
}

const Vec3 kReceiver(0.2, 0, -0.1);
const double kAlbedo[3] = {0.6, 0.3, 0.9};

void check_all_pixels(const RenderResult& r, const double expected[3]) {
    CHECK(r.counters.nonfinite_samples == 0);
    for (int c = 0; c < 3; ++c) {
        PixelStats s = channel_stats(r.image, c);
        CAPTURE(c);
        CHECK(s.min == doctest::Approx(expected[c]).epsilon(1e-5));
        CHECK(s.max == doctest::Approx(expected[c]).epsilon(1e-5));
    }
}

}  // namespace

TEST_CASE("point light: inverse-square law") {
    Vec3 light(0.9, 1.7, 0.4);
    Vec3 d = light - kReceiver;
    double cos_theta = d.y / d.norm();
    double intensity = 5.0;
    double expected[3];
    for (int c = 0; c < 3; ++c)
        expected[c] = kAlbedo[c] / kPi * intensity * cos_theta / d.norm2();
    std::string json =
        scene(R"({"type": "point", "position": [0.9, 1.7, 0.4], "intensity": [5, 5, 5]})");
    // -l does not change a delta light: one sample, the exact value. (A
    // lone plane cannot shadow anything, so the effects analysis skips its
    // shadow rays; forced on, there is exactly one per pixel.)
    for (int l : {1, 16}) {
        RenderSettings settings = settings_for(DirectStrategy::light, 1, l);
        RenderResult r = render_json(json, settings);
        check_all_pixels(r, expected);
        CHECK(r.counters.shadow_rays == 0);
        settings.force.shadow_rays = true;
        r = render_json(json, settings);
        check_all_pixels(r, expected);
        CHECK(r.counters.shadow_rays == r.counters.camera_rays);
    }
    check_all_pixels(render_json(json, settings_for(DirectStrategy::mis, 1, 4)), expected);
    // Twice the distance, a quarter of the light.
    Vec3 far = kReceiver + 2.0 * d;
    double expected_far[3];
    for (int c = 0; c < 3; ++c)
        expected_far[c] = expected[c] / 4;
    std::string far_json = scene(R"({"type": "point", "position": [)" + std::to_string(far.x) +
                                 ", " + std::to_string(far.y) + ", " + std::to_string(far.z) +
                                 R"(], "intensity": [5, 5, 5]})");
    check_all_pixels(render_json(far_json, settings_for(DirectStrategy::light, 1, 1)),
                     expected_far);
}

TEST_CASE("directional light: E cos(theta)") {
    Vec3 direction = Vec3(-1, -2, 0.5).unit();  // travel direction, from the light to the scene
    double cos_theta = -direction.y;
    double expected[3];
    for (int c = 0; c < 3; ++c)
        expected[c] = kAlbedo[c] / kPi * 2.0 * cos_theta;
    check_all_pixels(
        render_json(
            scene(
                R"({"type": "directional", "direction": [-1, -2, 0.5], "irradiance": [2, 2, 2]})"),
            settings_for(DirectStrategy::light, 1, 1)),
        expected);
}

TEST_CASE("hard shadow: a blocked point light adds nothing") {
    const double zero[3] = {0, 0, 0};
    // A small occluding square between the receiver and the light.
    check_all_pixels(
        render_json(
            scene(
                R"({"type": "point", "position": [0.2, 2, -0.1], "intensity": [5, 5, 5]})",
                R"({"type": "quad", "corner": [0.1, 1, -0.2], "edge1": [0.2, 0, 0], "edge2": [0, 0, 0.2],
                              "material": "floor"}, )"),
            settings_for(DirectStrategy::light, 1, 1)),
        zero);
}
