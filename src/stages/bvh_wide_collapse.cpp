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
    Collapser(const FlatBvh& bvh, std::vector<WideBvhNode<W>>& out) : bvh_(bvh), out_(out) {}

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
        // Open the interior lane of largest surface area until W lanes are used.
        while (lanes.size() < size_t(W)) {
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
            for (int i = 0; i < W; ++i)
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
    std::vector<WideBvhNode<W>>& out_;
};

}  // namespace

template <int W>
std::vector<WideBvhNode<W>> collapse_to_wide(const FlatBvh& bvh, int* depth) {
    std::vector<WideBvhNode<W>> out;
    if (bvh.nodes.empty()) return out;
    out.reserve(bvh.nodes.size() / (W - 1) + 1);
    Collapser<W> c(bvh, out);
    c.collapse(0, 0);
    if (depth) *depth = c.deepest;
    return out;
}

template std::vector<WideBvhNode<4>> collapse_to_wide<4>(const FlatBvh&, int*);
template std::vector<WideBvhNode<8>> collapse_to_wide<8>(const FlatBvh&, int*);

}  // namespace pt
