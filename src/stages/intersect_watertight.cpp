// The watertight ray-triangle test of Woop, Benthin and Wald, "Watertight
// Ray/Triangle Intersection" (JCGT 2(1), 2013), a reference option
// (`--triangle watertight`).
//
// Why: Moller-Trumbore computes each barycentric from differently rounded
// cross products, so a ray through an edge shared by two triangles can
// fail the inside test of both and pass through a closed mesh. The
// watertight test first moves the ray to the origin and shears space so
// the ray is the +z axis; then the inside test is the sign of three 2D
// edge functions of the sheared vertices. A shared edge has the same two
// sheared endpoints in both triangles, so its edge function is computed
// from the same numbers and has opposite signs in the two triangles: a
// ray can never miss both. The arithmetic is in stages/watertight.h.
#include <cmath>

#include "stages/intersect.h"
#include "stages/watertight.h"

namespace pt::reference {

std::optional<Hit> intersect_triangle_watertight(const Triangle& tri, const Ray& ray) {
    Hit hit;
    if (!watertight_hit(tri.p0, tri.p1, tri.p2, ray, prepare_watertight(ray), hit.t, hit.b1, hit.b2))
        return std::nullopt;
    // The normal exactly as reference::intersect_triangle computes it.
    const Vec3 ng = cross(tri.p1 - tri.p0, tri.p2 - tri.p0);
    hit.n = ng / ng.norm();
    if (tri.has_normals) {
        Vec3 n = (1.0 - hit.b1 - hit.b2) * tri.n0 + hit.b1 * tri.n1 + hit.b2 * tri.n2;
        double len = n.norm();
        if (len > 0 && std::isfinite(len)) hit.n = n / len;
    }
    if (!hit.n.is_finite()) return std::nullopt;
    return hit;
}

}  // namespace pt::reference
