// The watertight ray-triangle test of Woop, Benthin and Wald, "Watertight
// Ray/Triangle Intersection" (JCGT 2(1), 2013), a reference option
// (`--triangle watertight`).
//
// Why: Moller-Trumbore computes each barycentric from differently rounded
// cross products, so a ray through an edge shared by two triangles can
// fail the inside test of both and pass through a closed mesh. The
// watertight test first moves the ray to the origin and shears space so
// the ray is the +z axis; then the inside test is the sign of three 2D
// edge functions U, V, W of the sheared vertices. A shared edge has the
// same two sheared endpoints in both triangles, so its edge function is
// computed from the same numbers and has opposite signs in the two
// triangles: a ray can never miss both. Edge functions that round to
// exactly zero are recomputed in long double, as the paper recommends.
#include <cmath>

#include "core/vec3.h"
#include "stages/intersect.h"

namespace pt::reference {

std::optional<Hit> intersect_triangle_watertight(const Triangle& tri, const Ray& ray) {
    // The dimension where |d| is largest becomes z; swapping x and y when
    // d.z < 0 keeps the winding (and so the signs of U, V, W) unchanged.
    int kz = max_dimension(abs(ray.d));
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if (ray.d[kz] < 0) std::swap(kx, ky);
    if (!(ray.d[kz] != 0.0)) return std::nullopt;  // zero or NaN direction
    const double sx = ray.d[kx] / ray.d[kz], sy = ray.d[ky] / ray.d[kz], sz = 1.0 / ray.d[kz];

    // Vertices relative to the origin, sheared so the ray runs along +z.
    const Vec3 a = tri.p0 - ray.o, b = tri.p1 - ray.o, c = tri.p2 - ray.o;
    const double ax = a[kx] - sx * a[kz], ay = a[ky] - sy * a[kz];
    const double bx = b[kx] - sx * b[kz], by = b[ky] - sy * b[kz];
    const double cx = c[kx] - sx * c[kz], cy = c[ky] - sy * c[kz];

    // Scaled barycentrics: 2D edge functions (signed areas seen from the ray).
    double u = cx * by - cy * bx;
    double v = ax * cy - ay * cx;
    double w = bx * ay - by * ax;
    if (u == 0.0 || v == 0.0 || w == 0.0) {
        using LD = long double;
        u = double(LD(cx) * LD(by) - LD(cy) * LD(bx));
        v = double(LD(ax) * LD(cy) - LD(ay) * LD(cx));
        w = double(LD(bx) * LD(ay) - LD(by) * LD(ax));
    }
    // Inside when all three have the same sign (either winding); zeros count as inside.
    if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return std::nullopt;
    const double det = u + v + w;
    if (!(det != 0.0)) return std::nullopt;  // degenerate (or edge-on) triangle, or NaN

    // Scaled hit distance, then the division once the hit is known to be inside.
    const double t_scaled = u * (sz * a[kz]) + v * (sz * b[kz]) + w * (sz * c[kz]);
    const double inv_det = 1.0 / det;
    const double t = t_scaled * inv_det;
    if (!(t >= ray.t_min && t <= ray.t_max)) return std::nullopt;

    Hit hit;
    hit.t = t;
    hit.b1 = v * inv_det;
    hit.b2 = w * inv_det;
    const Vec3 ng = cross(tri.p1 - tri.p0, tri.p2 - tri.p0);
    hit.n = ng / ng.norm();
    if (tri.has_normals) {
        Vec3 n = (u * inv_det) * tri.n0 + hit.b1 * tri.n1 + hit.b2 * tri.n2;
        double len = n.norm();
        if (len > 0 && std::isfinite(len)) hit.n = n / len;
    }
    if (!hit.n.is_finite()) return std::nullopt;
    return hit;
}

}  // namespace pt::reference
