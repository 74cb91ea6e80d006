// Traversing the reference BVH (stages/flat_bvh.h): closest hit and any hit
// with an explicit stack, children nearest first, and a robust slab test
// (stages/bvh_kernels.h, shared with the 4-wide BVH of stages/bvh_wide.cpp).
#include <algorithm>
#include <cfloat>
#include <cmath>

#include "core/counters.h"
#include "core/math.h"
#include "scene/scene.h"
#include "stages/bvh.h"
#include "stages/bvh_kernels.h"
#include "stages/bvh_wide.h"
#include "stages/flat_bvh.h"
#include "stages/stages.h"

namespace pt {
namespace {

using namespace bvh_kernels;

// ---------------------------------------------------------------------------
// The accelerator

template <class Tester>
class ReferenceBvh final : public Accelerator, public InspectableBvh {
  public:
    ReferenceBvh(const Scene& scene, const IntersectStage& stage, FlatBvh bvh)
        : bvh_(std::move(bvh)), tester_(scene, stage, bvh_.primitives) {
        bvh_.nodes.shrink_to_fit();  // build_flat_bvh reserved the most nodes possible
        // Coordinates beyond 1e30 could put hits beyond float range (SlabRay).
        if (!bvh_.nodes.empty()) {
            const FlatBvhNode& root = bvh_.nodes[0];
            for (int a = 0; a < 3; ++a)
                float_scene_ = float_scene_ && std::fabs(root.bounds[a]) <= 1e30f &&
                               std::fabs(root.bounds[3 + a]) <= 1e30f;
        }
    }

    std::optional<Hit> intersect(const Ray& ray) const override {
        Hit best;
        uint32_t best_slot = 0;
        if (!closest_hit(ray, best, best_slot)) return std::nullopt;
        tester_.finish(best_slot, ray, best);
        best.primitive = bvh_.primitives[best_slot];
        return best;
    }

    bool occluded(const Ray& ray) const override { return any_hit(ray); }

    AcceleratorInfo info() const override {
        return {std::string("bvh-") + to_string(bvh_.split), bvh_.nodes.size(), bvh_.depth,
                bvh_.bytes() + tester_.bytes(), bvh_.bytes()};
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
    /// Closest hit: fills `best` and `best_slot` with the nearest hit (ties:
    /// the larger primitive id) and returns whether there is one. At each
    /// interior node both children's boxes are tested; the traversal goes on
    /// into the one the ray enters first and keeps the other, with its entry
    /// distance, on a stack. A kept node is skipped when the closest hit so
    /// far lies before its entry.
    bool closest_hit(const Ray& ray, Hit& best, uint32_t& best_slot) const {
        if (bvh_.nodes.empty()) return false;
        const FlatBvhNode* nodes = bvh_.nodes.data();
        const SlabRay slab(ray, float_scene_);
        const typename Tester::RayData query = tester_.prepare(ray);
        Ray r = ray;  // r.t_max shrinks to the closest hit so far
        // Box tests stop at t_box; kept nodes entering after t_cull are
        // skipped. Both are rounded up and t_cull is scaled like the far
        // distances, so that a primitive hit exactly at the closest t (a
        // tie) is never culled by rounding.
        float t_box = box_t_max(r.t_max), t_cull = t_box * kFarScale;
        bool found = false;
        uint64_t visited = 1, tests = 0;

        struct Entry {
            uint32_t node;  ///< a node still to visit
            float t;        ///< where the ray enters its box
        };
        Entry stack[kMaxBvhDepth + 1];  // at most one entry per level (flat_bvh.h)
        int size = 0;

        float t_enter;
        uint32_t node = 0;
        bool active = slab_test(nodes[0], slab, t_box, t_enter);
        Hit hit;
        while (active) {
            const FlatBvhNode& n = nodes[node];
            if (!n.is_leaf()) {
                uint32_t near_child = node + 1, far_child = n.offset;
                float t_near_child, t_far_child;
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
            } else {
                for (uint32_t slot = n.offset, end = n.offset + n.count; slot < end; ++slot) {
                    ++tests;
                    if (!tester_.intersect(slot, r, query, hit)) continue;
                    // hit.t <= r.t_max = best.t here; at equal t the larger id wins.
                    if (found && hit.t == best.t &&
                        bvh_.primitives[slot] < bvh_.primitives[best_slot])
                        continue;
                    best = hit;
                    best_slot = slot;
                    found = true;
                    r.t_max = hit.t;
                    t_box = box_t_max(r.t_max);
                    t_cull = t_box * kFarScale;
                }
            }
            // Next: the most recently kept node that the closest hit has not passed.
            active = false;
            while (size > 0) {
                const Entry& e = stack[--size];
                if (e.t <= t_cull) {
                    node = e.node;
                    active = true;
                    break;
                }
            }
        }
        add_counts(visited, tests);
        return found;
    }

    /// Any hit (shadow rays): order matters little, so each node's own box
    /// is tested when it is reached, and the child on the ray's side of the
    /// split axis goes first (pbrt-v3 section 4.4.2); stops at the first hit.
    bool any_hit(const Ray& ray) const {
        if (bvh_.nodes.empty()) return false;
        const FlatBvhNode* nodes = bvh_.nodes.data();
        const SlabRay slab(ray, float_scene_);
        const typename Tester::RayData query = tester_.prepare(ray);
        const float t_box = box_t_max(ray.t_max);
        uint64_t visited = 0, tests = 0;
        uint32_t stack[kMaxBvhDepth + 1];
        int size = 0;
        uint32_t node = 0;
        Hit hit;
        for (;;) {
            const FlatBvhNode& n = nodes[node];
            ++visited;
            float t_enter;
            if (slab_test(n, slab, t_box, t_enter)) {
                if (!n.is_leaf()) {
                    bool second_first = slab.negative[n.axis];
                    stack[size++] = second_first ? node + 1 : n.offset;
                    node = second_first ? n.offset : node + 1;
                    continue;
                }
                for (uint32_t slot = n.offset, end = n.offset + n.count; slot < end; ++slot) {
                    ++tests;
                    if (tester_.intersect(slot, ray, query, hit)) {
                        add_counts(visited, tests);
                        return true;
                    }
                }
            }
            if (size == 0) break;
            node = stack[--size];
        }
        add_counts(visited, tests);
        return false;
    }

    static void add_counts(uint64_t visited, uint64_t tests) {
        RayCounters& c = thread_counters();
        c.nodes_visited += visited;
        c.primitive_tests += tests;
    }

    FlatBvh bvh_;
    Tester tester_;            ///< holds a reference to bvh_.primitives: declared after bvh_
    bool float_scene_ = true;  ///< all coordinates within 1e30 (SlabRay)
};

}  // namespace

std::unique_ptr<Accelerator> make_reference_bvh(const Scene& scene, const IntersectStage& stage,
                                                const AcceleratorSettings& settings) {
    FlatBvh bvh = build_flat_bvh(scene, settings);
    if (settings.width == 4 || settings.width == 8)
        return make_wide_bvh(scene, stage, std::move(bvh), settings.width, settings.simd);
    // The inlined routine only where it is the routine the stage asks for:
    // with student (or any other) triangle code, call through the table.
    if (stage.intersect_triangle == &reference::intersect_triangle)
        return std::make_unique<ReferenceBvh<InlineMollerTrumbore>>(scene, stage, std::move(bvh));
    if (stage.intersect_triangle == &reference::intersect_triangle_watertight)
        return std::make_unique<ReferenceBvh<InlineWatertight>>(scene, stage, std::move(bvh));
    return std::make_unique<ReferenceBvh<StageRoutines>>(scene, stage, std::move(bvh));
}

}  // namespace pt
