// BBox: an axis-aligned bounding box. An empty box has min = +inf and
// max = -inf, so expanding it by any point gives that point's box.
#pragma once

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

}  // namespace pt
