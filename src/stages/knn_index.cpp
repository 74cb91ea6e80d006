// The query-side copy of a kd-tree's inner nodes (stages/knn_index.h).
#include "stages/knn_index.h"

#include <stdexcept>

#include "stages/kdtree_search.h"

namespace pt {
namespace {

using kdtree_detail::kScanBelow;

/// The deepest inner node's depth below [lo, hi) (-1: a bucket).
int inner_depth(size_t lo, size_t hi) {
    if (hi - lo <= kScanBelow) return -1;
    const size_t mid = lo + (hi - lo) / 2;
    // The right range is never larger than the left one.
    return 1 + inner_depth(lo, mid);
}

void copy_nodes(const KdTree& tree, KnnIndex& index, size_t lo, size_t hi, uint32_t h) {
    if (hi - lo <= kScanBelow) return;
    const size_t mid = lo + (hi - lo) / 2;
    KnnNode& node = index.pairs[h / 2].node[h % 2];
    node.point = tree.points[mid];
    node.axis = tree.axis[mid];
    copy_nodes(tree, index, lo, mid, 2 * h);
    copy_nodes(tree, index, mid + 1, hi, 2 * h + 1);
}

/// The search reads inner nodes from the index: node h, and while it is
/// examined the line of its four grandchildren's pairs (its children's
/// pair was fetched by its parent).
struct IndexNodes {
    const KnnNodePair* pairs;
    uint32_t count;  // pairs held
    int axis(uint32_t, uint32_t h) const { return int(pairs[h / 2].node[h % 2].axis); }
    const Vec3& point(uint32_t, uint32_t h) const { return pairs[h / 2].node[h % 2].point; }
    void prefetch(uint32_t, uint32_t, uint32_t, uint32_t h) const {
        if (2 * h + 1 < count) {
            __builtin_prefetch(&pairs[2 * h]);
            __builtin_prefetch(&pairs[2 * h + 1]);
        }
    }
};

}  // namespace

KnnIndex build_knn_index(const KdTree& tree) {
    KnnIndex index;
    index.tree_size = tree.size();
    const int depth = inner_depth(0, tree.size());
    if (depth < 0) return index;
    // Numbers 1 .. 2^(depth + 1) - 1: pairs 0 .. 2^depth - 1.
    index.pairs.resize(size_t(1) << depth);
    copy_nodes(tree, index, 0, tree.size(), 1);
    return index;
}

namespace reference {

void k_nearest(const KdTree& tree, const KnnIndex& index, const Vec3& p, int k, double max_dist2,
               std::vector<Neighbor>& out) {
    if (index.tree_size != tree.size())
        throw std::logic_error("k_nearest: the index was built from another tree");
    kdtree_detail::k_nearest(tree, IndexNodes{index.pairs.data(), uint32_t(index.pairs.size())}, p, k, max_dist2, out);
}

}  // namespace reference
}  // namespace pt
