// Vector math, frames and transforms.
#include <doctest/doctest.h>

#include <cmath>

#include "core/frame.h"
#include "core/transform.h"
#include "core/vec3.h"

using namespace pt;

TEST_CASE("vec3 dot, cross and normalize") {
    Vec3 a(1, 2, 3), b(4, 5, 6);
    CHECK(dot(a, b) == 32);
    CHECK(cross(a, b) == Vec3(-3, 6, -3));
    CHECK(cross(Vec3(1, 0, 0), Vec3(0, 1, 0)) == Vec3(0, 0, 1));
    CHECK(Vec3(3, 4, 0).norm() == 5);
    CHECK(Vec3(0, 0, 2).unit() == Vec3(0, 0, 1));
    CHECK(max_dimension(Vec3(1, -5, 2)) == 2);
    CHECK(reflect(Vec3(1, 1, 0).unit(), Vec3(0, 1, 0)).x == doctest::Approx(-std::sqrt(0.5)));
}

TEST_CASE("frame is orthonormal and right-handed for every normal, including near (0,0,-1)") {
    const Vec3 normals[] = {{0, 0, 1},  {0, 0, -1}, {1, 0, 0}, {0, 1, 0}, Vec3(1, 2, 3).unit(),
                            Vec3(1e-9, 0, -1).unit(), Vec3(0, 1e-12, -1).unit(), Vec3(-1e-7, 1e-7, -1).unit()};
    for (const Vec3& n : normals) {
        Frame f(n);
        CAPTURE(n.x);
        CAPTURE(n.y);
        CAPTURE(n.z);
        CHECK(f.s.norm() == doctest::Approx(1).epsilon(1e-12));
        CHECK(f.t.norm() == doctest::Approx(1).epsilon(1e-12));
        CHECK(std::fabs(dot(f.s, f.t)) < 1e-12);
        CHECK(std::fabs(dot(f.s, f.n)) < 1e-12);
        CHECK(std::fabs(dot(f.t, f.n)) < 1e-12);
        CHECK(dot(cross(f.s, f.t), f.n) == doctest::Approx(1).epsilon(1e-12));
        Vec3 w = Vec3(0.3, -0.4, 0.5);
        Vec3 back = f.to_world(f.to_local(w));
        CHECK((back - w).norm() < 1e-12);
        CHECK(f.to_local(n).z == doctest::Approx(1));
    }
}

TEST_CASE("transform applies scale, then rotation, then translation") {
    Transform t;
    t.scale = Vec3(2);
    t.set_rotation(Vec3(0, 1, 0), 90);  // +x goes to -z
    t.translate = Vec3(10, 0, 0);
    Vec3 p = t.point(Vec3(1, 0, 0));
    CHECK(p.x == doctest::Approx(10));
    CHECK(p.y == doctest::Approx(0));
    CHECK(p.z == doctest::Approx(-2));
    // Normals use the inverse transpose: a non-uniform scale tilts them the other way.
    Transform s;
    s.scale = Vec3(2, 1, 1);
    Vec3 n = s.normal(Vec3(1, 1, 0).unit());
    CHECK(n.x == doctest::Approx(1 / std::sqrt(5.0)));
    CHECK(n.y == doctest::Approx(2 / std::sqrt(5.0)));
}
