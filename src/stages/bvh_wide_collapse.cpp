// Collapsing the binary BVH into 4- or 8-wide nodes (stages/bvh_wide.h).
#include <algorithm>
#include <cmath>

#include "stages/bvh_wide.h"

namespace pt {
namespace {

float box_area(const FlatBvhNode& n) {
    float x = n.bounds[3] - n.bounds[0], y = n.bounds[4] - n.bounds[1], z = n.bounds[5] - n.bounds[2];
    return x * y + y * z + z * x;
}

template <int W>
class Collapser {
  public:
    Collapser(const FlatBvh& bvh, std::vector<WideBvhNode<W>>& out, const WidePlan* plan)
        : bvh_(bvh), out_(out), plan_(plan) {}

    /// Makes the wide node for binary node `index` (its children, or itself
    /// when it is a leaf) and returns its position in `out`.
    uint32_t collapse(uint32_t index, int depth) {
        deepest = std::max(deepest, depth);
        const FlatBvhNode& n = bvh_.nodes[index];
        // The lanes' binary nodes, in a fixed array (a vector here was one
        // heap allocation per wide node) with their areas, computed once.
        uint32_t lanes[W];
        float areas[W];
        bool interior[W];
        int used = 0;
        auto add = [&](int at, uint32_t node) {
            for (int i = used; i > at; --i) {
                lanes[i] = lanes[i - 1];
                areas[i] = areas[i - 1];
                interior[i] = interior[i - 1];
            }
            lanes[at] = node;
            areas[at] = box_area(bvh_.nodes[node]);
            interior[at] = !bvh_.nodes[node].is_leaf();
            ++used;
        };
        if (n.is_leaf()) {
            add(0, index);
        } else if (plan_ && plan_->first[index] != WidePlan::kNoPlan) {
            for (uint32_t k = 0; k < plan_->count[index]; ++k) add(used, plan_->lanes[plan_->first[index] + k]);
        } else {
            add(0, index + 1);
            add(1, n.offset);
        }
        // Open the interior lane of largest surface area until W lanes are used.
        while (!plan_ && used < W) {
            int widest = -1;
            for (int i = 0; i < used; ++i)
                if (interior[i] && (widest < 0 || areas[i] > areas[widest])) widest = i;
            if (widest < 0) break;
            uint32_t split = lanes[widest];
            lanes[widest] = split + 1;
            areas[widest] = box_area(bvh_.nodes[split + 1]);
            interior[widest] = !bvh_.nodes[split + 1].is_leaf();
            add(widest + 1, bvh_.nodes[split].offset);
        }
        uint32_t self = uint32_t(out_.size());
        out_.emplace_back();
        for (int p = 0; p < 6; ++p)
            for (int i = 0; i < W; ++i)
                out_[self].bounds[p][i] = p < 3 ? INFINITY : -INFINITY;
        for (int i = 0; i < used; ++i) {
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
    std::vector<WideBvhNode<W>>& out_;
    const WidePlan* plan_;
};

}  // namespace

template <int W>
std::vector<WideBvhNode<W>> collapse_to_wide(const FlatBvh& bvh, int* depth, const WidePlan* plan) {
    std::vector<WideBvhNode<W>> out;
    if (bvh.nodes.empty()) return out;
    // Measured: about one wide node per 5.8 binary nodes (8-wide) or 3
    // (4-wide) on meshes and the knot; reserving a little more than that
    // saves the copies of a growing vector.
    out.reserve(bvh.nodes.size() / (W == 8 ? 5 : 2) + 1);
    Collapser<W> c(bvh, out, plan);
    c.collapse(0, 0);
    if (depth) *depth = c.deepest;
    return out;
}

template std::vector<WideBvhNode<4>> collapse_to_wide<4>(const FlatBvh&, int*, const WidePlan*);
template std::vector<WideBvhNode<8>> collapse_to_wide<8>(const FlatBvh&, int*, const WidePlan*);

}  // namespace pt
