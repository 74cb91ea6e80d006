// Spheres far and near (Ray Tracing Gems chapter 7): unit spheres 10^3 to
// 10^6 units away classify every ray correctly and put hit points on the
// surface within a few ulp; rays starting inside, on and just outside the
// surface behave.
#include <doctest/doctest.h>

#include <cmath>

#include "core/frame.h"
#include "core/math.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "stages/intersect.h"

using namespace pt;

namespace {

double ulp(double x) { return std::nextafter(std::fabs(x), kInfinity) - std::fabs(x); }

/// The textbook solution with b^2 - 4ac, to show what the stable form avoids.
std::optional<double> textbook_sphere_t(const Sphere& s, const Ray& r) {
    Vec3 f = r.o - s.center;
    double a = dot(r.d, r.d), b = 2 * dot(f, r.d), c = dot(f, f) - s.radius * s.radius;
    double disc = b * b - 4 * a * c;
    if (disc < 0) return std::nullopt;
    double t = (-b - std::sqrt(disc)) / (2 * a);
    return t >= 0 ? std::optional<double>(t) : std::nullopt;
}

}  // namespace

TEST_CASE("unit spheres 10^3 to 10^6 away: no misclassified ray, hit points within a few ulp") {
    for (double distance : {1e3, 1e4, 1e5, 1e6}) {
        Sphere s{Vec3(distance, 0, 0), 1};
        Rng rng{uint64_t(distance)};
        int misclassified = 0, textbook_misclassified = 0, off_surface = 0;
        double worst_ulps = 0, textbook_worst_ulps = 0;
        const int rays = 20000;
        for (int i = 0; i < rays; ++i) {
            // Aim at a point of the plane through the centre, at radius r from
            // the centre: the ray's distance from the centre is r D / sqrt(D^2 + r^2).
            bool should_hit = i % 2 == 0;
            double r = should_hit ? (1 - 1e-7) * std::sqrt(rng.next_1d()) : 1 + 1e-7 + 0.5 * rng.next_1d();
            double phi = kTwoPi * rng.next_1d();
            Vec3 aim(distance, r * std::cos(phi), r * std::sin(phi));
            Ray ray(Vec3(0, 0, 0), aim.unit());
            std::optional<Hit> hit = reference::intersect_sphere(s, ray);
            misclassified += bool(hit) != should_hit;
            std::optional<double> textbook_t = textbook_sphere_t(s, ray);
            textbook_misclassified += bool(textbook_t) != should_hit;
            if (textbook_t && should_hit)
                textbook_worst_ulps = std::max(
                    textbook_worst_ulps, std::fabs((ray.at(*textbook_t) - s.center).norm() - 1) / ulp(distance));
            if (hit) {
                double error_ulps = std::fabs((ray.at(hit->t) - s.center).norm() - 1) / ulp(distance);
                worst_ulps = std::max(worst_ulps, error_ulps);
                off_surface += error_ulps > 4;
            }
        }
        MESSAGE("distance " << distance << ": misclassified " << misclassified << " of " << rays
                            << " (textbook formula: " << textbook_misclassified << "), worst hit point "
                            << worst_ulps << " ulp off the surface (textbook: " << textbook_worst_ulps << ")");
        CHECK(misclassified == 0);
        CHECK(off_surface == 0);
    }
}

TEST_CASE("rays starting inside, on and just outside a sphere") {
    for (double distance : {0.0, 1e3, 1e6}) {
        Sphere s{Vec3(distance, -distance, 0.5 * distance), 1};
        Rng rng(7);
        for (int i = 0; i < 5000; ++i) {
            Vec3 n = sample_uniform_sphere(rng.next_2d());
            Vec3 w = sample_uniform_sphere(rng.next_2d());
            double cos_wn = dot(w, n);
            if (std::fabs(cos_wn) < 0.1) continue;  // grazing directions are ambiguous by nature
            CAPTURE(distance);
            // Inside: always the far side, on the surface.
            Ray inside(s.center + n * (1 - 1e-6), w);
            std::optional<Hit> hit = reference::intersect_sphere(s, inside);
            REQUIRE(hit);
            CHECK(hit->t > 0);
            CHECK(std::fabs((inside.at(hit->t) - s.center).norm() - 1) < 8 * ulp(distance + 1));
            // Just outside: leaving misses, entering hits within a short distance.
            Ray outside(s.center + n * (1 + 1e-6), w);
            hit = reference::intersect_sphere(s, outside);
            if (cos_wn > 0) {
                CHECK_FALSE(hit);
            } else {
                REQUIRE(hit);
                CHECK(hit->t < 1e-5 / -cos_wn);
            }
            // On the surface (as close as rounding allows), leaving outward:
            // only a hit at t ~ 0 is possible, never one far away.
            Ray on(s.center + n, w);
            hit = reference::intersect_sphere(s, on);
            if (cos_wn > 0 && hit) CHECK(hit->t < 1e-6);
        }
    }
}
