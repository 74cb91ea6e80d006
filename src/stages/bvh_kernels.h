// The parts of the reference BVH's traversal that every node layout shares
// (stages/bvh_traverse.cpp for the binary tree, stages/bvh_wide.cpp for
// the 4-wide one): the conservative float slab test and the "primitive
// testers" that run the leaves. Internal to those two files.
//
// The leaf loop is written once, for any "primitive tester": a class that
// keeps per-primitive data in the BVH's leaf order and answers
//     prepare(ray)                 per-ray setup (e.g. a watertight test's shear)
//     intersect(slot, ray, q, hit) t, b1, b2 of a hit within [t_min, t_max]
//     finish(slot, ray, hit)       the rest of the Hit (the normal), once per ray
// Three testers exist: InlineMollerTrumbore (the reference triangle
// routine, inlined on precomputed edges), InlineWatertight (Woop et al.'s
// watertight test, `--triangle watertight`) and StageRoutines (the
// intersect stage's function pointers, e.g. student code).
#pragma once

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <optional>
#include <vector>

#include "core/math.h"
#include "scene/scene.h"
#include "stages/bvh.h"
#include "stages/flat_bvh.h"
#include "stages/watertight.h"

namespace pt::bvh_kernels {

// ---------------------------------------------------------------------------
// The slab test
//
// In single precision, on the nodes' float boxes, with the double-precision
// ray rounded so that the test stays conservative: it may report a box the
// ray misses by a few ulps, never miss one the ray enters (Ize, "Robust BVH
// Ray Traversal", JCGT 2013; pbrt-v3 section 3.9.2 for the error bounds).
//
//  - The origin is rounded to float twice, once for near planes and once
//    for far planes, each in the direction that can only lower the near
//    distance and raise the far one. Together they amount to growing the box
//    by the origin's rounding error. (For a positive direction the near
//    plane is the min plane: (b - o) * (1/d) gets smaller as o grows, so the
//    near origin is o rounded up; the rest follows the same way.)
//  - A computed distance (b - o) * (1/d) is within gamma(3) of the exact one
//    for the rounded origin (three roundings: subtraction, reciprocal,
//    product), so the far distance is scaled by 1 + 2 gamma(5) before it is
//    compared with the near one, with room for rounding 1/d twice and for the
//    scaling itself.
//  - A zero direction component gives 1/d = +-inf (IEEE) and the distances
//    +-inf, or NaN (0 * inf) when the origin lies exactly on a plane: then
//    the ray lies in the plane, on the closed box's boundary, and the plane
//    must constrain nothing. The comparisons below are false for NaN, so a
//    NaN distance never replaces t_near or t_far.
//  - -0.0: which plane is near follows the sign bit of 1/d, not d < 0, so a
//    direction of -0.0 (1/d = -inf) enters through the max plane like any
//    negative one.
//  - Float range: a ray from farther than 1e30, or with every direction
//    component below 1e-7, could have hits at t beyond float range; such
//    rays (and every ray in a scene with coordinates beyond 1e30) are
//    prepared so that every box test passes: correct, and as slow as a
//    linear scan. A nonzero component so small that 1/d overflows float
//    gets FLT_MAX for near planes (distances come out lower) and infinity
//    for far planes (higher).

constexpr float gamma_f(int n) {
    return n * 0x1p-24f / (1 - n * 0x1p-24f);
}
constexpr float kFarScale = 1.0f + 2.0f * gamma_f(5);

/// Hits of a ray that is not prepared to visit every box lie within this
/// distance: |o| <= 1e30, coordinates <= 1e30 and |d|max >= 1e-7.
constexpr double kFloatTraversalRange = 1e38;

/// A ray prepared for slab tests against float boxes.
struct SlabRay {
    float o_near[3];         ///< origin for the near planes (see above)
    float o_far[3];          ///< origin for the far planes
    float inv_near[3];       ///< 1 / d for the near planes
    float inv_far[3];        ///< 1 / d for the far planes
    uint32_t near_plane[3];  ///< index of the near plane in FlatBvhNode::bounds
    uint32_t far_plane[3];   ///< index of the far plane
    bool negative[3];        ///< whether the ray runs towards -infinity on each axis
    float t_min;             ///< the ray's t_min, rounded down

    SlabRay() = default;
    SlabRay(const Ray& ray, bool float_scene) : t_min(float_down(ray.t_min)) {
        double o_max = std::max({std::fabs(ray.o.x), std::fabs(ray.o.y), std::fabs(ray.o.z)});
        double d_max = std::max({std::fabs(ray.d.x), std::fabs(ray.d.y), std::fabs(ray.d.z)});
        const bool visit_all = !float_scene || !(o_max <= 1e30) || !(d_max >= 1e-7);
        for (int a = 0; a < 3; ++a) {
            double inv = 1.0 / ray.d[a];
            negative[a] = std::signbit(inv);
            near_plane[a] = uint32_t(negative[a] ? 3 + a : a);
            far_plane[a] = uint32_t(negative[a] ? a : 3 + a);
            inv_near[a] = inv_far[a] = float(inv);
            if (std::isinf(inv_near[a]) && ray.d[a] != 0) {  // 1/d overflowed
                inv_near[a] = std::copysign(FLT_MAX, inv_near[a]);
            }
            if (visit_all) {  // every near distance -inf, every far one +inf
                o_near[a] = negative[a] ? -INFINITY : INFINITY;
                o_far[a] = -o_near[a];
            } else {
                o_near[a] = negative[a] ? float_down(ray.o[a]) : float_up(ray.o[a]);
                o_far[a] = negative[a] ? float_up(ray.o[a]) : float_down(ray.o[a]);
            }
        }
    }
};

/// The t_max of box tests for a ray interval ending at t_max: rounded up,
/// and finite (so that a ray parallel to a slab and outside it, entering
/// at t = +inf, misses even when t_max = +inf).
inline float box_t_max(double t_max) {
    return float_up(std::min(t_max, kFloatTraversalRange));
}

/// Whether the ray enters the node's box before t_max; the entry distance
/// goes to t_enter.
inline bool slab_test(const FlatBvhNode& node, const SlabRay& r, float t_max, float& t_enter) {
    float t_near = r.t_min, t_far = t_max;
    for (int a = 0; a < 3; ++a) {
        float t0 = (node.bounds[r.near_plane[a]] - r.o_near[a]) * r.inv_near[a];
        float t1 = (node.bounds[r.far_plane[a]] - r.o_far[a]) * r.inv_far[a];
        t_near = t0 > t_near ? t0 : t_near;
        t_far = t1 < t_far ? t1 : t_far;
    }
    t_enter = t_near;
    return t_near <= t_far * kFarScale;
}

// ---------------------------------------------------------------------------
// Primitive testers

/// Whether a primitive goes through the stage's routines in the inlined
/// testers: a sphere, or a triangle whose normal the reference cannot
/// normalise (then whether it is hit depends on its vertex normals at the
/// hit point: reference::intersect_triangle).
inline bool is_generic_primitive(const Scene& scene, uint32_t prim) {
    if (scene.is_sphere(prim)) return true;
    const TriangleRecord& r = scene.triangles[prim];
    const Vec3 &p0 = scene.positions[r.v[0]], &p1 = scene.positions[r.v[1]], &p2 = scene.positions[r.v[2]];
    Vec3 ng = cross(p1 - p0, p2 - p0);
    return !(ng / ng.norm()).is_finite();
}

/// is_generic_primitive of every primitive, in primitive order (which reads
/// the scene's arrays in sequence).
inline std::vector<uint8_t> generic_primitives(const Scene& scene) {
    std::vector<uint8_t> generic(scene.primitive_count(), 0);
    for (uint32_t prim = 0; prim < generic.size(); ++prim)
        generic[prim] = is_generic_primitive(scene, prim) ? 1 : 0;
    return generic;
}

/// What the inlined testers share: the slot-to-primitive order, the slots
/// that must go through the stage's routines (spheres, and triangles whose
/// normal the reference could not normalise, which depends on the hit
/// point), and the shading normal exactly as the reference computes it.
class InlineTriangleSlots {
  public:
    /// `generic_prims`: generic_primitives(scene), when the caller has it.
    InlineTriangleSlots(const Scene& scene, const IntersectStage& stage, const std::vector<uint32_t>& order,
                        const std::vector<uint8_t>* generic_prims = nullptr)
        : scene_(scene), stage_(stage), order_(order), generic_(order.size(), 0) {
        // Decided in primitive order (generic_primitives), then given to the slots.
        const std::vector<uint8_t> own = generic_prims ? std::vector<uint8_t>() : generic_primitives(scene);
        const std::vector<uint8_t>& generic = generic_prims ? *generic_prims : own;
        for (const TriangleRecord& r : scene.triangles)
            vertex_normals_ = vertex_normals_ || r.n[0] != kNoIndex;
        for (size_t slot = 0; slot < order.size(); ++slot)
            generic_[slot] = order[slot] < generic.size() ? generic[order[slot]] : 1;
    }

  protected:
    bool is_generic(uint32_t slot) const { return generic_[slot] != 0; }
    bool intersect_generic(uint32_t slot, const Ray& ray, Hit& hit) const {
        std::optional<Hit> h = intersect_primitive(scene_, stage_, order_[slot], ray);
        if (h) hit = *h;
        return h.has_value();
    }
    /// hit.n from the unnormalised geometric normal and the vertex normals.
    void shading_normal(uint32_t slot, const Vec3& ng, Hit& hit) const {
        hit.n = ng / ng.norm();
        if (!vertex_normals_) return;  // no triangle has them: not worth fetching the record
        const TriangleRecord& r = scene_.triangles[order_[slot]];
        if (r.n[0] != kNoIndex) {
            double b1 = hit.b1, b2 = hit.b2;
            Vec3 n = (1.0 - b1 - b2) * scene_.normals[r.n[0]] + b1 * scene_.normals[r.n[1]] +
                     b2 * scene_.normals[r.n[2]];
            double len = n.norm();
            if (len > 0 && std::isfinite(len)) hit.n = n / len;
        }
    }
    uint64_t slot_bytes() const { return generic_.size(); }

    const Scene& scene_;
    IntersectStage stage_;
    const std::vector<uint32_t>& order_;  ///< primitive id of each slot (FlatBvh::primitives)

  private:
    std::vector<uint8_t> generic_;  ///< 1: test the slot through the stage's routines
    bool vertex_normals_ = false;  ///< some triangle has vertex normals
};

/// The reference triangle routine (Moller-Trumbore, stages/intersect.cpp)
/// on triangles stored as (p0, e1, e2) in leaf order: the same operations in
/// the same order, so the same bits, without the call and without fetching
/// vertices through the scene's index arrays.
class InlineMollerTrumbore : public InlineTriangleSlots {
  public:
    struct RayData {};  ///< Moller-Trumbore needs no per-ray setup

    /// `blocks`: the caller (the wide BVH) will test every inline triangle in
    /// its leaf blocks and only generic slots through intersect(); then the
    /// per-slot copy is not made (stored() reads the scene's corners).
    InlineMollerTrumbore(const Scene& scene, const IntersectStage& stage, const std::vector<uint32_t>& order,
                         bool blocks = false, const std::vector<uint8_t>* generic_prims = nullptr)
        : InlineTriangleSlots(scene, stage, order, generic_prims) {
        if (blocks) return;
        triangles_.resize(order.size());
        for (size_t slot = 0; slot < order.size(); ++slot) {
            if (scene.is_sphere(order[slot])) continue;
            const TriangleRecord& r = scene.triangles[order[slot]];
            const Vec3 &p0 = scene.positions[r.v[0]], &p1 = scene.positions[r.v[1]], &p2 = scene.positions[r.v[2]];
            triangles_[slot] = {p0, p1 - p0, p2 - p0};
        }
    }

    RayData prepare(const Ray&) const { return {}; }

    bool intersect(uint32_t slot, const Ray& ray, const RayData&, Hit& hit) const {
        if (is_generic(slot)) return intersect_generic(slot, ray, hit);
        // Exactly reference::intersect_triangle's arithmetic; tests/bvh
        // checks that t, b1 and b2 agree to the last bit.
        const TriangleData& tri = triangles_[slot];
        Vec3 pvec = cross(ray.d, tri.e2);
        double det = dot(tri.e1, pvec);
        if (!(det != 0.0)) return false;
        double inv_det = 1.0 / det;
        Vec3 s = ray.o - tri.p0;
        double b1 = dot(s, pvec) * inv_det;
        if (!(b1 >= 0.0 && b1 <= 1.0)) return false;
        Vec3 qvec = cross(s, tri.e1);
        double b2 = dot(ray.d, qvec) * inv_det;
        if (!(b2 >= 0.0 && b1 + b2 <= 1.0)) return false;
        double t = dot(tri.e2, qvec) * inv_det;
        if (!(t >= ray.t_min && t <= ray.t_max)) return false;
        hit.t = t;
        hit.b1 = b1;
        hit.b2 = b2;
        return true;
    }

    /// The shading normal, as reference::intersect_triangle computes it.
    void finish(uint32_t slot, const Ray&, Hit& hit) const {
        if (is_generic(slot)) return;  // the routine filled in everything
        Vec3 p0, e1, e2;
        stored(slot, p0, e1, e2);
        shading_normal(slot, cross(e1, e2), hit);
    }

    /// finish() for an inline slot whose (e1, e2) the caller holds (the
    /// same bits as stored()'s: the wide BVH's leaf blocks), so that the
    /// triangle is not fetched again.
    void finish_from_edges(uint32_t slot, const Vec3& e1, const Vec3& e2, Hit& hit) const {
        shading_normal(slot, cross(e1, e2), hit);
    }

    uint64_t bytes() const { return triangles_.size() * sizeof(TriangleData) + slot_bytes(); }

    /// Whether the slot is a triangle tested inline (not a generic slot), and
    /// its stored (p0, e1, e2): for the wide BVH's leaf blocks (bvh_leaf_block.h).
    bool is_inline(uint32_t slot) const { return !is_generic(slot); }
    /// Without the per-slot copy, computed from the scene's corners (the same bits).
    void stored(uint32_t slot, Vec3& p0, Vec3& e1, Vec3& e2) const {
        if (triangles_.empty()) {
            const TriangleRecord& r = scene_.triangles[order_[slot]];
            p0 = scene_.positions[r.v[0]];
            e1 = scene_.positions[r.v[1]] - p0;
            e2 = scene_.positions[r.v[2]] - p0;
            return;
        }
        p0 = triangles_[slot].p0;
        e1 = triangles_[slot].e1;
        e2 = triangles_[slot].e2;
    }

    /// The slot's three corners, from the scene (for the wide BVH's
    /// FloatCornerBlocks, which store corners and subtract the edges).
    void corners(uint32_t slot, Vec3& p0, Vec3& p1, Vec3& p2) const {
        const TriangleRecord& r = scene_.triangles[order_[slot]];
        p0 = scene_.positions[r.v[0]];
        p1 = scene_.positions[r.v[1]];
        p2 = scene_.positions[r.v[2]];
    }

  private:
    struct TriangleData {
        Vec3 p0;  ///< first corner
        Vec3 e1;  ///< p1 - p0
        Vec3 e2;  ///< p2 - p0
    };
    std::vector<TriangleData> triangles_;  ///< per slot; unused for generic slots
};

/// The watertight test (stages/watertight.h, `--triangle watertight`) on
/// triangles stored as corners in leaf order; the shear is set up once per ray.
class InlineWatertight : public InlineTriangleSlots {
  public:
    using RayData = WatertightRay;

    InlineWatertight(const Scene& scene, const IntersectStage& stage, const std::vector<uint32_t>& order)
        : InlineTriangleSlots(scene, stage, order), triangles_(order.size()) {
        for (size_t slot = 0; slot < order.size(); ++slot) {
            if (scene.is_sphere(order[slot])) continue;
            Triangle tri = scene.triangle(order[slot]);
            triangles_[slot] = {tri.p0, tri.p1, tri.p2};
        }
    }

    RayData prepare(const Ray& ray) const { return prepare_watertight(ray); }

    bool intersect(uint32_t slot, const Ray& ray, const RayData& w, Hit& hit) const {
        if (is_generic(slot)) return intersect_generic(slot, ray, hit);
        const TriangleData& tri = triangles_[slot];
        return watertight_hit(tri.p0, tri.p1, tri.p2, ray, w, hit.t, hit.b1, hit.b2);
    }

    void finish(uint32_t slot, const Ray&, Hit& hit) const {
        if (is_generic(slot)) return;
        const TriangleData& tri = triangles_[slot];
        shading_normal(slot, cross(tri.p1 - tri.p0, tri.p2 - tri.p0), hit);
    }

    uint64_t bytes() const { return triangles_.size() * sizeof(TriangleData) + slot_bytes(); }

  private:
    struct TriangleData {
        Vec3 p0, p1, p2;  ///< corners
    };
    std::vector<TriangleData> triangles_;  ///< per slot; unused for generic slots
};

/// Every primitive through the intersect stage's function pointers (the
/// student's routines, or any routine that is not the reference one).
class StageRoutines {
  public:
    struct RayData {};

    StageRoutines(const Scene& scene, const IntersectStage& stage,
                  const std::vector<uint32_t>& order)
        : scene_(scene), stage_(stage), order_(order) {}

    RayData prepare(const Ray&) const { return {}; }
    bool intersect(uint32_t slot, const Ray& ray, const RayData&, Hit& hit) const {
        std::optional<Hit> h = intersect_primitive(scene_, stage_, order_[slot], ray);
        if (h) hit = *h;
        return h.has_value();
    }
    void finish(uint32_t, const Ray&, Hit&) const {}
    uint64_t bytes() const { return 0; }

  private:
    const Scene& scene_;
    IntersectStage stage_;
    const std::vector<uint32_t>& order_;
};

}  // namespace pt::bvh_kernels
