// A spherical light above a Lambertian point. A uniform sphere of radiance
// L that subtends a cone of half-angle alpha (sin alpha = r / d) and lies
// wholly above the horizon gives irradiance
//     E = pi L sin^2(alpha) cos(theta)
// (theta: the angle from the normal to the sphere's centre; Nusselt's
// analogue: the projected area of the cap on the unit disk is pi sin^2(alpha)
// cos(theta)), so Lo = albedo / pi * E. Light sampling (cone), hemisphere
// sampling and MIS must agree with it and with each other: a wrong r^2 or
// cos factor in the cone pdf shows as a ratio between them.
#include <doctest/doctest.h>

#include "analytic/tiny_render.h"
#include "core/math.h"

using namespace pt;
using namespace pt::analytic;

namespace {

const Vec3 kCenter(0.4, 1.5, 0.3), kReceiver(0, 0, 0);
const double kRadius = 0.6, kLe = 4.0, kAlbedo = 0.7;

const char* kScene = R"({
    "camera": {"position": [3, 0.4, 2], "look_at": [0, 0, 0], "vfov": 0.0002},
    "film": {"width": 32, "height": 32},
    "materials": {"floor": {"type": "diffuse", "albedo": [0.7, 0.7, 0.7]},
                  "lamp": {"type": "diffuse", "albedo": [0, 0, 0], "emission": [4, 4, 4]}},
    "objects": [
        {"type": "quad", "corner": [-10, 0, -10], "edge1": [0, 0, 20], "edge2": [20, 0, 0], "material": "floor"},
        {"type": "sphere", "center": [0.4, 1.5, 0.3], "radius": 0.6, "material": "lamp"}]
})";

}  // namespace

TEST_CASE("sphere light: light, hemisphere and MIS sampling agree with the closed form") {
    Vec3 d = kCenter - kReceiver;
    double sin2_alpha = kRadius * kRadius / d.norm2();
    double cos_theta = d.y / d.norm();
    REQUIRE(std::asin(std::sqrt(sin2_alpha)) <
            std::asin(d.y / d.norm()));  // wholly above the horizon
    double expected = kAlbedo / kPi * kPi * kLe * sin2_alpha * cos_theta;
    CAPTURE(expected);

    PixelStats light =
        channel_stats(render_json(kScene, settings_for(DirectStrategy::light, 4, 4, 3)).image, 0);
    PixelStats hemi = channel_stats(
        render_json(kScene, settings_for(DirectStrategy::hemisphere, 16, 4, 3)).image, 0);
    PixelStats mis =
        channel_stats(render_json(kScene, settings_for(DirectStrategy::mis, 4, 4, 3)).image, 0);
    for (const PixelStats& s : {light, hemi, mis}) {
        CAPTURE(s.mean);
        CAPTURE(s.standard_error);
        CHECK(s.standard_error > 0);
        CHECK(s.standard_error < 0.02 * expected);
        CHECK(std::fabs(s.z(expected)) <= 4.0);
    }
    // Hemisphere and light sampling against each other.
    double z = (hemi.mean - light.mean) / std::sqrt(hemi.standard_error * hemi.standard_error +
                                                    light.standard_error * light.standard_error);
    CHECK(std::fabs(z) <= 4.0);
    // Cone sampling of a sphere wholly in view is nearly noise-free; MIS adds
    // BSDF samples and must not be noisier than hemisphere sampling.
    CHECK(light.standard_error < hemi.standard_error);
    CHECK(mis.standard_error < hemi.standard_error);
}
