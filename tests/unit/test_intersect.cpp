// Ray-triangle and ray-sphere intersection (stage `intersect`, reference).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "stages/intersect.h"

using namespace pt;

namespace {

Triangle unit_triangle() {
    Triangle t;
    t.p0 = Vec3(0, 0, 0);
    t.p1 = Vec3(1, 0, 0);
    t.p2 = Vec3(0, 1, 0);
    return t;
}

double ulp(double x) { return std::nextafter(std::fabs(x), kInfinity) - std::fabs(x); }

}  // namespace

TEST_CASE("triangle: a hit reports t, barycentrics and the geometric normal") {
    Ray ray(Vec3(0.25, 0.5, 2), Vec3(0, 0, -1));
    std::optional<Hit> hit = reference::intersect_triangle(unit_triangle(), ray);
    REQUIRE(hit);
    CHECK(hit->t == 2);
    CHECK(hit->b1 == 0.25);
    CHECK(hit->b2 == 0.5);
    CHECK(hit->n == Vec3(0, 0, 1));  // (p1 - p0) x (p2 - p0), not flipped towards the ray
    // From below: same hit, same (unflipped) normal.
    std::optional<Hit> below = reference::intersect_triangle(unit_triangle(), Ray(Vec3(0.25, 0.5, -1), Vec3(0, 0, 1)));
    REQUIRE(below);
    CHECK(below->t == 1);
    CHECK(below->n == Vec3(0, 0, 1));
}

TEST_CASE("triangle: misses outside, behind the origin, outside [t_min, t_max] and parallel") {
    Triangle tri = unit_triangle();
    CHECK_FALSE(reference::intersect_triangle(tri, Ray(Vec3(0.6, 0.6, 1), Vec3(0, 0, -1))));   // outside b1+b2<=1
    CHECK_FALSE(reference::intersect_triangle(tri, Ray(Vec3(-0.1, 0.5, 1), Vec3(0, 0, -1))));  // b1 < 0
    CHECK_FALSE(reference::intersect_triangle(tri, Ray(Vec3(0.2, 0.2, 1), Vec3(0, 0, 1))));    // behind
    CHECK_FALSE(reference::intersect_triangle(tri, Ray(Vec3(0.2, 0.2, 1), Vec3(0, 0, -1), 1.5, 10)));  // t < t_min
    CHECK_FALSE(reference::intersect_triangle(tri, Ray(Vec3(0.2, 0.2, 1), Vec3(0, 0, -1), 0, 0.5)));   // t > t_max
    CHECK(reference::intersect_triangle(tri, Ray(Vec3(0.2, 0.2, 1), Vec3(0, 0, -1), 1, 1)));  // interval is closed
    CHECK_FALSE(reference::intersect_triangle(tri, Ray(Vec3(0.2, 0.2, 1), Vec3(1, 0, 0))));    // parallel, off plane
    CHECK_FALSE(reference::intersect_triangle(tri, Ray(Vec3(-1, 0.2, 0), Vec3(1, 0, 0))));     // in the plane
}

TEST_CASE("triangle: edges and vertices count as inside") {
    Triangle tri = unit_triangle();
    CHECK(reference::intersect_triangle(tri, Ray(Vec3(0.5, 0, 1), Vec3(0, 0, -1))));   // edge p0-p1
    CHECK(reference::intersect_triangle(tri, Ray(Vec3(0.5, 0.5, 1), Vec3(0, 0, -1))));  // edge p1-p2
    CHECK(reference::intersect_triangle(tri, Ray(Vec3(0, 0, 1), Vec3(0, 0, -1))));      // vertex p0
}

TEST_CASE("triangle: degenerate triangles never hit and never give NaN") {
    Triangle line;
    line.p0 = Vec3(0, 0, 0);
    line.p1 = Vec3(1, 1, 0);
    line.p2 = Vec3(2, 2, 0);
    Triangle point;  // all three corners equal
    const Ray rays[] = {Ray(Vec3(1, 1, 1), Vec3(0, 0, -1)), Ray(Vec3(0, 0, 1), Vec3(0, 0, -1)),
                        Ray(Vec3(-1, -1, 0), Vec3(1, 1, 0).unit())};
    for (const Ray& r : rays) {
        CHECK_FALSE(reference::intersect_triangle(line, r));
        CHECK_FALSE(reference::intersect_triangle(point, r));
    }
    // NaN input is rejected rather than propagated.
    double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK_FALSE(reference::intersect_triangle(unit_triangle(), Ray(Vec3(nan, 0.2, 1), Vec3(0, 0, -1))));
}

TEST_CASE("triangle: vertex normals are interpolated, and zero interpolations fall back") {
    Triangle tri = unit_triangle();
    tri.has_normals = true;
    tri.n0 = Vec3(0, 0, 1);
    tri.n1 = Vec3(1, 0, 0);
    tri.n2 = Vec3(0, 1, 0);
    std::optional<Hit> hit = reference::intersect_triangle(tri, Ray(Vec3(0.5, 0, 1), Vec3(0, 0, -1)));
    REQUIRE(hit);
    CHECK(hit->n.x == doctest::Approx(std::sqrt(0.5)));
    CHECK(hit->n.z == doctest::Approx(std::sqrt(0.5)));
    // Opposite normals at p0 and p1 cancel at the midpoint of their edge.
    tri.n1 = Vec3(0, 0, -1);
    hit = reference::intersect_triangle(tri, Ray(Vec3(0.5, 0, 1), Vec3(0, 0, -1)));
    REQUIRE(hit);
    CHECK(hit->n == Vec3(0, 0, 1));
}

TEST_CASE("sphere: outside, inside, tangent, behind and interval limits") {
    Sphere s{Vec3(0, 0, 0), 1};
    std::optional<Hit> hit = reference::intersect_sphere(s, Ray(Vec3(0, 0, 5), Vec3(0, 0, -1)));
    REQUIRE(hit);
    CHECK(hit->t == 4);
    CHECK(hit->n == Vec3(0, 0, 1));
    // From inside, the far side, with the outward normal.
    hit = reference::intersect_sphere(s, Ray(Vec3(0, 0, 0.5), Vec3(0, 0, -1)));
    REQUIRE(hit);
    CHECK(hit->t == 1.5);
    CHECK(hit->n == Vec3(0, 0, -1));
    // Tangent: touches at one point.
    hit = reference::intersect_sphere(s, Ray(Vec3(1, 0, 5), Vec3(0, 0, -1)));
    REQUIRE(hit);
    CHECK(hit->t == doctest::Approx(5));
    CHECK_FALSE(reference::intersect_sphere(s, Ray(Vec3(1.000001, 0, 5), Vec3(0, 0, -1))));
    // Behind the origin.
    CHECK_FALSE(reference::intersect_sphere(s, Ray(Vec3(0, 0, 5), Vec3(0, 0, 1))));
    // Near root outside the interval: the far root.
    hit = reference::intersect_sphere(s, Ray(Vec3(0, 0, 5), Vec3(0, 0, -1), 4.5, 100));
    REQUIRE(hit);
    CHECK(hit->t == 6);
    CHECK_FALSE(reference::intersect_sphere(s, Ray(Vec3(0, 0, 5), Vec3(0, 0, -1), 0, 3.9)));
    // A direction that is not unit length scales t.
    hit = reference::intersect_sphere(s, Ray(Vec3(0, 0, 5), Vec3(0, 0, -2)));
    REQUIRE(hit);
    CHECK(hit->t == 2);
}

TEST_CASE("sphere: a unit sphere 10^6 units away is hit on its surface within a few ulp") {
    const double far = 1e6;
    Sphere s{Vec3(far, 0, 0), 1};
    // Straight on: t = 10^6 - 1 exactly representable.
    std::optional<Hit> hit = reference::intersect_sphere(s, Ray(Vec3(0, 0, 0), Vec3(1, 0, 0)));
    REQUIRE(hit);
    CHECK(std::fabs(hit->t - (far - 1)) <= 2 * ulp(far));
    // Off axis, aimed at the surface point c + (-0.6, 0.8, 0). The textbook
    // b^2 - 4ac loses about 10^-4 here; the stable form keeps a few ulp.
    Vec3 target(far - 0.6, 0.8, 0);
    Ray ray(Vec3(0, 0, 0), target.unit());
    hit = reference::intersect_sphere(s, ray);
    REQUIRE(hit);
    Vec3 p = ray.at(hit->t);
    CHECK(std::fabs((p - s.center).norm() - 1) <= 8 * ulp(far));
    CHECK((p - target).norm() <= 8 * ulp(far));
    CHECK(hit->n.x == doctest::Approx(-0.6).epsilon(1e-6));
    CHECK(hit->n.y == doctest::Approx(0.8).epsilon(1e-6));
}
