// Part 1, tasks 3 and 4, written from the TODO steps.
#include <cmath>

#include "stages/intersect.h"

namespace pt::student {

std::optional<Hit> intersect_triangle(const Triangle& tri, const Ray& ray) {
    Vec3 e1 = tri.p1 - tri.p0, e2 = tri.p2 - tri.p0, s = ray.o - tri.p0;
    Vec3 s1 = cross(ray.d, e2), s2 = cross(s, e1);
    double det = dot(s1, e1);
    if (det == 0) return std::nullopt;
    double t = dot(s2, e2) / det, b1 = dot(s1, s) / det, b2 = dot(s2, ray.d) / det;
    if (b1 < 0 || b2 < 0 || b1 + b2 > 1) return std::nullopt;
    if (t < ray.t_min || t > ray.t_max) return std::nullopt;
    Hit hit;
    hit.t = t, hit.b1 = b1, hit.b2 = b2;
    if (tri.has_normals)
        hit.n = ((1 - b1 - b2) * tri.n0 + b1 * tri.n1 + b2 * tri.n2).unit();
    else
        hit.n = cross(e1, e2).unit();
    return hit;
}

std::optional<Hit> intersect_sphere(const Sphere& sphere, const Ray& ray) {
    Vec3 f = ray.o - sphere.center;
    double a = dot(ray.d, ray.d), b = 2 * dot(f, ray.d);
    double c = dot(f, f) - sphere.radius * sphere.radius;
    double disc = b * b - 4 * a * c;
    if (disc < 0) return std::nullopt;
    double t = (-b - std::sqrt(disc)) / (2 * a);
    if (t < ray.t_min || t > ray.t_max) t = (-b + std::sqrt(disc)) / (2 * a);
    if (t < ray.t_min || t > ray.t_max) return std::nullopt;
    Hit hit;
    hit.t = t;
    hit.n = (ray.at(t) - sphere.center) / sphere.radius;
    return hit;
}

}  // namespace pt::student
