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
// (128 kB) stay in L2, and the two lines of a node's four grandchildren are
// prefetched while it is examined.
// The records are exact copies of the tree's doubles and the search is
// the same code (stages/kdtree_search.h).
//
// A guessed first bound. Until k points are held, the search keeps every
// point it meets, and about 40 of its 90 insertions per query (k = 50,
// 10^6 points) are points that a tighter bound would have refused and that
// are evicted later. Neighbouring queries (a renderer's gathers, pixel
// after pixel) have nearly the same k-th distance, so the query starts
// with 1.21 times (a radius 1.1 times) the larger k-th squared distance of
// this thread's last two queries on the same index with the same k. If that finds k
// points, no two at the same distance, and no point was evicted at the
// distance of the k-th, the k points are the k nearest and the answer is
// the only one (no tie to break), which the search without a guess also
// returns; otherwise the query runs again without the guess. So answers
// equal reference::k_nearest's bit for bit, ties included, whatever the
// order of the queries; only the time depends on it.
//
// How the guessed query runs (issue 19, round 4): on a processor with AVX2
// it collects every point within the guess unsorted, then counts each
// one's rank (how many are nearer) with AVX2 on float copies of the
// distances and places the k of rank below k; a tie among them (or with the
// next) shows as a repeated rank and falls back. When more than 2k + 16
// (4k + 16 through the quantised groups below)
// points lie within the guess it runs the sorted insertion of
// stages/kdtree_search.h from the guess instead (as without AVX2). A
// query far from this thread's last one (more than 4 times its k-th
// distance away) lists the buckets within the guess first and prefetches
// them, so that their cache misses overlap.
//
// Quantised groups (issue 19, round 5): such a far query (since round 6
// every query, a coherent one too: 1.2 times as fast) neither descends
// below subtrees of at most 64 points (groups) nor reads them from the
// tree. Each group also has a copy here (KnnGroup, stages/knn_group.h: each coordinate as 8 bits
// within the group's box, one cache line per axis, 4 MB for 10^6 points
// against the tree's 24 MB), from which a conservative lower bound of each
// point's squared distance is computed in 16-bit integers (in whole steps); only the points it does
// not rule out (about 70, k = 50) are read from the tree, prefetched, and
// kept by their exact distance: the same points as the descent into the
// group and the scan of its buckets keeps, so the answers do not change.
// The descent stops two levels higher, so it reads only the top 0.5 MB of
// the inner nodes (cached). A query with fewer than k points within the
// guess collects once more from 1.5 times it before it falls back to the
// search without a guess.
//
// Tests: tests/unit/test_knn_index.cpp; cost in `bench kdtree`.
#pragma once

#include <cstdint>
#include <vector>

#include "stages/kdtree.h"
#include "stages/knn_group.h"

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
    std::vector<KnnGroup> groups;    ///< the group of number h at groups[h - first_group]; empty: none (see below)
    uint32_t first_group = 0;        ///< the smallest breadth-first number of a group
    size_t tree_size = 0;            ///< points of the tree it was built from

    const KnnNode& node(uint32_t h) const { return pairs[h / 2].node[h % 2]; }
    size_t bytes() const { return pairs.capacity() * sizeof(KnnNodePair) + groups.capacity() * sizeof(KnnGroup); }
};

/// How often this thread's indexed queries started from a guessed bound,
/// and how many of those were answered again from scratch (for `bench`
/// and the tests).
struct KnnGuessCounts {
    uint64_t guessed = 0;
    uint64_t fell_back = 0;
    uint64_t crowded = 0;  ///< of the guessed: too many points within the guess, searched with insertions from it
    uint64_t retried = 0;  ///< fewer than k points within the guess: collected again from 1.5 times it
};
KnnGuessCounts knn_guess_counts();

/// The index of `tree` (any tree valid in the layout of stages/kdtree.h).
KnnIndex build_knn_index(const KdTree& tree);

namespace reference {
/// reference::k_nearest(tree, ...) through `index`, which must have been
/// built from `tree`: the same answers, faster (from a guessed first bound,
/// see the file comment). Throws std::logic_error when the index holds
/// another number of points.
void k_nearest(const KdTree& tree, const KnnIndex& index, const Vec3& p, int k, double max_dist2,
               std::vector<Neighbor>& out);
}  // namespace reference

}  // namespace pt
