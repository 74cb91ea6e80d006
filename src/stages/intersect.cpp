// Reference implementation of stage `intersect`. See stages/intersect.h.
#include "stages/intersect.h"

#include <cmath>

#include "core/math.h"

namespace pt::reference {

std::optional<Hit> intersect_triangle(const Triangle& tri, const Ray& ray) {
    Vec3 e1 = tri.p1 - tri.p0;
    Vec3 e2 = tri.p2 - tri.p0;
    Vec3 pvec = cross(ray.d, e2);
    double det = dot(e1, pvec);
    // det = 0: the ray is parallel to the plane or the triangle is
    // degenerate. Comparing with 0 (not an epsilon) keeps tiny but valid
    // triangles; the NaN-safe form (!(det != 0)) also rejects NaN input.
    if (!(det != 0.0)) return std::nullopt;
    double inv_det = 1.0 / det;
    Vec3 s = ray.o - tri.p0;
    double b1 = dot(s, pvec) * inv_det;
    if (!(b1 >= 0.0 && b1 <= 1.0)) return std::nullopt;
    Vec3 qvec = cross(s, e1);
    double b2 = dot(ray.d, qvec) * inv_det;
    if (!(b2 >= 0.0 && b1 + b2 <= 1.0)) return std::nullopt;
    double t = dot(e2, qvec) * inv_det;
    if (!(t >= ray.t_min && t <= ray.t_max)) return std::nullopt;

    Hit hit;
    hit.t = t;
    hit.b1 = b1;
    hit.b2 = b2;
    Vec3 ng = cross(e1, e2);
    hit.n = ng / ng.norm();
    if (tri.has_normals) {
        // Interpolated normals can cancel to zero (opposing vertex normals);
        // keep the geometric normal then.
        Vec3 n = (1.0 - b1 - b2) * tri.n0 + b1 * tri.n1 + b2 * tri.n2;
        double len = n.norm();
        if (len > 0 && std::isfinite(len)) hit.n = n / len;
    }
    if (!hit.n.is_finite()) return std::nullopt;  // area underflowed to zero
    return hit;
}

std::optional<Hit> intersect_sphere(const Sphere& sphere, const Ray& ray) {
    // Solve a t^2 - 2 b' t + c = 0 with f = o - center, a = d.d, b' = -f.d,
    // c = f.f - r^2 (Ray Tracing Gems ch. 7, equations 7.5 to 7.9).
    Vec3 f = ray.o - sphere.center;
    double a = dot(ray.d, ray.d);
    double b = -dot(f, ray.d);  // b' above: the parameter of the point closest to the centre, times a
    double c = dot(f, f) - sphere.radius * sphere.radius;
    // Discriminant from the perpendicular distance: r^2 - |f + (b/a) d|^2,
    // times a. Avoids b^2 - ac, which cancels catastrophically for far spheres.
    Vec3 perp = f + (b / a) * ray.d;
    double disc = a * (sphere.radius * sphere.radius - dot(perp, perp));
    if (!(disc >= 0.0)) return std::nullopt;
    double root = std::sqrt(disc);
    // q has the sign of b, so b + sign(b) root never cancels; t0 t1 = c / a.
    double q = b + std::copysign(root, b);
    double t0 = c / q;
    double t1 = q / a;
    if (t0 > t1) std::swap(t0, t1);
    double t = t0;
    if (!(t >= ray.t_min && t <= ray.t_max)) {
        t = t1;
        if (!(t >= ray.t_min && t <= ray.t_max)) return std::nullopt;
    }
    Hit hit;
    hit.t = t;
    hit.n = (ray.o + t * ray.d - sphere.center) / sphere.radius;
    double len = hit.n.norm();
    if (!(len > 0)) return std::nullopt;
    hit.n = hit.n / len;
    return hit;
}

}  // namespace pt::reference
