// What the spatial subdivisions (`--accel grid`, `--accel kdtree`) share:
// primitive boxes grown by a margin, the double-precision clip of a ray to
// a box, and the closest-hit bookkeeping with the accelerators' tie rule.
//
// Why the margin: a grid cell or kd-tree voxel is left behind for good once
// the ray has passed it, so a primitive must be listed in every cell where
// its computed hit can lie. The computed hit point o + t d of a primitive
// lies a few ulps (relative to |o - p0|, more at grazing angles) off the
// exact primitive, and the cell boundaries are computed with rounding too.
// Listing each primitive in every cell its box touches after growing the
// box by 2^-20 of the scene's largest coordinate (about 10^-6, far above
// those errors and far below a cell) makes both errors harmless; the cost is
// a few extra references for primitives lying on cell planes.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/bbox.h"
#include "core/ray.h"
#include "scene/scene.h"
#include "stages/bvh.h"

namespace pt {

/// The margin described above for a scene whose primitives lie in `bounds`.
inline double insertion_margin(const BBox& bounds) {
    double m = 0;
    for (int a = 0; a < 3; ++a)
        m = std::max({m, std::fabs(bounds.min[a]), std::fabs(bounds.max[a])});
    return std::ldexp(m, -20) + 1e-300;
}

/// padded_primitive_bounds grown by `margin` on every side.
inline BBox insertion_bounds(const Scene& scene, uint32_t prim, double margin) {
    BBox b = padded_primitive_bounds(scene, prim);
    return BBox(b.min - Vec3(margin), b.max + Vec3(margin));
}

/// The part [t0, t1] of [ray.t_min, ray.t_max] inside the closed box, in
/// double precision; false when empty. A zero direction component (either
/// sign) constrains nothing when the origin lies within that slab.
inline bool clip_ray(const BBox& box, const Ray& ray, double& t0, double& t1) {
    t0 = ray.t_min;
    t1 = ray.t_max;
    for (int a = 0; a < 3; ++a) {
        if (ray.d[a] == 0) {
            if (ray.o[a] < box.min[a] || ray.o[a] > box.max[a]) return false;
            continue;
        }
        double inv = 1.0 / ray.d[a];
        double near = (box.min[a] - ray.o[a]) * inv, far = (box.max[a] - ray.o[a]) * inv;
        if (near > far) std::swap(near, far);
        t0 = std::max(t0, near);
        t1 = std::min(t1, far);
    }
    return t0 <= t1;
}

/// The closest hit so far, with the tie rule of every accelerator (bvh.h):
/// at equal t the larger primitive id wins, as in the linear scan.
struct ClosestHit {
    explicit ClosestHit(const Ray& ray) : ray(ray) {}
    /// Keeps `hit` if it is closer; the ray's t_max follows the closest hit
    /// (inclusive, so that an equal t can still win the tie).
    void offer(const std::optional<Hit>& hit) {
        if (!hit || !BVHTree::closer(*hit, best)) return;
        best = hit;
        ray.t_max = hit->t;
    }
    Ray ray;                  ///< the query ray, t_max shrunk to the closest hit
    std::optional<Hit> best;  ///< the closest hit so far
};

}  // namespace pt
