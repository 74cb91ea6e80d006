// Mirror and glass in rendered scenes, against geometry worked out by hand:
//   - a mirror reflects the analytic direction: a camera looks at a mirror
//     floor through a narrow field of view; the lamp placed on the reflected
//     ray, d - 2 (d . n) n, shows with radiance reflectance x Le in every
//     pixel, and a lamp moved off that ray is not seen at all.
//   - a glass sphere shows total internal reflection from inside: from a
//     camera inside it, a ray meets the surface at sin(theta) = |c x d| / r
//     (c the camera's offset from the centre); beyond the critical angle,
//     sin(theta) > 1 / ior, it is reflected, and on a sphere it meets every
//     later point at the same angle, so it never leaves: those pixels are
//     exactly black under a sky of radiance 1; the others are not.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "core/math.h"
#include "global/global_render.h"
#include "stages/camera.h"

using namespace pt;
using namespace pt::global_test;

namespace {

std::string mirror_scene(const Vec3& lamp_center) {
    // Lamp: a 0.2 x 0.2 square centred on lamp_center, facing the origin
    // along -(0, 1, -1) / sqrt 2 (edge1 x edge2 points back down the ray).
    Vec3 e1(0.2, 0, 0), e2 = Vec3(0, 0.2, 0.2) / std::sqrt(2.0);
    Vec3 corner = lamp_center - 0.5 * e1 - 0.5 * e2;
    auto v = [](const Vec3& p) {
        return "[" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) +
               "]";
    };
    return R"({
    "camera": {"position": [0, 1, 1], "look_at": [0, 0, 0], "vfov": 0.5},
    "film": {"width": 8, "height": 8},
    "materials": {"chrome": {"type": "mirror", "reflectance": [0.9, 0.6, 0.3]},
                  "lamp": {"type": "diffuse", "albedo": [0, 0, 0], "emission": [2, 4, 8]}},
    "objects": [
      {"type": "quad", "corner": [-5, 0, -5], "edge1": [0, 0, 10], "edge2": [10, 0, 0], "material": "chrome"},
      {"type": "quad", "corner": )" +
           v(corner) + R"(, "edge1": )" + v(e1) + R"(, "edge2": )" + v(e2) +
           R"(, "material": "lamp"}
    ]
})";
}

}  // namespace

TEST_CASE("a mirror reflects the analytic direction d - 2 (d . n) n") {
    // The camera ray d = (0, -1, -1) / sqrt 2 meets the floor (n = +y) at the
    // origin and leaves along (0, 1, -1) / sqrt 2: the lamp sits 2 along it.
    Vec3 d = Vec3(0, -1, -1).unit(), n(0, 1, 0);
    Vec3 reflected = d - 2 * dot(d, n) * n;
    CHECK(reflected.y == doctest::Approx(1 / std::sqrt(2.0)));
    for (IntegratorKind kind :
         {IntegratorKind::path, IntegratorKind::whitted, IntegratorKind::automatic}) {
        CAPTURE(std::string(to_string(kind)));
        RenderSettings settings = path_settings(1, 1);
        RenderResult on = render(scene_from(mirror_scene(2 * reflected)), settings, kind);
        const double expected[3] = {0.9 * 2, 0.6 * 4, 0.3 * 8};
        for (int c = 0; c < 3; ++c) {
            PixelStats s = channel_stats(on.image, c);
            CHECK(s.min == doctest::Approx(expected[c]).epsilon(1e-6));
            CHECK(s.max == doctest::Approx(expected[c]).epsilon(1e-6));
        }
        // Off the reflected ray (along the unreflected continuation of d), it is not seen.
        RenderResult off = render(scene_from(mirror_scene(Vec3(0, 0.3, -2))), settings, kind);
        CHECK(channel_stats(off.image, 2).max == 0.0);
    }
}

TEST_CASE("a glass sphere shows total internal reflection from inside") {
    const double ior = 1.5;
    std::string json = R"({
    "camera": {"position": [0, 0, 0.8], "look_at": [1, 0, 0.8], "up": [0, 0, 1], "vfov": 110},
    "film": {"width": 32, "height": 32},
    "materials": {"glass": {"type": "glass", "ior": 1.5}},
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "glass"}],
    "lights": [{"type": "environment", "radiance": [1, 1, 1]}]
})";
    Scene scene = scene_from(json);
    for (IntegratorKind kind : {IntegratorKind::whitted, IntegratorKind::path}) {
        CAPTURE(std::string(to_string(kind)));
        RenderSettings settings = path_settings(kind == IntegratorKind::path ? 200 : 1, 1);
        settings.russian_roulette = false;
        RenderResult r = render(scene, settings, kind);
        int trapped = 0, escaping = 0;
        for (int y = 0; y < 32; ++y) {
            for (int x = 0; x < 32; ++x) {
                // The pixel-centre ray, as raytrace_pixel makes it at -s 1.
                Ray ray = reference::generate_ray(scene.camera, (x + 0.5) / 32, 1 - (y + 0.5) / 32,
                                                  Vec2(0.5, 0.5));
                double sin_theta = cross(ray.o - Vec3(0, 0, 0), ray.d.unit()).norm();
                double value = r.image.at(x, y).g;
                if (sin_theta > 1 / ior + 0.01) {
                    ++trapped;
                    CHECK(value == 0.0);
                } else if (sin_theta < 1 / ior - 0.01) {
                    ++escaping;
                    CHECK(value > 0.05);
                }
            }
        }
        CHECK(trapped > 100);
        CHECK(escaping > 100);
    }
}
