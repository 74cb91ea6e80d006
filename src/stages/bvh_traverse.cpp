// Traversing the reference BVH (stages/flat_bvh.h): closest hit and any hit
// with an explicit stack, children nearest first, and a robust slab test.
//
// The leaf loop is written once, for any "primitive tester": a class that
// keeps per-primitive data in the BVH's leaf order and answers
//     prepare(ray)                 per-ray setup (e.g. a watertight test's shear)
//     intersect(slot, ray, q, hit) t, b1, b2 of a hit within [t_min, t_max]
//     finish(slot, ray, hit)       the rest of the Hit (the normal), once per ray
// Two testers exist: InlineMollerTrumbore (the reference triangle routine,
// inlined on precomputed edges) and StageRoutines (the intersect stage's
// function pointers, e.g. student code). A second inline triangle test,
// such as Woop et al.'s watertight one, is one more tester class and one
// more line in make_reference_bvh.
#include <cfloat>
#include <cmath>

#include "core/counters.h"
#include "core/math.h"
#include "scene/scene.h"
#include "stages/bvh.h"
#include "stages/flat_bvh.h"
#include "stages/stages.h"

namespace pt {
namespace {

// ---------------------------------------------------------------------------
// The slab test

/// Rounding allowance on far-plane distances. A computed distance
/// (b - o) * (1/d) is within gamma(3) of the true one (three roundings:
/// the subtraction, the reciprocal, the product; pbrt-v3 section 3.9.2), so
/// scaling the far planes by 1 + 2 gamma(6) keeps every computed near
/// distance below the computed far distance whenever the true ones are in
/// that order, with room for the rounding of the factor itself (Ize 2013).
const double kFarScale = 1.0 + 2.0 * gamma(6);

/// A ray prepared for slab tests: reciprocal directions and which box
/// corner is nearer on each axis.
struct SlabRay {
    double o[3];        ///< origin
    double inv[3];      ///< 1 / d: +-inf for a +-0 component (IEEE division)
    double inv_far[3];  ///< inv * kFarScale: for the far planes
    int near[3];        ///< 0 when the min corner is entered first, 1 when the max corner is
    double t_min;       ///< the ray's t_min

    explicit SlabRay(const Ray& ray) : t_min(ray.t_min) {
        for (int a = 0; a < 3; ++a) {
            o[a] = ray.o[a];
            inv[a] = 1.0 / ray.d[a];
            inv_far[a] = inv[a] * kFarScale;
            // The sign bit of 1/d, not d < 0: a direction of -0.0 has
            // 1/d = -inf and enters through the max corner like any negative one.
            near[a] = std::signbit(inv[a]) ? 1 : 0;
        }
    }
};

/// The largest t_max a box test uses for a ray interval ending at t_max:
/// scaled like the far planes (so that a primitive hit exactly at t_max, a
/// tie, is not culled by rounding) and finite (so that a ray parallel to a
/// slab and outside it, entering at t = +inf, misses even when t_max = +inf).
inline double box_t_max(double t_max) {
    return std::min(t_max * kFarScale, DBL_MAX);
}

/// Whether the ray enters the node's box before t_max; the entry distance
/// goes to t_enter. Where a distance is NaN (a zero direction component and
/// an origin exactly on that plane: 0 * inf), the comparisons below are
/// false and the plane is ignored, which is right: such a ray lies in the
/// plane, on the closed box's boundary along that axis.
inline bool slab_test(const FlatBvhNode& node, const SlabRay& r, double t_max, double& t_enter) {
    double t_near = r.t_min, t_far = t_max;
    for (int a = 0; a < 3; ++a) {
        double t0 = (double(node.bounds[r.near[a]][a]) - r.o[a]) * r.inv[a];
        double t1 = (double(node.bounds[1 - r.near[a]][a]) - r.o[a]) * r.inv_far[a];
        t_near = t0 > t_near ? t0 : t_near;
        t_far = t1 < t_far ? t1 : t_far;
    }
    t_enter = t_near;
    return t_near <= t_far;
}

// ---------------------------------------------------------------------------
// Primitive testers

/// The reference triangle routine (Moller-Trumbore, stages/intersect.cpp)
/// on triangles stored as (p0, e1, e2) in leaf order: the same operations in
/// the same order, so the same bits, without the call and without fetching
/// vertices through the scene's index arrays. Spheres, and triangles whose
/// normal the reference could not normalise, go through the stage's routines.
class InlineMollerTrumbore {
  public:
    struct RayData {};  ///< Moller-Trumbore needs no per-ray setup

    InlineMollerTrumbore(const Scene& scene, const IntersectStage& stage,
                         const std::vector<uint32_t>& order)
        : scene_(scene),
          stage_(stage),
          order_(order),
          triangles_(order.size()),
          generic_(order.size(), 0) {
        for (size_t slot = 0; slot < order.size(); ++slot) {
            uint32_t prim = order[slot];
            if (scene.is_sphere(prim)) {
                generic_[slot] = 1;
                continue;
            }
            Triangle tri = scene.triangle(prim);
            TriangleData& d = triangles_[slot];
            d.p0 = tri.p0;
            d.e1 = tri.p1 - tri.p0;
            d.e2 = tri.p2 - tri.p0;
            // The reference drops a hit whose geometric normal is not finite
            // (its area underflowed) unless the vertex normals rescue it,
            // which depends on the hit point: leave those to the routine.
            Vec3 ng = cross(d.e1, d.e2);
            if (!(ng / ng.norm()).is_finite()) generic_[slot] = 1;
        }
    }

    RayData prepare(const Ray&) const { return {}; }

    bool intersect(uint32_t slot, const Ray& ray, const RayData&, Hit& hit) const {
        if (generic_[slot]) {
            std::optional<Hit> h = intersect_primitive(scene_, stage_, order_[slot], ray);
            if (h) hit = *h;
            return h.has_value();
        }
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
        if (generic_[slot]) return;  // the routine filled in everything
        const TriangleData& d = triangles_[slot];
        Vec3 ng = cross(d.e1, d.e2);
        hit.n = ng / ng.norm();
        const TriangleRecord& r = scene_.triangles[order_[slot]];
        if (r.n[0] != kNoIndex) {
            double b1 = hit.b1, b2 = hit.b2;
            Vec3 n = (1.0 - b1 - b2) * scene_.normals[r.n[0]] + b1 * scene_.normals[r.n[1]] +
                     b2 * scene_.normals[r.n[2]];
            double len = n.norm();
            if (len > 0 && std::isfinite(len)) hit.n = n / len;
        }
    }

    uint64_t bytes() const { return triangles_.size() * sizeof(TriangleData) + generic_.size(); }

  private:
    struct TriangleData {
        Vec3 p0;  ///< first corner
        Vec3 e1;  ///< p1 - p0
        Vec3 e2;  ///< p2 - p0
    };
    const Scene& scene_;
    IntersectStage stage_;
    const std::vector<uint32_t>& order_;   ///< primitive id of each slot (FlatBvh::primitives)
    std::vector<TriangleData> triangles_;  ///< per slot; unused for generic slots
    std::vector<uint8_t> generic_;         ///< 1: test the slot through the stage's routines
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

// ---------------------------------------------------------------------------
// The accelerator

template <class Tester>
class ReferenceBvh final : public Accelerator, public InspectableBvh {
  public:
    ReferenceBvh(const Scene& scene, const IntersectStage& stage, FlatBvh bvh)
        : bvh_(std::move(bvh)), tester_(scene, stage, bvh_.primitives) {}

    std::optional<Hit> intersect(const Ray& ray) const override {
        Hit best;
        uint32_t best_slot = 0;
        if (!traverse<false>(ray, best, best_slot)) return std::nullopt;
        tester_.finish(best_slot, ray, best);
        best.primitive = bvh_.primitives[best_slot];
        return best;
    }

    bool occluded(const Ray& ray) const override {
        Hit hit;
        uint32_t slot = 0;
        return traverse<true>(ray, hit, slot);
    }

    AcceleratorInfo info() const override {
        return {std::string("bvh-") + to_string(bvh_.split), bvh_.nodes.size(), bvh_.depth,
                bvh_.bytes() + tester_.bytes()};
    }

    std::optional<BvhNodeView> node_at(const std::string& path) const override {
        if (bvh_.nodes.empty()) return std::nullopt;
        uint32_t node = 0;
        for (char step : path) {
            if (bvh_.nodes[node].is_leaf()) return std::nullopt;
            node = step == 'L' ? node + 1 : bvh_.nodes[node].offset;
        }
        // Depth-first order: a subtree's primitives run from its leftmost
        // leaf's first to its rightmost leaf's last.
        uint32_t first = node, last = node;
        while (!bvh_.nodes[first].is_leaf())
            first = first + 1;
        while (!bvh_.nodes[last].is_leaf())
            last = bvh_.nodes[last].offset;
        const FlatBvhNode& a = bvh_.nodes[first];
        const FlatBvhNode& b = bvh_.nodes[last];
        BvhNodeView view;
        view.box = bvh_.nodes[node].box();
        view.leaf = bvh_.nodes[node].is_leaf();
        view.primitives.assign(bvh_.primitives.begin() + a.offset,
                               bvh_.primitives.begin() + b.offset + b.count);
        return view;
    }

  private:
    /// The one traversal loop. Closest hit (kAnyHit false): fills `best`
    /// and `best_slot` with the nearest hit (ties: larger primitive id) and
    /// returns whether there is one. Any hit: returns at the first hit.
    template <bool kAnyHit>
    bool traverse(const Ray& ray, Hit& best, uint32_t& best_slot) const {
        if (bvh_.nodes.empty()) return false;
        const FlatBvhNode* nodes = bvh_.nodes.data();
        const SlabRay slab(ray);
        const typename Tester::RayData query = tester_.prepare(ray);
        Ray r = ray;  // r.t_max shrinks to the closest hit so far
        double t_box = box_t_max(r.t_max);
        bool found = false;
        uint64_t visited = 1, tests = 0;

        // Each entry: a node whose box the ray enters at t, still to visit.
        struct Entry {
            uint32_t node;
            double t;
        };
        Entry stack[kMaxBvhDepth + 1];
        int size = 0;

        double t_enter;
        uint32_t node = 0;
        bool active = slab_test(nodes[0], slab, t_box, t_enter);
        while (active) {
            const FlatBvhNode& n = nodes[node];
            if (n.is_leaf()) {
                for (uint32_t slot = n.offset, end = n.offset + n.count; slot < end; ++slot) {
                    ++tests;
                    Hit hit;
                    if (!tester_.intersect(slot, r, query, hit)) continue;
                    if (kAnyHit) {
                        add_counts(visited, tests);
                        return true;
                    }
                    // hit.t <= r.t_max = best.t here; at equal t the larger id wins.
                    if (found && hit.t == best.t &&
                        bvh_.primitives[slot] < bvh_.primitives[best_slot])
                        continue;
                    best = hit;
                    best_slot = slot;
                    found = true;
                    r.t_max = hit.t;
                    t_box = box_t_max(r.t_max);
                }
            } else {
                // Test both children, go to the nearer, keep the farther.
                uint32_t near_child = node + 1, far_child = n.offset;
                double t_near_child, t_far_child;
                bool hit_near = slab_test(nodes[near_child], slab, t_box, t_near_child);
                bool hit_far = slab_test(nodes[far_child], slab, t_box, t_far_child);
                visited += 2;
                if (hit_near && hit_far) {
                    if (t_far_child < t_near_child) {
                        std::swap(near_child, far_child);
                        std::swap(t_near_child, t_far_child);
                    }
                    stack[size++] = {far_child, t_far_child};
                    node = near_child;
                    continue;
                }
                if (hit_near || hit_far) {
                    node = hit_near ? near_child : far_child;
                    continue;
                }
            }
            // Next: the nearest kept node that the closest hit has not passed.
            active = false;
            while (size > 0) {
                const Entry& e = stack[--size];
                if (e.t <= t_box) {
                    node = e.node;
                    active = true;
                    break;
                }
            }
        }
        add_counts(visited, tests);
        return found;
    }

    static void add_counts(uint64_t visited, uint64_t tests) {
        RayCounters& c = thread_counters();
        c.nodes_visited += visited;
        c.primitive_tests += tests;
    }

    FlatBvh bvh_;
    Tester tester_;  ///< holds a reference to bvh_.primitives: declared after bvh_
};

}  // namespace

std::unique_ptr<Accelerator> make_reference_bvh(const Scene& scene, const IntersectStage& stage,
                                                const AcceleratorSettings& settings) {
    FlatBvh bvh = build_flat_bvh(scene, settings);
    // The inlined routine only where it is the routine the stage asks for:
    // with student (or any other) triangle code, call through the table.
    if (stage.intersect_triangle == &reference::intersect_triangle)
        return std::make_unique<ReferenceBvh<InlineMollerTrumbore>>(scene, stage, std::move(bvh));
    return std::make_unique<ReferenceBvh<StageRoutines>>(scene, stage, std::move(bvh));
}

}  // namespace pt
