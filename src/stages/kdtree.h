// KdTree: a balanced kd-tree over points, for the photon maps (Part 8).
//
// A photon map answers one question millions of times: which stored points
// lie nearest to x? A brute-force scan costs O(n) per query; a kd-tree
// (Bentley 1975) answers in about O(log n + k) by cutting space in half at
// each level and skipping every half that lies farther away than the k-th
// best point found so far. Jensen ("Realistic Image Synthesis Using Photon
// Mapping", 2001, chapter 6) stores it without pointers, as here.
//
// Layout (the contract that a student's build must meet, so that every
// query works on either side's tree): `points` holds the n points in tree
// order. The node of an index range [lo, hi) is its middle element
//     mid = lo + (hi - lo) / 2,
// with split dimension axis[mid] (0 = x, 1 = y, 2 = z); its left subtree
// is the range [lo, mid), its right one [mid + 1, hi), and
//     points[i][axis[mid]] <= points[mid][axis[mid]]  for i in [lo, mid)
//     points[i][axis[mid]] >= points[mid][axis[mid]]  for i in (mid, hi).
// The root is the range [0, n). ids[i] is the index, in the input, of
// points[i]. Building is O(n log n): a median selection (nth_element) per
// level; the split dimension is the widest extent of the range's points.
//
// Queries (reference only; they read the layout above, so they work on a
// student's tree too):
//   k_nearest      the k closest points within a maximum distance, sorted
//                  nearest first (the best k found so far kept sorted; a
//                  subtree is skipped when its cell lies farther than the
//                  current k-th distance; the first k come from the
//                  nearest cells, best-first, so that bound starts tight)
//   within_radius  every point within a fixed distance (SPPM's query)
// The search itself is stages/kdtree_search.h; the renderer runs it
// through a query-side copy of the inner nodes (stages/knn_index.h), with
// the same answers.
// Distances are squared Euclidean; a point at exactly the maximum distance
// is found. Ties at equal distance may be broken either way.
//
// Tests: tests/unit/test_kdtree.cpp (every query against brute force on
// random points, duplicates, points on a plane, one point, none, k in the
// thousands; the layout's invariant); cost in `bench kdtree`.
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace pt {

struct KdTree {
    std::vector<Vec3> points;     ///< the points in tree order (see the file comment), scene units
    std::vector<uint32_t> ids;    ///< ids[i]: index in the input of points[i]
    std::vector<uint8_t> axis;    ///< axis[mid]: split dimension of the node at mid (0, 1, 2)

    size_t size() const { return points.size(); }
    bool empty() const { return points.empty(); }
    /// Bytes held by the tree (its three arrays).
    size_t bytes() const { return points.capacity() * sizeof(Vec3) + ids.capacity() * 4 + axis.capacity(); }
};

/// A point found by a query.
struct Neighbor {
    uint32_t id = 0;     ///< index in the input of the point
    double dist2 = 0;    ///< squared distance to the query point, scene units^2
};

/// The layout's invariant (see the file comment) holds for every node,
/// and ids is a permutation of 0..n-1; for tests and the grader.
bool kdtree_is_valid(const KdTree& tree);

namespace reference {
/// The balanced tree over `points` (any number, duplicates allowed).
KdTree build_kdtree(const std::vector<Vec3>& points);
/// The (at most) k points nearest to p with dist2 <= max_dist2, nearest first,
/// written to `out` (cleared first). k <= 0 or an empty tree: none.
void k_nearest(const KdTree& tree, const Vec3& p, int k, double max_dist2, std::vector<Neighbor>& out);
}  // namespace reference

/// Every point with dist2 <= radius2 of p, in tree order, written to `out`
/// (cleared first). A negative radius2 finds none; 0 finds points equal to p.
void within_radius(const KdTree& tree, const Vec3& p, double radius2, std::vector<Neighbor>& out);

}  // namespace pt
