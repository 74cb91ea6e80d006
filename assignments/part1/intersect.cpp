// Part 1, tasks 3 and 4: ray-triangle and ray-sphere intersection.
// Read assignments/part1/README.md first; the contract of each function is
// in src/stages/intersect.h.
#include "core/error.h"
#include "stages/intersect.h"

namespace pt::student {

std::optional<Hit> intersect_triangle(const Triangle& triangle, const Ray& ray) {
    // TODO(part1.3): intersect_triangle, as src/stages/intersect.h states its contract.
    // [guided]
    // the Moller-Trumbore test. Return a Hit with t, the
    // barycentrics b1 and b2, and the unit normal n (interpolated from
    // triangle.n0, n1, n2 when triangle.has_normals, else the geometric
    // normal) when t lies in [ray.t_min, ray.t_max]; std::nullopt otherwise.
    // [/guided]
    (void)triangle, (void)ray;
    throw NotImplemented(1, "3", "intersect_triangle");
}

std::optional<Hit> intersect_sphere(const Sphere& sphere, const Ray& ray) {
    // TODO(part1.4): intersect_sphere, as src/stages/intersect.h states its contract.
    // [guided]
    // solve the quadratic |o + t d - c|^2 = r^2 and return the
    // nearest root in [ray.t_min, ray.t_max] with the outward unit normal.
    // [/guided]
    (void)sphere, (void)ray;
    throw NotImplemented(1, "4", "intersect_sphere");
}

}  // namespace pt::student
