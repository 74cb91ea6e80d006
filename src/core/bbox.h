// BBox: an axis-aligned bounding box. An empty box has min = +inf and
// max = -inf, so expanding it by any point gives that point's box.
#pragma once

#include <utility>

#include "core/math.h"
#include "core/ray.h"
#include "core/vec3.h"

namespace pt {

struct BBox {
    Vec3 min{kInfinity};   ///< smallest corner, scene units
    Vec3 max{-kInfinity};  ///< largest corner, scene units

    BBox() = default;
    BBox(const Vec3& a, const Vec3& b) : min(pt::min(a, b)), max(pt::max(a, b)) {}

    bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    void expand(const Vec3& p) {
        min = pt::min(min, p);
        max = pt::max(max, p);
    }
    void expand(const BBox& b) {
        min = pt::min(min, b.min);
        max = pt::max(max, b.max);
    }
    Vec3 extent() const { return max - min; }
    Vec3 centroid() const { return (min + max) * 0.5; }
    /// Surface area: the SAH's probability that a random ray hits the box is
    /// proportional to it (MacDonald and Booth 1990).
    double surface_area() const {
        if (empty()) return 0.0;
        Vec3 e = extent();
        return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
    bool contains(const Vec3& p) const {
        return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y && p.z >= min.z &&
               p.z <= max.z;
    }
    bool contains(const BBox& b) const { return b.empty() || (contains(b.min) && contains(b.max)); }
    /// Position of p in the box: 0 at min, 1 at max, per axis.
    Vec3 offset(const Vec3& p) const {
        Vec3 o = p - min;
        Vec3 e = extent();
        return {e.x > 0 ? o.x / e.x : 0.0, e.y > 0 ? o.y / e.y : 0.0, e.z > 0 ? o.z / e.z : 0.0};
    }
};

inline BBox unite(BBox a, const BBox& b) {
    a.expand(b);
    return a;
}

/// Whether the ray enters `box` within [ray.t_min, t_max], for the
/// accelerators' inner nodes (inv_d = 1 / ray.d per axis). NaN from 0 * inf
/// (a ray in a slab's plane) loses every comparison and so leaves the
/// interval as it was. The far distance is widened by 2 gamma(3) (pbrt-v3
/// section 3.9.2), so rounding never culls a box the ray touches.
inline bool ray_enters(const BBox& box, const Ray& ray, const Vec3& inv_d, double t_max) {
    double t_near = ray.t_min, t_far = t_max;
    for (int a = 0; a < 3; ++a) {
        double t0 = (box.min[a] - ray.o[a]) * inv_d[a], t1 = (box.max[a] - ray.o[a]) * inv_d[a];
        if (t0 > t1) std::swap(t0, t1);
        t1 *= 1 + 2 * gamma(3);
        t_near = t0 > t_near ? t0 : t_near;
        t_far = t1 < t_far ? t1 : t_far;
        if (t_near > t_far) return false;
    }
    return true;
}

}  // namespace pt
