// Collapsing the binary BVH into 4-wide nodes, and traversing them
// (stages/bvh_wide.h).
#include "stages/bvh_wide.h"

#include <algorithm>
#include <cmath>

#include "core/counters.h"
#include "scene/scene.h"
#include "stages/bvh.h"
#include "stages/bvh_kernels.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace pt {
namespace {

using namespace bvh_kernels;

float box_area(const FlatBvhNode& n) {
    float x = n.bounds[3] - n.bounds[0], y = n.bounds[4] - n.bounds[1], z = n.bounds[5] - n.bounds[2];
    return x * y + y * z + z * x;
}

class Collapser {
  public:
    Collapser(const FlatBvh& bvh, std::vector<WideBvhNode>& out) : bvh_(bvh), out_(out) {}

    /// Makes the wide node for binary node `index` (its children, or itself
    /// when it is a leaf) and returns its position in `out`.
    uint32_t collapse(uint32_t index, int depth) {
        deepest = std::max(deepest, depth);
        const FlatBvhNode& n = bvh_.nodes[index];
        std::vector<uint32_t> lanes;
        if (n.is_leaf()) {
            lanes = {index};
        } else {
            lanes = {index + 1, n.offset};
        }
        while (lanes.size() < size_t(WideBvhNode::kWidth)) {
            int widest = -1;
            for (int i = 0; i < int(lanes.size()); ++i)
                if (!bvh_.nodes[lanes[i]].is_leaf() &&
                    (widest < 0 || box_area(bvh_.nodes[lanes[i]]) > box_area(bvh_.nodes[lanes[widest]])))
                    widest = i;
            if (widest < 0) break;
            uint32_t split = lanes[widest];
            lanes[widest] = split + 1;
            lanes.insert(lanes.begin() + widest + 1, bvh_.nodes[split].offset);
        }
        uint32_t self = uint32_t(out_.size());
        out_.emplace_back();
        for (int p = 0; p < 6; ++p)
            for (int i = 0; i < WideBvhNode::kWidth; ++i)
                out_[self].bounds[p][i] = p < 3 ? INFINITY : -INFINITY;
        for (int i = 0; i < int(lanes.size()); ++i) {
            const FlatBvhNode& c = bvh_.nodes[lanes[i]];
            for (int p = 0; p < 6; ++p)
                out_[self].bounds[p][i] = c.bounds[p];
            out_[self].valid |= uint8_t(1u << i);
            if (c.is_leaf()) {
                out_[self].child[i] = c.offset;
                out_[self].count[i] = uint8_t(c.count);
            } else {
                uint32_t child = collapse(lanes[i], depth + 1);  // may reallocate out_
                out_[self].child[i] = child;
            }
        }
        return self;
    }

    int deepest = 0;

  private:
    const FlatBvh& bvh_;
    std::vector<WideBvhNode>& out_;
};

/// The ray for 4-wide slab tests: SlabRay's values broadcast to all lanes.
struct WideRay {
    explicit WideRay(const SlabRay& s) : slab(s) {}
    const SlabRay& slab;

    /// Bit i set when the ray enters child i's box before t_max; the entry
    /// distances go to t_enter. Per lane exactly slab_test (bvh_kernels.h).
    unsigned test(const WideBvhNode& node, float t_max, float t_enter[4]) const {
#if defined(__SSE2__)
        __m128 t_near = _mm_set1_ps(slab.t_min), t_far = _mm_set1_ps(t_max);
        for (int a = 0; a < 3; ++a) {
            __m128 t0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[slab.near_plane[a]]),
                                              _mm_set1_ps(slab.o_near[a])),
                                   _mm_set1_ps(slab.inv_near[a]));
            __m128 t1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[slab.far_plane[a]]),
                                              _mm_set1_ps(slab.o_far[a])),
                                   _mm_set1_ps(slab.inv_far[a]));
            t_near = _mm_max_ps(t0, t_near);  // t0 > t_near ? t0 : t_near (NaN keeps t_near)
            t_far = _mm_min_ps(t1, t_far);    // t1 < t_far ? t1 : t_far
        }
        _mm_storeu_ps(t_enter, t_near);
        __m128 hit = _mm_cmple_ps(t_near, _mm_mul_ps(t_far, _mm_set1_ps(kFarScale)));
        return unsigned(_mm_movemask_ps(hit)) & node.valid;
#else
        unsigned mask = 0;
        for (int i = 0; i < WideBvhNode::kWidth; ++i) {
            float t_near = slab.t_min, t_far = t_max;
            for (int a = 0; a < 3; ++a) {
                float t0 = (node.bounds[slab.near_plane[a]][i] - slab.o_near[a]) * slab.inv_near[a];
                float t1 = (node.bounds[slab.far_plane[a]][i] - slab.o_far[a]) * slab.inv_far[a];
                t_near = t0 > t_near ? t0 : t_near;
                t_far = t1 < t_far ? t1 : t_far;
            }
            t_enter[i] = t_near;
            if (t_near <= t_far * kFarScale) mask |= 1u << i;
        }
        return mask & node.valid;
#endif
    }
};

/// A child to visit: a wide node, or a leaf's slots.
struct ChildRef {
    uint32_t index;  ///< node index, or first slot of a leaf
    uint32_t count;  ///< 0: a node; else the leaf's primitive count
};

template <class Tester>
class WideReferenceBvh final : public Accelerator {
  public:
    WideReferenceBvh(const Scene& scene, const IntersectStage& stage, FlatBvh bvh)
        : primitives_(std::move(bvh.primitives)), tester_(scene, stage, primitives_), split_(bvh.split) {
        if (!bvh.nodes.empty()) {
            const FlatBvhNode& root = bvh.nodes[0];
            for (int a = 0; a < 3; ++a)
                float_scene_ = float_scene_ && std::fabs(root.bounds[a]) <= 1e30f &&
                               std::fabs(root.bounds[3 + a]) <= 1e30f;
            nodes_ = collapse_to_wide(bvh, &depth_);
        }
    }

    std::optional<Hit> intersect(const Ray& ray) const override {
        Hit best;
        uint32_t best_slot = 0;
        if (!closest_hit(ray, best, best_slot)) return std::nullopt;
        tester_.finish(best_slot, ray, best);
        best.primitive = primitives_[best_slot];
        return best;
    }

    bool occluded(const Ray& ray) const override { return any_hit(ray); }

    AcceleratorInfo info() const override {
        uint64_t tree = nodes_.size() * sizeof(WideBvhNode) + primitives_.size() * sizeof(uint32_t);
        return {std::string("bvh4-") + to_string(split_), nodes_.size(), depth_, tree + tester_.bytes(), tree};
    }

  private:
    /// Closest hit: at each node the four boxes are tested at once; the
    /// children hit are visited nearest first, the others kept on a stack
    /// with their entry distances and skipped once the closest hit lies
    /// before them (as in the binary traversal, bvh_traverse.cpp).
    bool closest_hit(const Ray& ray, Hit& best, uint32_t& best_slot) const {
        if (nodes_.empty()) return false;
        const SlabRay slab(ray, float_scene_);
        const WideRay wide(slab);
        const typename Tester::RayData query = tester_.prepare(ray);
        Ray r = ray;
        float t_box = box_t_max(r.t_max), t_cull = t_box * kFarScale;
        bool found = false;
        uint64_t visited = 0, tests = 0;

        struct Entry {
            ChildRef ref;
            float t;
        };
        Entry stack[3 * kMaxBvhDepth + 4];  // at most three kept per level
        int size = 0;
        ChildRef current{0, 0};
        Hit hit;
        for (;;) {
            if (current.count == 0) {
                const WideBvhNode& node = nodes_[current.index];
                alignas(16) float t_enter[4];
                unsigned mask = wide.test(node, t_box, t_enter);
                visited += WideBvhNode::kWidth;
                if (mask != 0) {
                    // The children hit, nearest first (insertion sort of <= 4).
                    Entry hits[4];
                    int n = 0;
                    for (; mask != 0; mask &= mask - 1) {
                        int i = __builtin_ctz(mask);
                        Entry e{{node.child[i], node.count[i]}, t_enter[i]};
                        int j = n++;
                        for (; j > 0 && hits[j - 1].t > e.t; --j)
                            hits[j] = hits[j - 1];
                        hits[j] = e;
                    }
                    for (int j = n - 1; j > 0; --j)
                        stack[size++] = hits[j];
                    current = hits[0].ref;
                    continue;
                }
            } else {
                for (uint32_t slot = current.index, end = current.index + current.count; slot < end; ++slot) {
                    ++tests;
                    if (!tester_.intersect(slot, r, query, hit)) continue;
                    // hit.t <= r.t_max = best.t here; at equal t the larger id wins.
                    if (found && hit.t == best.t && primitives_[slot] < primitives_[best_slot]) continue;
                    best = hit;
                    best_slot = slot;
                    found = true;
                    r.t_max = hit.t;
                    t_box = box_t_max(r.t_max);
                    t_cull = t_box * kFarScale;
                }
            }
            bool next = false;
            while (size > 0) {
                const Entry& e = stack[--size];
                if (e.t <= t_cull) {
                    current = e.ref;
                    next = true;
                    break;
                }
            }
            if (!next) break;
        }
        add_counts(visited, tests);
        return found;
    }

    /// Any hit: the children hit are all kept, in lane order; stops at the
    /// first primitive hit.
    bool any_hit(const Ray& ray) const {
        if (nodes_.empty()) return false;
        const SlabRay slab(ray, float_scene_);
        const WideRay wide(slab);
        const typename Tester::RayData query = tester_.prepare(ray);
        const float t_box = box_t_max(ray.t_max);
        uint64_t visited = 0, tests = 0;
        ChildRef stack[3 * kMaxBvhDepth + 4];
        int size = 0;
        ChildRef current{0, 0};
        Hit hit;
        for (;;) {
            if (current.count == 0) {
                const WideBvhNode& node = nodes_[current.index];
                alignas(16) float t_enter[4];
                unsigned mask = wide.test(node, t_box, t_enter);
                visited += WideBvhNode::kWidth;
                if (mask != 0) {
                    int first = __builtin_ctz(mask);
                    for (mask &= mask - 1; mask != 0; mask &= mask - 1) {
                        int i = __builtin_ctz(mask);
                        stack[size++] = {node.child[i], node.count[i]};
                    }
                    current = {node.child[first], node.count[first]};
                    continue;
                }
            } else {
                for (uint32_t slot = current.index, end = current.index + current.count; slot < end; ++slot) {
                    ++tests;
                    if (tester_.intersect(slot, ray, query, hit)) {
                        add_counts(visited, tests);
                        return true;
                    }
                }
            }
            if (size == 0) break;
            current = stack[--size];
        }
        add_counts(visited, tests);
        return false;
    }

    static void add_counts(uint64_t visited, uint64_t tests) {
        RayCounters& c = thread_counters();
        c.nodes_visited += visited;
        c.primitive_tests += tests;
    }

    std::vector<uint32_t> primitives_;  ///< slot -> primitive id (FlatBvh::primitives)
    Tester tester_;                     ///< holds a reference to primitives_: declared after it
    std::vector<WideBvhNode> nodes_;
    BvhSplit split_;
    int depth_ = 0;
    bool float_scene_ = true;  ///< all coordinates within 1e30 (SlabRay)
};

}  // namespace

std::vector<WideBvhNode> collapse_to_wide(const FlatBvh& bvh, int* depth) {
    std::vector<WideBvhNode> out;
    if (bvh.nodes.empty()) return out;
    out.reserve(bvh.nodes.size() / 2 + 1);
    Collapser c(bvh, out);
    c.collapse(0, 0);
    if (depth) *depth = c.deepest;
    return out;
}

std::unique_ptr<Accelerator> make_wide_bvh(const Scene& scene, const IntersectStage& stage, FlatBvh bvh) {
    if (stage.intersect_triangle == &reference::intersect_triangle)
        return std::make_unique<WideReferenceBvh<InlineMollerTrumbore>>(scene, stage, std::move(bvh));
    if (stage.intersect_triangle == &reference::intersect_triangle_watertight)
        return std::make_unique<WideReferenceBvh<InlineWatertight>>(scene, stage, std::move(bvh));
    return std::make_unique<WideReferenceBvh<StageRoutines>>(scene, stage, std::move(bvh));
}

}  // namespace pt
