// Camera rays (stage `camera`, reference): centre, corner and thin-lens rays
// against hand-computed directions.
#include <doctest/doctest.h>

#include <cmath>
#include <optional>

#include "core/math.h"
#include "core/rng.h"
#include "scene/camera.h"
#include "scene/camera_importance.h"
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

namespace {

/// A camera at the origin looking down -z with +y up, of the given type.
Camera typed_camera(CameraType type, double aspect) {
    Camera c;
    c.type = type;
    c.position = Vec3(0, 0, 0);
    c.look_at = Vec3(0, 0, -1);
    c.aspect = aspect;
    c.height = 4;
    c.fov = 180;
    c.finalize();
    return c;
}

}  // namespace

TEST_CASE("orthographic: parallel rays from a height x (aspect height) rectangle") {
    Camera c = typed_camera(CameraType::orthographic, 1.5);  // height 4, width 6
    Ray centre = orthographic_ray(c, 0.5, 0.5, {});
    CHECK(centre.o == Vec3(0, 0, 0));
    check_direction(centre.d, Vec3(0, 0, -1));
    // Corners by hand: x = +-3, y = +-2, all looking down -z.
    struct Corner {
        double x, y;
        Vec3 origin;
    } corners[] = {{0, 0, Vec3(-3, -2, 0)}, {1, 0, Vec3(3, -2, 0)}, {0, 1, Vec3(-3, 2, 0)}, {1, 1, Vec3(3, 2, 0)},
                   {0.25, 0.75, Vec3(-1.5, 1, 0)}};
    for (const Corner& k : corners) {
        Ray r = orthographic_ray(c, k.x, k.y, {});
        CHECK((r.o - k.origin).norm() < 1e-12);
        check_direction(r.d, Vec3(0, 0, -1));
    }
    // A rotated camera: at (0, 5, 0) looking down at the origin, with -z as up.
    Camera top;
    top.type = CameraType::orthographic;
    top.position = Vec3(0, 5, 0);
    top.look_at = Vec3(0, 0, 0);
    top.up = Vec3(0, 0, -1);
    top.height = 2;
    top.aspect = 1;
    top.finalize();
    Ray r = orthographic_ray(top, 1, 1, {});  // top right: +x, and "up" = -z
    CHECK((r.o - Vec3(1, 5, -1)).norm() < 1e-12);
    check_direction(r.d, Vec3(0, -1, 0));
}

TEST_CASE("fisheye: equidistant angles, the image circle, 360 degrees") {
    Camera c = typed_camera(CameraType::fisheye, 2.0);  // fov 180; circle of radius 1 = half the height
    check_direction(fisheye_ray(c, 0.5, 0.5, {}).d, Vec3(0, 0, -1));
    // Top and bottom edge centres are on the circle: 90 degrees off the axis.
    check_direction(fisheye_ray(c, 0.5, 1, {}).d, Vec3(0, 1, 0));
    check_direction(fisheye_ray(c, 0.5, 0, {}).d, Vec3(0, -1, 0));
    // Horizontally the film is twice as wide: x = 0.75 is r = 1 (the circle),
    // x = 0.625 is r = 1/2, 45 degrees.
    check_direction(fisheye_ray(c, 0.75, 0.5, {}).d, Vec3(1, 0, 0));
    check_direction(fisheye_ray(c, 0.625, 0.5, {}).d, Vec3(1, 0, -1));
    // Diagonal at r = 1/2: 45 degrees, halfway between +x and +y.
    double h = 0.5 / std::sqrt(2.0);
    check_direction(fisheye_ray(c, 0.5 + h / 4, 0.5 + h / 2, {}).d, Vec3(0.5, 0.5, -std::sqrt(0.5)));
    // The film's corners lie outside the circle: those rays see nothing.
    CHECK(sees_nothing(fisheye_ray(c, 1, 1, {})));
    CHECK(sees_nothing(fisheye_ray(c, 0.8, 0.5, {})));
    CHECK_FALSE(sees_nothing(fisheye_ray(c, 0.74, 0.5, {})));
    // 360 degrees: the circle is the direction straight behind, r = 1/2 sideways.
    c.fov = 360;
    c.finalize();
    check_direction(fisheye_ray(c, 0.5, 1, {}).d, Vec3(0, 0, 1));
    check_direction(fisheye_ray(c, 0.5, 0.75, {}).d, Vec3(0, 1, 0));
    check_direction(fisheye_ray(c, 0.625, 0.5, {}).d, Vec3(1, 0, 0));
    // A tall film: the circle fits the width.
    Camera tall = typed_camera(CameraType::fisheye, 0.5);
    check_direction(fisheye_ray(tall, 1, 0.5, {}).d, Vec3(1, 0, 0));
    check_direction(fisheye_ray(tall, 0.5, 0.75, {}).d, Vec3(0, 1, 0));
}

TEST_CASE("camera_film_position inverts the camera rays of every type") {
    Rng rng(3);
    for (CameraType type : {CameraType::perspective, CameraType::orthographic, CameraType::fisheye}) {
        for (double aspect : {0.7, 1.6}) {
            Camera c;
            c.type = type;
            c.position = Vec3(1, 2, 3);
            c.look_at = Vec3(-2, 1, -1);
            c.up = Vec3(0.1, 1, 0);
            c.vfov = 50;
            c.height = 3;
            c.fov = type == CameraType::fisheye ? 300 : 180;
            c.aspect = aspect;
            c.finalize();
            CAPTURE(to_string(type));
            int checked = 0;
            for (int i = 0; i < 200; ++i) {
                double x = rng.next_1d(), y = rng.next_1d();
                Ray r = type == CameraType::perspective ? reference::generate_ray(c, x, y, {})
                        : type == CameraType::orthographic ? orthographic_ray(c, x, y, {})
                                                           : fisheye_ray(c, x, y, {});
                if (sees_nothing(r)) continue;  // outside the fisheye's circle
                std::optional<Vec2> p = camera_film_position(c, r.o, r.d);
                REQUIRE(p.has_value());
                CHECK(std::fabs(p->x - x) < 1e-9);
                CHECK(std::fabs(p->y - y) < 1e-9);
                ++checked;
            }
            CHECK(checked > 60);  // the circle covers pi / (4 aspect) of a wide film
            // Behind a perspective or orthographic camera: nowhere on the film.
            if (type != CameraType::fisheye) CHECK_FALSE(camera_film_position(c, c.position, c.backward).has_value());
            // A 300-degree fisheye sees 150 degrees off its axis, not 160.
            if (type == CameraType::fisheye) {
                auto off_axis = [&](double degrees) {
                    return c.to_world(Vec3(std::sin(radians(degrees)), 0, -std::cos(radians(degrees))));
                };
                CHECK(camera_film_position(c, c.position, off_axis(140)).has_value());
                CHECK_FALSE(camera_film_position(c, c.position, off_axis(160)).has_value());
                CHECK(camera_importance_missing(c) == "the fisheye camera has no importance function");
            }
        }
    }
}
