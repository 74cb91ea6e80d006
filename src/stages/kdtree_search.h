// The reference k-nearest search (stages/kdtree.h), written once for two
// ways of reading a tree's inner nodes: from the students' layout itself
// (stages/kdtree.cpp) and from the query-side copy of stages/knn_index.h.
// Private to those two files. Both read the same doubles and do the same
// arithmetic in the same order, so they return the same answers bit for
// bit, ties included (tests/unit/test_knn_index.cpp checks it).
#pragma once

#include <cstdint>
#include <algorithm>
#include <utility>
#include <vector>

#include "stages/kdtree.h"

namespace pt::kdtree_detail {

/// Subtrees of at most this many points are scanned, not descended (a
/// bucket): 16 to 32 measured alike (docs/photon_mapping.md).
constexpr uint32_t kScanBelow = 16;

/// A subtree still to visit, with what the pruning test needs: the
/// squared distance from p to the subtree's cell, the offsets that sum to
/// it (Arya and Mount's incremental distance, 1993: crossing a plane
/// replaces one axis's term, so a far cell is skipped when its whole box,
/// not only its nearest plane, lies beyond the k-th distance) and the node
/// point on the plane between the cell and its sibling.
struct PendingCell {
    uint32_t lo, hi;     ///< the subtree's range [lo, hi)
    uint32_t node;       ///< the parent's node point (its position in tree order), on this cell's boundary
    uint32_t heap;       ///< the cell's breadth-first number (root 1, children 2h and 2h + 1)
    double dist2;        ///< squared distance from p to the cell
    double offset[3];    ///< p's distance to the cell along each axis (0 inside)
};

/// The cell being descended, held in the query's locals (registers): its
/// range, breadth-first number and squared distance from p. Its per-axis
/// offsets are a separate array: indexed by a variable axis, they would
/// keep the whole struct in memory (measured 3 to 5% slower).
struct Cell {
    uint32_t lo, hi, heap;
    double dist2;
    static Cell root(const KdTree& tree) { return {0, uint32_t(tree.size()), 1, 0}; }
    /// A pending cell resumed: its range and distance, and its offsets into `offset`.
    static Cell resume(const PendingCell& c, double offset[3]) {
        offset[0] = c.offset[0];
        offset[1] = c.offset[1];
        offset[2] = c.offset[2];
        return {c.lo, c.hi, c.heap, c.dist2};
    }
};

/// Descends from `cell` to the bucket that holds p (at most kStop points;
/// a bucket unless a caller stops higher), pushing the far child of every
/// node it passes onto the stack. `Nodes` as in knn_search below.
template <uint32_t kStop = kScanBelow, class Nodes>
[[gnu::always_inline]] inline void descend_to_bucket(const Nodes& nodes, const Vec3& p, Cell& cell, double offset[3],
                                                     PendingCell* stack, int& top) {
    while (cell.hi - cell.lo > kStop) {
        const uint32_t mid = cell.lo + (cell.hi - cell.lo) / 2;
        nodes.prefetch(cell.lo, mid, cell.hi, cell.heap);
        const int axis = nodes.axis(mid, cell.heap);
        const double delta = p[axis] - nodes.point(mid, cell.heap)[axis];
        PendingCell& far = stack[top++];
        far.node = mid;
        far.dist2 = cell.dist2 - offset[axis] * offset[axis] + delta * delta;
        far.offset[0] = offset[0];
        far.offset[1] = offset[1];
        far.offset[2] = offset[2];
        far.offset[axis] = delta;
        if (delta <= 0) {
            far.lo = mid + 1;
            far.hi = cell.hi;
            far.heap = 2 * cell.heap + 1;
            cell.hi = mid;
            cell.heap = 2 * cell.heap;
        } else {
            far.lo = cell.lo;
            far.hi = mid;
            far.heap = 2 * cell.heap;
            cell.lo = mid + 1;
            cell.heap = 2 * cell.heap + 1;
        }
    }
}

/// Backs up to the nearest pending cell on the stack that can still hold a
/// point within `bound`; null when none is left. A cell's node point lies on
/// its boundary, so it is no nearer than the cell: both are skipped together.
inline const PendingCell* pop_within(const PendingCell* stack, int& top, double bound) {
    while (top > 0) {
        const PendingCell& pending = stack[--top];
        if (pending.dist2 <= bound) return &pending;
    }
    return nullptr;
}

/// One k-nearest query (reference): the (at most) k points within `bound`
/// nearest to p, nearest first: their squared distances written to
/// dist2[0, count) and their positions in tree order (not yet ids: ids are
/// looked up once, for the answers) to at[0, count); returns count.
/// dist2[-1] must be readable: it is set to -1, a sentinel below every
/// distance, so that the insertion loop needs no test for the front.
///
/// `Nodes` reads the inner node of range [lo, hi) (more than kScanBelow
/// points, middle `mid`, breadth-first number `heap`):
///   nodes.axis(mid, heap), nodes.point(mid, heap)   its split axis and point
///   nodes.prefetch(lo, mid, hi, heap)               hint: its children come next
/// Buckets are always read from tree.points.
///
/// Why it is shaped this way, measured by `bench kdtree` and perf
/// (docs/photon_mapping.md): with k = 50 a query looks at about 300
/// points, and the time went to branch mispredictions in the candidate
/// bookkeeping and to cache misses on the descent, not to the distances.
/// Hence: the best k kept as a sorted array (insertion from the back, so
/// the answer needs no final sort; a heap plus a sort cost more at this
/// k), distances and positions in two arrays (a shift moves one double
/// and one index, not a padded pair), the first k taken best-first (see
/// below), a bucket's distances computed first and filtered without branches,
/// an explicit stack instead of recursion, and the children prefetched
/// while the parent is examined. The state lives in locals, not in
/// members, so that the compiler keeps the bound in a register.
///
/// With kDetectTies, *ties is set when the answer may hang on a tie at the
/// k-th distance: a point evicted from the full best while one at its
/// distance stays (see stages/knn_index.cpp, which needs it).
template <class Nodes, bool kDetectTies = false>
inline size_t knn_search(const KdTree& tree, const Nodes& nodes, const Vec3& p, size_t k, double bound,
                         double* best_dist2, uint32_t* best_at, bool* ties = nullptr) {
    const Vec3* points = tree.points.data();
    size_t count = 0;  // how many of the best are filled
    [[maybe_unused]] bool tie = false;
    best_dist2[-1] = -1;

    // Keeps a point within the bound: inserted into the sorted best from
    // the back (the farthest drops out once k are held); the bound then
    // becomes the k-th distance.
    auto consider = [&](double dist2, uint32_t at) {
        if (!(dist2 <= bound)) return;  // written so that a NaN distance is never kept
        const bool full = count == k;
        size_t i = count < k ? count++ : k - 1;
        for (; best_dist2[i - 1] > dist2; --i) {
            best_dist2[i] = best_dist2[i - 1];
            best_at[i] = best_at[i - 1];
        }
        best_dist2[i] = dist2;
        best_at[i] = at;
        if (count == k) {
            // The evicted point was at the old bound: a tie if the new k-th is there too.
            if constexpr (kDetectTies) tie = tie || (full && best_dist2[k - 1] == bound);
            bound = best_dist2[k - 1];
        }
    };
    // Every point of the bucket [lo, hi), at most kScanBelow of them.
    auto scan_bucket = [&](uint32_t lo, uint32_t hi) {
        double dist2[kScanBelow];
        uint32_t inside[kScanBelow];
        const uint32_t n = hi - lo;
        for (uint32_t j = 0; j < n; ++j) dist2[j] = (points[lo + j] - p).norm2();
        // Most points of a bucket lie beyond the bound: keep the others by
        // arithmetic, not by a branch that the processor mispredicts.
        uint32_t m = 0;
        for (uint32_t j = 0; j < n; ++j) {
            inside[m] = j;
            m += dist2[j] <= bound;
        }
        for (uint32_t s = 0; s < m; ++s) consider(dist2[inside[s]], lo + inside[s]);
    };

    // A descent pushes at most one cell per level, and a 32-bit size has
    // at most 32 levels. Depth-first, the stack holds one path; a
    // best-first choice leaves older cells below a new descent, so it is
    // made only while a whole descent still fits.
    constexpr int kMaxDescent = 32, kStackSize = 128;
    PendingCell stack[kStackSize];
    int top = 0;
    Cell cell = Cell::root(tree);
    double offset[3] = {0, 0, 0};
    for (;;) {
        descend_to_bucket(nodes, p, cell, offset, stack, top);
        scan_bucket(cell.lo, cell.hi);
        // Until k points are held the bound is infinite and every point
        // found is kept, so the first k decide how tight the bound starts:
        // take them from the nearest pending cell (best-first), not from
        // the last one pushed. Afterwards the stack's order (depth-first,
        // nearer side first) is as good and costs nothing.
        if (count < k && top > 1 && top + kMaxDescent <= kStackSize) {
            int nearest = top - 1;
            for (int i = top - 2; i >= 0; --i)
                if (stack[i].dist2 < stack[nearest].dist2) nearest = i;
            std::swap(stack[nearest], stack[top - 1]);
        }
        // Back up to the nearest pending cell that can still hold a better point.
        const PendingCell* next = pop_within(stack, top, bound);
        if (!next) {
            if constexpr (kDetectTies) *ties = tie;
            return count;
        }
        // The parent of cell h is h / 2 (breadth-first numbering).
        consider((nodes.point(next->node, next->heap / 2) - p).norm2(), next->node);
        cell = Cell::resume(*next, offset);
    }
}

/// knn_search's output arrays for `kept` neighbours, reused across queries
/// on this thread (no allocation per query). `best` has one more distance
/// in front of it, for knn_search's sentinel.
struct KnnScratch {
    double* best;
    uint32_t* at;
};
inline KnnScratch knn_scratch(size_t kept) {
    thread_local std::vector<double> dist2;
    thread_local std::vector<uint32_t> at;
    if (at.size() < kept) {
        dist2.resize(kept + 1);
        at.resize(kept);
    }
    return {dist2.data() + 1, at.data()};
}

/// reference::k_nearest's contract (stages/kdtree.h) over knn_search.
template <class Nodes>
inline void k_nearest(const KdTree& tree, const Nodes& nodes, const Vec3& p, int k, double max_dist2,
                      std::vector<Neighbor>& out) {
    out.clear();
    if (k <= 0 || tree.empty() || max_dist2 < 0) return;
    const size_t kept = std::min(size_t(k), tree.size());
    const KnnScratch s = knn_scratch(kept);
    const size_t found = knn_search(tree, nodes, p, kept, max_dist2, s.best, s.at);
    out.resize(found);
    for (size_t i = 0; i < found; ++i) out[i] = {tree.ids[s.at[i]], s.best[i]};
}

}  // namespace pt::kdtree_detail
