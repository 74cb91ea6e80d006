// Camera rays (stage `camera`, reference): centre, corner and thin-lens rays
// against hand-computed directions.
#include <doctest/doctest.h>

#include <cmath>

#include "core/math.h"
#include "scene/camera.h"
#include "stages/camera.h"

using namespace pt;

namespace {

Camera camera_at_origin(double vfov, double aspect) {
    Camera c;
    c.position = Vec3(0, 0, 0);
    c.look_at = Vec3(0, 0, -1);
    c.up = Vec3(0, 1, 0);
    c.vfov = vfov;
    c.aspect = aspect;
    c.finalize();
    return c;
}

void check_direction(const Vec3& got, const Vec3& expected) {
    Vec3 e = expected.unit();
    CHECK(got.x == doctest::Approx(e.x).epsilon(1e-12));
    CHECK(got.y == doctest::Approx(e.y).epsilon(1e-12));
    CHECK(got.z == doctest::Approx(e.z).epsilon(1e-12));
}

}  // namespace

TEST_CASE("centre and corner rays of a 90-degree camera with aspect 2") {
    // tan(45 deg) = 1 vertically and 2 horizontally: the corners of the
    // sensor at z = -1 are (+-2, +-1, -1).
    Camera c = camera_at_origin(90, 2);
    Ray centre = reference::generate_ray(c, 0.5, 0.5, {0.5, 0.5});
    CHECK(centre.o == Vec3(0, 0, 0));
    check_direction(centre.d, Vec3(0, 0, -1));
    check_direction(reference::generate_ray(c, 1, 1, {}).d, Vec3(2, 1, -1));
    check_direction(reference::generate_ray(c, 0, 0, {}).d, Vec3(-2, -1, -1));
    check_direction(reference::generate_ray(c, 1, 0, {}).d, Vec3(2, -1, -1));
    check_direction(reference::generate_ray(c, 0.25, 0.75, {}).d, Vec3(-1, 0.5, -1));
    CHECK(centre.d.norm() == doctest::Approx(1).epsilon(1e-15));
    CHECK(centre.t_min == c.near_clip);
    CHECK(centre.t_max == c.far_clip);
}

TEST_CASE("the Cornell box camera looks along +z with +x to the left") {
    Camera c;
    c.position = Vec3(278, 273, -800);
    c.look_at = Vec3(278, 273, 0);
    c.vfov = 39.3;
    c.aspect = 1;
    c.finalize();
    check_direction(reference::generate_ray(c, 0.5, 0.5, {}).d, Vec3(0, 0, 1));
    double t = std::tan(radians(39.3 / 2));
    // The right edge of the image looks towards -x (the green wall at x = 0).
    check_direction(reference::generate_ray(c, 1, 0.5, {}).d, Vec3(-t, 0, 1));
    check_direction(reference::generate_ray(c, 0.5, 1, {}).d, Vec3(0, t, 1));
}

TEST_CASE("thin-lens rays start on the lens and meet at the plane of focus") {
    Camera c = camera_at_origin(60, 1.5);
    c.lens_radius = 0.25;
    c.focal_distance = 4;
    for (double x : {0.1, 0.5, 0.93}) {
        Ray pinhole = reference::generate_ray(Camera(camera_at_origin(60, 1.5)), x, 0.3, {});
        Vec3 focus = pinhole.o + pinhole.d * (4 / -pinhole.d.z);  // where it meets z = -4
        for (Vec2 u : {Vec2(0.1, 0.2), Vec2(0.9, 0.5), Vec2(0.5, 0.99)}) {
            Ray r = reference::generate_ray(c, x, 0.3, u);
            CHECK(r.o.z == 0);
            CHECK(std::hypot(r.o.x, r.o.y) <= 0.25 + 1e-15);
            Vec3 p = r.o + r.d * ((4 + r.o.z) / -r.d.z);
            CHECK((p - focus).norm() < 1e-12);
        }
    }
}
