// KnnIndex: a query-side copy of a photon map's kd-tree inner nodes, in
// breadth-first order, that the reference renderer builds from the tree
// (the students' layout, stages/kdtree.h, stays the tree) so that its
// k-nearest queries miss the cache less (issue 19).
//
// Why: in the students' layout the node of [lo, hi) is points[mid], so a
// descent touches one 24-byte point per level, each in another cache line
// of a 24 MB array (10^6 points): about one miss per level below the
// cached top. Here each inner node (a range of more than 16 points; buckets
// stay in the tree) is a 32-byte record (its point and split axis) at its
// breadth-first number h (root 1, children 2h and 2h + 1), two siblings
// per 64-byte line: 65,535 nodes, 2 MB, for 10^6 points; the top 12 levels
// (128 kB) stay in L2, and one prefetch fetches both grandchildren pairs.
// The records are exact copies of the tree's doubles and the search is
// the same code (stages/kdtree_search.h), so answers equal
// reference::k_nearest's bit for bit, ties included.
//
// Tests: tests/unit/test_knn_index.cpp; cost in `bench kdtree`.
#pragma once

#include <cstdint>
#include <vector>

#include "stages/kdtree.h"

namespace pt {

/// One inner node of the tree: its point (a copy of points[mid]) and split axis.
struct alignas(32) KnnNode {
    Vec3 point;
    uint32_t axis = 0;
};

/// Two siblings, 2j and 2j + 1, in one cache line.
struct alignas(64) KnnNodePair {
    KnnNode node[2];
};

struct KnnIndex {
    std::vector<KnnNodePair> pairs;  ///< node h at pairs[h / 2].node[h % 2]; unused numbers are holes
    size_t tree_size = 0;            ///< points of the tree it was built from

    const KnnNode& node(uint32_t h) const { return pairs[h / 2].node[h % 2]; }
    size_t bytes() const { return pairs.capacity() * sizeof(KnnNodePair); }
};

/// The index of `tree` (any tree valid in the layout of stages/kdtree.h).
KnnIndex build_knn_index(const KdTree& tree);

namespace reference {
/// reference::k_nearest(tree, ...) through `index`, which must have been
/// built from `tree`: the same answers, faster. Throws std::logic_error
/// when the index holds another number of points.
void k_nearest(const KdTree& tree, const KnnIndex& index, const Vec3& p, int k, double max_dist2,
               std::vector<Neighbor>& out);
}  // namespace reference

}  // namespace pt
