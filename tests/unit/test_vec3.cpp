#include <doctest/doctest.h>

#include "core/frame.h"
#include "core/vec3.h"

using namespace pt;

TEST_CASE("vec3 dot, cross and normalize") {
    Vec3 a(1, 2, 3), b(4, 5, 6);
    CHECK(dot(a, b) == 32);
    CHECK(cross(a, b) == Vec3(-3, 6, -3));
    CHECK(cross(Vec3(1, 0, 0), Vec3(0, 1, 0)) == Vec3(0, 0, 1));
    CHECK(Vec3(3, 4, 0).norm() == 5);
    CHECK(Vec3(0, 0, 2).unit() == Vec3(0, 0, 1));
}
